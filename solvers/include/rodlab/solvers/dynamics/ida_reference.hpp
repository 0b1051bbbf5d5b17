#pragma once
// `ida`: the dynamics reference. Method of lines in s, integrated in time by SUNDIALS IDA
// (variable-order BDF, error control at rtol = atol = 1e-10 by default) with the KLU sparse
// linear solver (common/ida_solver.hpp).
//
// Semi-discretisation: the time-continuous limit of `variational` (variational.hpp), so the two
// agree at equal N as dt -> 0. Nodes j = 0..N-1 at s_j = j ds, ds = L / (N - 1); node 0 is the
// fixed base (g_0 = base, eta_0 = 0). Unknowns per node j >= 1, 13 of them: the position p_j
// (world), a quaternion q_j = [w x y z] (normalised when R_j is formed; its ODE keeps |q| = 1 to
// the tolerance) and the body velocity eta_j = [psi; kappa]. On segment j (nodes j, j + 1):
//   G = g_j^-1 g_(j+1),  xi_j = log(G) / ds,
//   xi_dot_j = dexp^-1_{-ds xi_j} (eta_(j+1) - Ad_{G^-1} eta_j) / ds   (exact d/dt of xi_j)
//   sigma_j = K (xi_j - xi*) + V xi_dot_j + sum_k F_k c_k(xi_j)         at the segment midpoint
//   lambda_j = dexp^-T_{ds xi_j} sigma_j   (node j's frame; Ad_G^T lambda_j in node j + 1's)
// and at the nodes, with trapezoid weights w_j = ds (w_(N-1) = ds / 2):
//   F_j = lambda_j - Ad_{G_(j-1)}^T lambda_(j-1)   (lambda_(N-1) := W_tip at the tip)
//   p_dot = R kappa,  q_dot = q (x) [0; psi] / 2,
//   M eta_dot = ad_eta^T M eta + F_j / w_j + W_bar(R_j, eta_j, t)       (thesis (3.8))
// plus the entry load of a cable pulled from outside at the node nearest its entry point.
// The system is an ODE written as IDA's residual F = y' - f(t, y) (the eta rows divided by M);
// the Newton matrix cj I - df/dy is block tridiagonal in the nodes (13 x 13 blocks) and is
// filled by finite differences with three node colours (j mod 3), then factorised by KLU.
//
// Energy ledger: kinetic, strain and gravity energies come from energy.hpp; `dissipated`
// (viscous power sum_j ds xi_dot^T V xi_dot, drag power -w_j drag . eta_j) and `work_in` (tip
// wrench, distributed wrench, actuator and cable-entry power) are two extra differential
// unknowns D' = P_diss(y), W' = P_in(y) integrated by IDA under the same error control (plain
// IDA has no quadrature facility; that is IDAS). Their rows of the Newton matrix are exact
// finite differences too (the powers are sums of per-segment and per-node terms, which the
// colouring keeps apart). The semi-discrete balance T + U + P + D - W = const is exact, so
// Energy::total() drifts only by the integration error.
//
// Absolute tolerances per component (atol is the option):
//   position [m]: atol;  quaternion [1]: atol;
//   angular velocity [rad/s]: atol * omega_1;  linear velocity [m/s]: atol * L * omega_1;
//   dissipated and work_in [J]: atol * E_bend,
// with omega_1 = 2 pi f_1 the first (Euler-Bernoulli, free tip) bending frequency and
// E_bend = 1/2 EI (pi / 2L)^2 L the strain energy of a quarter-circle bend (the characteristic
// velocity and energy of the rod's gross motion).
//
// Consistent initial conditions: the run starts at rest from the given node poses, so y'0 =
// f(0, y0) is computed directly (p' = q' = 0, eta' = M^-1 (...), no IDACalcIC).
// Kirchhoff rods are not supported yet (std::invalid_argument).
#include <memory>
#include <span>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {

struct IdaOptions {
  int nodes = 20;
  double rtol = 1e-10, atol = 1e-10;  ///< IDA's tolerances (atol scaled per component, above)
  int max_steps = 100000;             ///< internal IDA steps per step() call
};

/// Starts at rest from the node poses g0 (base first, options.nodes of them). step(t, dt)
/// integrates to t + dt with the stop time there (a failed IDASolve is a failed StepStatus with
/// IDA's flag name and time; `iterations` counts IDA's Newton iterations in the step). A call
/// whose t is not the time reached restarts IDA there from the current state.
std::unique_ptr<Stepper> make_ida(const DynamicProblem& problem, const IdaOptions& options,
                                  std::span<const SE3> g0);

}  // namespace rodlab::solvers::dynamics
