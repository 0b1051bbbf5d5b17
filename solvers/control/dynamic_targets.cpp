#include "rodlab/solvers/control/dynamic_targets.hpp"

#include <algorithm>
#include <random>

#include "rodlab/check.hpp"
#include "rodlab/rod/characteristics.hpp"
#include "rodlab/solvers/control/plant.hpp"
#include "rodlab/solvers/dynamics/dynamic_workspace.hpp"

namespace rodlab::solvers::control {

std::vector<lie::Vector3> dynamic_workspace_tips(const scene::Scene& scene,
                                                 const DynamicTargetOptions& o) {
  dynamics::DynamicWorkspaceOptions w;
  w.solve = o.solver;
  w.solve.max_iterations = std::max(o.solver.max_iterations, PlantOptions::kShotsPerStep);
  w.holds = o.holds;
  const auto problem = dynamics::DynamicProblem::from_scene(scene);
  // the plant's step (for variational below its stability limit: dt_c is far above it)
  PlantOptions po;
  po.solver = o.solver;
  po.dt_control = o.dt_control;
  w.solve.dt = requested_step(problem, po);
  const auto ch = rod::characteristics(problem.model(), o.solver.nodes, rod::TipSupport::free);
  w.hold_time = std::max(o.dt_control, 1.0 / ch.first_bending_frequency_hz);
  w.outputs_per_hold = 10;
  w.seed = o.seed;
  const auto run = dynamics::sample_dynamic_workspace(scene, w);
  const lie::Vector3 rest = problem.reference_tip().translation();
  std::vector<lie::Vector3> tips;
  for (const auto& sample : run.samples) {
    const lie::Vector3 tip = scene.base.pose * sample.tip;  // world frame
    if (sample.converged && (tip - rest).norm() > o.exclude_radius) tips.push_back(tip);
  }
  RODLAB_THROW_UNLESS(!tips.empty(), "control: the dynamic workspace run reached no tip");
  return tips;
}

std::vector<lie::Vector3> draw_dynamic_targets(const scene::Scene& scene,
                                               const DynamicTargetOptions& options, int count) {
  const auto tips = dynamic_workspace_tips(scene, options);
  std::mt19937 rng(options.seed);
  std::vector<lie::Vector3> out;
  for (int k = 0; k < count; ++k) out.push_back(tips[static_cast<std::size_t>(rng() % tips.size())]);
  return out;
}

}  // namespace rodlab::solvers::control
