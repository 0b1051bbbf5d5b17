#pragma once
// `variational`: the explicit discrete variational Lie-group integrator (thesis Algorithm 1,
// (3.26)-(3.44)); derivation, indexing and departures from the thesis in docs/dynamics.md.
//
// Grid: nodes j = 0..N-1 at s_j = j ds (ds = L / (N - 1)) carry the pose g^j, the velocity
// eta^j over the current step and the discrete momentum; segments j = 0..N-2 carry the relative
// pose G^j = exp(ds xi^j) = (g^j)^-1 g^(j+1). One step, t -> t + dt:
//   E^j = exp(dt eta^j)                                        (3.26)
//   G^j <- (E^j)^-1 G^j E^(j+1),  xi^j = log(G^j) / ds           (3.38), exact compatibility
//   g^(j+1) = g^j G^j from the base                              (3.39)
//   lambda^j = dexp^-T_{ds xi^j} [K (xi^j - xi*) + V xi_dot^j + sum F c]   (3.40), xi_dot over the step
//   w_j ds (mu^j - Ad^T_{E^j} mu_old^j) / dt = lambda^j - Ad^T_{G^(j-1)} lambda^(j-1) + w_j ds W_bar^j
//                                                                (3.41); at the tip lambda^(N-1) := W_tip
//   dexp^-T_{dt eta^j} M eta^j = mu^j, solved for eta^j by Newton   (3.42)
// with trapezoid weights w_j (1/2 at the tip node; the thesis gives the tip a full cell, which
// makes the scheme first order in space). Conservative loads are evaluated at the new
// configuration; viscosity and drag at the mean of the rates before and after it (verlet, by a
// corrector pass) or at the old ones (symplectic-euler). Kirchhoff rods (nu = nu*) get constraint forces per
// segment, solved each step so that the next step's segments satisfy the constraint (SHAKE;
// kirchhoff_constraint.hpp, docs/dynamics.md).
//
// The time rule (VariationalStep): `verlet` (the default) starts with half a step's impulse at
// the initial configuration, which makes the velocities those of the half steps and the scheme
// the Lie-group Stormer-Verlet (leapfrog) of the trapezoidal discrete Lagrangian: second order
// in time for conservative loads. `symplectic-euler` starts with the initial velocity over the
// first step, as the thesis does: first order. The steps after the first are the same.
#include <memory>
#include <optional>
#include <string_view>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {

enum class VariationalStep { verlet, symplectic_euler };
/// "verlet", "symplectic-euler"; nullopt for any other name.
std::string_view variational_step_name(VariationalStep step);
std::optional<VariationalStep> variational_step_from_name(std::string_view name);

struct VariationalOptions {
  int nodes = 20;
  double tol = 1e-12;      ///< relative tolerance of the Newton solve of (3.42)
  int max_iterations = 20; ///< Newton iterations per node and step
  VariationalStep step = VariationalStep::verlet;
  /// The plain step on pairs of nodes (SSE2; docs/dynamics.md "The packed variational step")
  /// where the scene allows it: a rod without actuators or cables entering from outside. It
  /// computes the general loop's quantities to rounding; false runs the general loop (the tests
  /// compare the two).
  bool packed = true;
  /// The corrected grid's free tip (solver.grid: corrected; corrected_grid.hpp): the tip's half
  /// cell as a rigid body (TipHalfCell). The problem is to carry the grid's model
  /// (corrected_grid_problem); Cosserat rods without actuators.
  bool corrected_grid = false;
};

/// Starts at rest from `initial` (options.nodes nodes).
std::unique_ptr<Stepper> make_variational(const DynamicProblem& problem,
                                          const VariationalOptions& options,
                                          const RestState& initial);

}  // namespace rodlab::solvers::dynamics
