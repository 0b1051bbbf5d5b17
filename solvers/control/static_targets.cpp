#include "rodlab/solvers/control/static_targets.hpp"

#include "rodlab/solvers/statics/workspace.hpp"

namespace rodlab::solvers::control {

StaticTargets sample_static_targets(const scene::Scene& scene, const statics::StaticSolveOptions& options,
                                    int count, unsigned seed) {
  const auto workspace = statics::sample_workspace(scene, options, count, seed);
  StaticTargets out;
  out.seed = seed;
  out.failed = workspace.failed;
  for (const auto& sample : workspace.samples) {
    if (!sample.converged) continue;
    out.inputs.emplace_back(Eigen::Map<const Eigen::VectorXd>(sample.inputs.data(),
                                                              static_cast<Eigen::Index>(sample.inputs.size())));
    out.tips.push_back(scene.base.pose * sample.tip);  // sample_workspace gives base-frame tips
  }
  return out;
}

}  // namespace rodlab::solvers::control
