#pragma once
// The shooting stepper shared by `implicit-midpoint` and `bdf-alpha`: a time-difference rule
// (time_rule.hpp) in time, explicit Euler RKMK in space, single shooting (thesis Algorithm 2,
// (3.46)-(3.54); Till, Aloi & Rucker 2019); docs/dynamics.md. This is the thesis' grid
// (ShootingGrid::euler, kept by name for reproducing it); the default, ShootingGrid::staggered,
// marches the semi-discrete rod of `ida` instead (staggered_shooting_stepper.hpp: second order
// in s, its undamped energy conserved, its ledger closed; docs/dynamics.md "Why the staggered
// grid is the default").
//
// Each step solves, for the unknown profiles at t_u = t + theta dt with x_dot = c x + h
// (x = xi, eta), the BVP in s
//   g'      = g hat(xi)
//   Lambda' = M (c eta + h_eta) - ad_eta^T M eta + ad_xi^T Lambda - W_bar(t_u)   (3.51)
//   eta'    = (c xi + h_xi) - ad_xi eta                                           (3.52)
//   Lambda  = K (xi - xi*) + V (c xi + h_xi) + sum_k F_k(t_u) c_k(xi)
//           = Kt (xi - xi_ref) + sum_k F_k c_k(xi),  Kt = K + c V,
//             xi_ref = Kt^-1 (K xi* - V h_xi)                      (3.10), solved for xi
// from g(0) = base, eta(0) = 0 and the unknown Lambda(0), to the tip condition
// Lambda(L) = W_tip(t_u). The rule then advances the state (xi, eta at the nodes) from the
// converged profiles; poses follow from xi by the same spatial integration. Lambda, not xi (the
// thesis), is shot from the base, as in the statics: actuators and Kirchhoff constraint forces
// (nu held at nu*, Lambda's force part is then the constraint force) need no special treatment.
// Newton on Lambda(0): finite-difference Jacobian, Broyden updates, reused across steps, with a
// linear predictor from the last two steps.
#include <memory>
#include <optional>
#include <string_view>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"
#include "rodlab/solvers/dynamics/shooting/time_rule.hpp"

namespace rodlab::solvers::dynamics {

/// The spatial grid of a shooting march (`solver.grid`, `--grid`).
enum class ShootingGrid {
  euler,      ///< nodes, explicit Euler RKMK (the thesis' Algorithm 2)
  staggered,  ///< nodes and segments of `variational` / `ida` (staggered_shooting_stepper.hpp)
  /// the staggered grid with its two O(ds^2) corrections (corrected_grid.hpp), every scheme's
  corrected
};
/// "euler" / "staggered" / "corrected".
std::string_view shooting_grid_name(ShootingGrid grid);
std::optional<ShootingGrid> shooting_grid_from_name(std::string_view name);

struct ShootingOptions {
  int nodes = 20;
  double tol = 1e-10;       ///< on the tip residual, wrenches scaled by E I / L and E I / L^2
  int max_iterations = 50;  ///< shooting integrations per step, Jacobian columns included
  /// The default is the most correct grid (second order in s, energy-stable); `euler` reproduces
  /// the thesis.
  ShootingGrid grid = ShootingGrid::staggered;
  /// Intervals of the staggered grids' march (multiple shooting; step_bound.hpp): 0 picks them
  /// from the step (1, single shooting, within its lower step bound); > 0 forces that many
  /// (tests; the Euler grid and actuator unknowns always shoot singly).
  int intervals = 0;
};

/// Starts at rest from `initial` (options.nodes nodes).
std::unique_ptr<Stepper> make_shooting_stepper(const DynamicProblem& problem,
                                               const ShootingOptions& options,
                                               const RestState& initial,
                                               std::unique_ptr<TimeRule> rule);

}  // namespace rodlab::solvers::dynamics
