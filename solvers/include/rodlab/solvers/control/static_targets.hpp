#pragma once
// Targets drawn from the static workspace (thesis 2.7.3, 4.1): inputs sampled uniformly within
// every actuator's limits with a seed (std::mt19937, statics::sample_workspace), each solved by
// the forward statics; the tips are reachable by construction. For the reach tests of inverse
// statics (control/inverse_statics.hpp) and the controllers after it.
#include <vector>

#include <Eigen/Core>

#include "rodlab/lie/se3.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::solvers::control {

struct StaticTargets {
  unsigned seed = 0;
  std::vector<Eigen::VectorXd> inputs;  ///< the sampled inputs of each target (scene order)
  std::vector<lie::Vector3> tips;       ///< the targets: their tips, world frame
  int failed = 0;                       ///< samples whose statics did not converge (left out)
};

/// `count` samples with `seed` (statics::sample_workspace: the same draws as `rodlab workspace`);
/// those that converge become targets. Throws std::invalid_argument as sample_workspace does
/// (no actuators, an actuator without limits, count < 1).
StaticTargets sample_static_targets(const scene::Scene& scene, const statics::StaticSolveOptions& options,
                                    int count, unsigned seed);

}  // namespace rodlab::solvers::control
