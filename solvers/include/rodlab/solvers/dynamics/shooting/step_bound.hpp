#pragma once
// The lower step bound of single shooting (`implicit-midpoint`, `bdf-alpha`), known before the
// run starts (docs/dynamics.md "The lower step bound of single shooting").
//
// Each step solves a BVP in s whose linearisation about the straight rod, with x_dot = c x + h
// (c = 2 / dt: the midpoint rule and bdf-alpha's midpoint start-up steps), has solutions growing
// like e^(k s) along the rod:
//   bending   k_b = (rho A c^2 / Kt_bend)^(1/4)       (w'''' = rho A c^2 w / Kt_bend)
//   shear     k_s = c sqrt(rho A / Kt_shear)          axial  k_a = c sqrt(rho A / Kt_axial)
//   torsion   k_t = c sqrt(rho J / Kt_torsion),       Kt = K + c V (Kelvin-Voigt, (3.10)),
// so the tip residual amplifies an error at the base by e^kappa, kappa = L max(k). Newton on the
// base wrench can then converge only while the rounding of the march, eps e^kappa, stays below
// the tolerance: kappa <= ln(tol / eps) (13.0 at tol = 1e-10). Measured (implicit-midpoint,
// N = 20, released under gravity, E from 1e6 to 2e11 Pa, viscosity 0 and 300 Pa s): on the
// staggered grid every run with kappa <= 12.0 ran and every one with kappa >= 12.3 failed; the
// thesis' Euler grid, whose explicit Euler march amplifies less than e^(k ds) per segment, ran up
// to 14.8 and failed at 15.9; the bound is the same at N = 20..50 (the viscous cantilever: dt =
// 2 ms runs, 1 ms fails at every N). Beyond the bound the staggered grids march by multiple
// shooting (shooting_intervals); runs it does not reach are refused before they start (exit 2),
// naming the smallest step within the bound (necessary, not sufficient: a heavy, very soft rod
// also fails at large steps, where one step's motion is too nonlinear for Newton from the last
// state) and the schemes without it.
#include <string>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/shooting/shooting_stepper.hpp"

namespace rodlab::solvers::dynamics {

/// kappa = L max(k_b, k_s, k_a, k_t) at c = 2 / dt (the problem's own section: muscles' embedded
/// stiffness is left out, which only lowers kappa).
double single_shooting_exponent(const DynamicProblem& problem, double dt);

/// The largest kappa a grid's single shooting reaches tol on: ln(tol / eps) plus the grid's
/// measured allowance (the boundaries above: staggered 12.2, Euler 15.5 at tol = 1e-10).
double single_shooting_exponent_bound(ShootingGrid grid, double tol);
inline constexpr double kStaggeredGridAllowance = -0.8;
inline constexpr double kEulerGridAllowance = 2.5;

/// The smallest dt whose kappa is within the bound (bisection on the monotone kappa(dt)).
double single_shooting_min_step(const DynamicProblem& problem, ShootingGrid grid, double tol);

/// Empty when `scheme` (implicit-midpoint or bdf-alpha) can run at dt by single shooting; else
/// why not, naming the smallest step that fits and the schemes to use instead.
std::string single_shooting_step_problem(const DynamicProblem& problem, std::string_view scheme,
                                         ShootingGrid grid, double dt, double tol);

/// Multiple shooting (the staggered and corrected grids' stepper, docs/dynamics.md "Multiple
/// shooting below the bound"): beyond the bound the rod is cut into intervals whose exponents
/// stay kIntervalMargin below it, ceil(kappa / (bound - margin)) of them (at least one per
/// kMinIntervalExponent of kappa where the tolerance leaves almost no room; at most one per
/// segment: Newton's model is sparse beyond 96 unknowns, inverse_broyden.hpp; until session 33
/// a dense inverse capped them at 32); 1 within the bound
/// (single shooting, unchanged). kappa overstates the march's amplification where k ds > 1
/// (a segment amplifies by about 1 + k ds, not e^(k ds)): the viscous cantilever at N = 20 runs
/// at dt = 1.1e-6 s with 19 intervals, kappa / 19 = 12.7. The margin: the joins' residuals
/// carry the march's rounding amplified over an interval, and at dt = 0.1 ms (the viscous
/// cantilever, N = 20, kappa 25.1) three intervals (8.4 each) stalled at 1-3e-10 from t = 0.11 s
/// on, four (6.3) ran.
inline constexpr double kIntervalMargin = 4.0;
inline constexpr double kMinIntervalExponent = 1.0;
int shooting_intervals(double kappa, ShootingGrid grid, double tol, int segments);

/// Empty when the stepper runs at dt: by single shooting within the bound, by multiple shooting
/// beyond it on the staggered and corrected grids; else (the Euler grid beyond its bound)
/// single_shooting_step_problem's reason.
std::string shooting_step_problem(const DynamicProblem& problem, std::string_view scheme,
                                  ShootingGrid grid, double dt, double tol);

}  // namespace rodlab::solvers::dynamics
