#pragma once
// Time steps chosen for the user (`dt: auto`, docs/dynamics.md "Stability of the explicit
// scheme").
//
// The explicit scheme is a symplectic Euler step of the semi-discrete rod; per linear mode of
// frequency omega with Kelvin-Voigt relaxation time tau (V = tau K) and drag rate c, it is
// stable iff  omega^2 dt^2 + 2 dt (tau omega^2 + c) < 4  (Jury criterion of the 2x2 step
// matrix). The highest frequency of the scheme linearised about the reference configuration
// comes from a von Neumann analysis of its node equations: for perturbations h_j = h e^{i k j},
//     K(k) = C^H D^T K D C / ds,  C = e^{i k} I - Ad_{G*^-1},  D = dexp^-1_{-ds xi*},
//     omega(k)^2 = eig(M^-1 K(k)) / ds,
// maximised over k in [0, pi]. This contains the axial and shear waves (omega = 2 c / ds, the
// CFL bound (3.43)) and the rotation-shear coupling (sqrt(G A / rho I)) that limits coarse grids.
#include <string_view>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"

namespace rodlab::solvers::dynamics {

/// Highest frequency [rad/s] of `variational` linearised about the reference configuration.
double variational_max_frequency(const rod::RodModel& model, int nodes);
/// The same for a problem: with embedded muscles, of the composite section (rod plus muscles'
/// transported stiffness and inertia), the largest over the grid; else the rod's.
double variational_max_frequency(const DynamicProblem& problem, int nodes);

/// The largest stable step of `variational` for the linearised rod, with viscosity and laminar
/// drag (turbulent drag and pre-stress are left to the safety factor).
double variational_stable_step(const DynamicProblem& problem, int nodes);

/// Safety factor of `dt: auto` for `variational`, from the measured limits (docs/dynamics.md):
/// the nonlinear runs went unstable between 1.00 and 1.0x the linear limit.
inline constexpr double kVariationalSafety = 0.9;

/// `dt: auto` for a scheme: kVariationalSafety times the stable step for `variational`; for the
/// implicit schemes a tenth of the first bending period (above implicit-midpoint's lower bound).
double auto_time_step(const DynamicProblem& problem, std::string_view scheme, int nodes);

}  // namespace rodlab::solvers::dynamics
