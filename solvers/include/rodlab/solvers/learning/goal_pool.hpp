#pragma once
// The goals of the learning tasks (thesis 4.4.2; docs/learning.md "Tasks"):
//   reach-one  one tip of the dynamic workspace outside the static one: the first candidate (in
//              the seeded draw order) whose closest quasi-static tip (inverse statics, chebyshev)
//              is farther than the success threshold, so the rod can pass through it but not
//              hold it there;
//   reach-any  every candidate tip of the dynamic workspace (control/dynamic_targets.hpp);
//   track      tips of the static workspace (control/static_targets.hpp), the ends of the
//              random paths.
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/learning/rod_environment.hpp"

namespace rodlab::solvers::learning {

struct GoalPoolOptions {
  int dynamic_holds = 100;  ///< input vectors of the dynamic-workspace run (reach tasks)
  int static_points = 50;  ///< static-workspace samples (track)
  std::uint64_t seed = 1;
};

/// The pool of `environment.task` on the environment's plant (scheme, nodes, dt_control).
/// Throws std::invalid_argument when the workspaces give no goal (reach-one: no candidate lies
/// outside the static workspace).
GoalPool make_goal_pool(const scene::Scene& scene, const EnvironmentOptions& environment,
                        const GoalPoolOptions& options = {});

}  // namespace rodlab::solvers::learning
