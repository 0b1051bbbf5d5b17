#pragma once
// One dynamic simulation: the initial state, the time loop shared by every scheme, the output
// series, and the detection of non-convergence and instability (reported in the result, never
// as NaN or a silent success).
#include <functional>
#include <string>
#include <string_view>

#include "rodlab/result/dynamic_result.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/ida_reference.hpp"
#include "rodlab/solvers/dynamics/shooting/bdf_alpha.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"
#include "rodlab/solvers/dynamics/variational/variational.hpp"

namespace rodlab::solvers::dynamics {

/// The options of one run; the scheme-specific ones take their defaults from the scheme's own
/// options struct, where each default is written once.
struct DynamicSolveOptions {
  std::string scheme = "variational";  ///< the default dynamics scheme (rodlab dynamic)
  int nodes = 20;
  double dt = 0.0;          ///< > 0 (resolve `auto` with auto_time_step first)
  double t_end = 0.0;       ///< > 0
  int output_every = 1;     ///< record every k-th step (and the last one)
  double tol = 1e-10;       ///< nonlinear solves inside a step
  int max_iterations = 50;  ///< per nonlinear solve
  ShootingGrid grid = ShootingOptions{}.grid;  ///< `implicit-midpoint`, `bdf-alpha`: solver.grid
  int shooting_intervals = ShootingOptions{}.intervals;  ///< and their march's intervals (0: auto)
  double alpha = BdfAlphaOptions{}.alpha;      ///< `bdf-alpha`: in [-0.5, 0] (0 BDF2, -0.5 trapezoidal)
  /// `variational`: solver.variational_step (verlet, second order; symplectic-euler, the thesis)
  VariationalStep variational_step = VariationalOptions{}.step;
  double rtol = IdaOptions{}.rtol;  ///< `ida`: relative tolerance of the time integration
  double atol = IdaOptions{}.atol;  ///< `ida`: absolute tolerance (scaled per component, ida_reference.hpp)
  scene::Initial initial = scene::Initial::straight;
  /// Wall-time guard [s]: the run stops, not converged, once it has taken longer (checked after
  /// every step; inside `ida`'s long steps between chunks of internal steps); 0: none.
  double max_wall_time = 0.0;
  /// Called with the stepper at every recorded time (t = 0, every output_every-th step, the
  /// last one, a failed step's): ParaView output (--vtk). Its own time is not in wall_time_s.
  std::function<void(double t, const Stepper& state)> on_output;
  /// Called after every step that succeeded (steps done of all, the time reached, the step):
  /// the progress line.
  std::function<void(long done, long steps, double t, double dt)> on_step;
};

/// The scheme options a scene sets (solver.alpha, solver.grid, solver.variational_step) and its initial state
/// (dynamics.initial), over the defaults: what `rodlab dynamic` and the studies take from it.
void apply_scene_options(const scene::Scene& scene, DynamicSolveOptions& options);

/// The problem on options.grid: `problem` itself, or on the corrected grid its model with the
/// grid's residual bending flexibility (corrected_grid.hpp; std::invalid_argument naming
/// solver.grid where options.scheme or the scene cannot take it). `dt: auto` and every run of
/// a scheme read the problem through it.
DynamicProblem problem_on_grid(DynamicProblem problem, const DynamicSolveOptions& options);
/// The problem `scheme` runs at `nodes` nodes on the scene's own grid (apply_scene_options, then
/// problem_on_grid, which throws where the scheme or the scene cannot take that grid).
DynamicProblem scene_problem_on_grid(const scene::Scene& scene, std::string_view scheme,
                                     int nodes);

/// The rod at rest in its rest shape on a grid of `nodes` nodes: the reference configuration's
/// poses, and each node's strain its segment's rest strain (RodModel::segment_xi_star).
RestState rest_shape(const DynamicProblem& problem, int nodes);

/// The initial state at rest (options.initial): the reference configuration, or the static
/// equilibrium under the t = 0 loads. A clamped tip must hold the reference configuration's tip
/// to start from it (else std::invalid_argument). A failed equilibrium leaves the reference
/// configuration and its reason in `failure`.
RestState initial_state(const scene::Scene& scene, const DynamicProblem& problem,
                        const DynamicSolveOptions& options, std::string& failure);

/// Whether a dynamics scheme marches the rod in s every step (implicit-midpoint, bdf-alpha): the
/// schemes that take the thesis' Euler grid (solver.grid: euler); the others ignore it.
bool marches_in_s(std::string_view scheme);

/// Why options.scheme cannot run at the step dt on `problem`, or "" when it can: single
/// shooting (implicit-midpoint, bdf-alpha) has a lower step bound, which multiple shooting lifts
/// on the staggered grids without actuator unknowns (step_bound.hpp). Runs are refused with it
/// before they start (solve_dynamic, rodlab.Simulation).
std::string step_problem(const DynamicProblem& problem, const DynamicSolveOptions& options,
                         double dt);

/// Runs the simulation. Throws std::invalid_argument for bad options or unsupported scene
/// features; a failed step or an instability ends the run with converged = false and the reason.
result::DynamicResult solve_dynamic(const scene::Scene& scene, const DynamicSolveOptions& options);

}  // namespace rodlab::solvers::dynamics
