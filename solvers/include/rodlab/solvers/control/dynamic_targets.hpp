#pragma once
// Targets drawn from the dynamic workspace (thesis 3.4.1, 4.4.1): random inputs, each held for
// one first bending period on the plant's scheme (dynamics::sample_dynamic_workspace), every
// recorded tip a candidate: points the rod passes through, beyond what it can hold. For the
// dynamic reach of the controllers (control_run.hpp) and the learning tasks (learning/).
#include <vector>

#include "rodlab/lie/se3.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"

namespace rodlab::solvers::control {

struct DynamicTargetOptions {
  /// The plant's scheme and options; its step is the plant's for dt_control (plant.hpp,
  /// requested_step: below the stability limit for `variational`).
  dynamics::DynamicSolveOptions solver;
  double dt_control = 0.05;  ///< [s]
  int holds = 10;            ///< random input vectors, each held for one first bending period
  /// Candidates within this distance of the rest tip are left out [m] (a target the rod starts
  /// on is no test).
  double exclude_radius = 0.0;
  unsigned seed = 1;
};

/// The candidate tips (world frame) of one dynamic-workspace run. Throws std::invalid_argument
/// for a scene without actuators or limits, or when no tip lies beyond exclude_radius.
std::vector<lie::Vector3> dynamic_workspace_tips(const scene::Scene& scene,
                                                 const DynamicTargetOptions& options);

/// `count` of them drawn with options.seed (std::mt19937, with replacement).
std::vector<lie::Vector3> draw_dynamic_targets(const scene::Scene& scene,
                                               const DynamicTargetOptions& options, int count);

}  // namespace rodlab::solvers::control
