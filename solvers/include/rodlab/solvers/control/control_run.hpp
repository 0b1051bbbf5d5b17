#pragma once
// One `rodlab control` run (thesis 4.4.1; docs/control.md "Tasks"): a controller on a task,
// episode after episode, into a rodlab.control-result/1.
//
//   reach  each target: control steps until the tip is within threshold * L (success) or
//          max_steps have passed; the plant starts from its initial state every episode.
//   hold   each target: success once the error has stayed below threshold * L for hold_steps
//          consecutive steps, within max_steps.
//   track  one episode along control.trajectory for its duration; the horizon's targets are the
//          trajectory's points at the coming control steps; success: mean error below
//          threshold * L.
//
// Targets: control.targets, else `target_count` drawn with `seed` from the static workspace
// (static_targets.hpp: reachable by construction). Controllers: `nlsq-mpc` (nlsq_mpc.hpp) on a
// dynamics scheme; `lqr` (reach, hold; lqr_hold.hpp) about the equilibrium of the inverse
// statics' inputs for each target, its gain designed at the episode's start; `policy` a trained
// policy (learning/policy.hpp: one network evaluation per step; reach-one's target by default);
// `quasi-static` (inverse_statics.hpp) on the statics: one inverse-statics
// solve per target (reach, hold: `steps` counts its updates) or per control step (track).
// A solver failure ends its episode (the episode's reason) and marks the run (converged false,
// the first failure's reason); the other episodes still run. A target the quasi-static
// controller cannot reach (outside the workspace) is reported with its closest tip and reason.
#include <functional>
#include <optional>
#include <string>

#include "rodlab/result/control_result.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/learning/policy.hpp"

namespace rodlab::solvers::control {

struct ControlRunOptions {
  std::string controller = "nlsq-mpc";  ///< quasi-static | nlsq-mpc | lqr (ilqr: not yet)
  scene::Control control;               ///< the task and its settings
  /// The dynamics scheme of the plant (scheme, nodes, tol, grid, ...); its max_iterations is
  /// raised to the plant's (plant.hpp).
  dynamics::DynamicSolveOptions solver;
  /// `policy`: the trained policy (learning/policy.hpp) acting on the plant; its nodes,
  /// dt_control, inputs and observation scales must be the plant's.
  std::optional<learning::Policy> policy;
  /// Called with the plant's state at every episode's start and after every control step of
  /// a dynamic controller (episode index, the episode's time): ParaView output (--vtk).
  std::function<void(int episode, double t, const dynamics::Stepper& state)> on_state;
};

/// Runs the task. Throws std::invalid_argument for bad options (an unknown or not yet available
/// controller, a task without what it needs) and what the plant refuses.
result::ControlResult run_control(const scene::Scene& scene, const ControlRunOptions& options);

}  // namespace rodlab::solvers::control
