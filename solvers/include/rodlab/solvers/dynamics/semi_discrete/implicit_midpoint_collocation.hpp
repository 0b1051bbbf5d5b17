#pragma once
// `implicit-midpoint-collocation`: the implicit midpoint rule in time on the semi-discrete rod of
// `ida` (semi_discrete_rod.hpp, the staggered grid of `variational`), each step's spatial problem
// solved globally (all nodes at once) by KINSOL with the KLU sparse linear solver;
// docs/dynamics.md, section `implicit-midpoint-collocation`.
//
// One step from (t, y0) with h = t + dt/2 (y = [nodes; D; W], f from semi_discrete_rod.hpp):
//   y1 = y0 + dt f(h, (y0 + y1) / 2)                         (implicit midpoint, cf. (3.50))
// Unknown: the half-step increment z = (y1 - y0) / 2 of the node rows (the ledger rows do not
// feed back into f, so D1 = D0 + dt P_diss(h, y0 + z), W1 = W0 + dt P_in(h, y0 + z)). Residual
// and Newton matrix, in rates (units of y'):
//   F(z) = (2 / dt) z - f(h, y0 + z),    dF/dz = (2 / dt) I - df/dy(h, y0 + z)
// the same block-tridiagonal matrix as ida's cj I - df/dy with cj = 2 / dt, factorised by KLU.
// Working in z (not y1 or the midpoint) and in rates keeps the residual free of the rounding of
// y0 + z - y0 at small dt, and makes the tolerance a rate: the error committed per step is
// about dt/2 times the residual, so the solver's share of the global error does not grow as
// dt -> 0 (no lower time-step bound). Scaling: F_i by 1 / (omega_1 w_i) and z_i by
// 2 / (dt omega_1 w_i), w = tolerance_scale(); converged when max |scaled F| <= tol, floored at
// the rounding level of f (kRoundingFloor eps (omega_max / omega_1)^2, omega_max the highest
// frequency of the grid, time_step.hpp).
//
// Predictor: the step's mean rate extrapolated linearly from the last two steps' mean rates
// (2 z / dt), or f(h, y0) after a start or a restart. Jacobian: analytic where the derivation
// covers the scene, else finite differences with three node colours (semi_discrete_rod.hpp),
// kept across steps and refreshed when a solve needed more
// than a few iterations, every `jacobian_max_age` steps, or within a solve where good Broyden's
// steps on its factors stop contracting (KinsolSolver::solve_broyden; the diagonal follows a
// change of dt). Its factors are kept with it (KinsolSolver's KluReuse::factors): a step
// with the kept Jacobian and an unchanged dt starts from them without refactorising, the
// symbolic analysis is done once, and a new Jacobian is refactorised numerically on the kept
// pivot order.
// A step that does not converge is a failed StepStatus with KINSOL's flag and the state is left
// at t.
//
// Kirchhoff rods (nu = nu*): the unknowns are u = [z; f], f the step's mean constraint forces
// (3 per segment, in the segments' stresses: semi_discrete_rod.hpp), and the residual gets the
// constraint rows at the END of the step, c(y0 + 2 z) = 0 (the midpoint analogue of SHAKE):
//   F = [ (2/dt) z - f(h, y0 + z; f) ;  c(y0 + 2 z) ],
//   dF/du = [ (2/dt) I - df/dy   -df/df ;  2 dc/dy   0 ]   (finite differences, KLU).
// f is scaled by E I / L^2, c by 1; f is predicted by the last step's. The initial poses are put
// on the constraint (each segment keeps its rotation, nu = nu*).
#include <memory>
#include <span>

#include "rodlab/solvers/common/kinsol_solver.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {

struct ImplicitMidpointCollocationOptions {
  int nodes = 20;
  double tol = 1e-10;        ///< on the scaled residual (max norm), see above
  int max_iterations = 50;   ///< Newton iterations per step
  /// 1: exact Newton (KINSOL, a Jacobian at every iteration); otherwise a step starts with
  /// Broyden's steps, and KINSOL's fallbacks take a Jacobian every max_setup_calls iterations
  int max_setup_calls = 10;
  int jacobian_max_age = 50;  ///< steps a Jacobian is kept at most (0: a
                              ///< fresh one at the start of every step; with
                              ///< max_setup_calls = 1, exact Newton throughout)
  /// The corrected grid (as IdaOptions::corrected_grid).
  bool corrected_grid = false;
  /// The Newton systems' linear solver where the step's unknowns are the node rows alone
  /// (Cosserat rods without actuator unknowns; else KLU): the pose rows condensed and block LU
  /// (the same solutions to rounding, about 3x cheaper than KLU at N = 20), or `klu`.
  NewtonLinearSolver linear_solver = NewtonLinearSolver::condensed_rod_blocks;
};

/// The stepper, with the diagnostics of the scheme beyond Stepper's.
class ImplicitMidpointCollocationStepper : public Stepper {
 public:
  /// max_j | |q_j| - 1 | of the stored (unnormalised) quaternions: the midpoint rule keeps
  /// this quadratic invariant up to the solver tolerance.
  virtual double max_quaternion_norm_deviation() const = 0;
  /// Finite-difference Jacobians computed so far (the rest of the solves reused one).
  virtual long jacobian_evaluations() const = 0;
};

/// Starts at rest from the node poses g0 (base first, options.nodes of them).
std::unique_ptr<ImplicitMidpointCollocationStepper> make_implicit_midpoint_collocation(
    const DynamicProblem& problem, const ImplicitMidpointCollocationOptions& options,
    std::span<const SE3> g0);

/// The same from a RestState: only the poses are used (the strains follow from them).
std::unique_ptr<ImplicitMidpointCollocationStepper> make_implicit_midpoint_collocation(
    const DynamicProblem& problem, const ImplicitMidpointCollocationOptions& options,
    const RestState& initial);

}  // namespace rodlab::solvers::dynamics
