#include "rodlab/solvers/dynamics/dynamic_workspace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "rodlab/solvers/statics/workspace.hpp"

namespace rodlab::solvers::dynamics {

result::WorkspaceResult sample_dynamic_workspace(const scene::Scene& scene_in,
                                                 const DynamicWorkspaceOptions& options) {
  if (options.holds < 1) throw std::invalid_argument("holds must be >= 1");
  if (!(options.hold_time > 0.0) || !std::isfinite(options.hold_time))
    throw std::invalid_argument("the hold time must be > 0");
  if (options.outputs_per_hold < 1) throw std::invalid_argument("outputs_per_hold must be >= 1");
  const auto start = std::chrono::steady_clock::now();
  scene::Scene scene = scene_in;
  const auto inputs = statics::workspace_inputs(scene);

  // The held inputs: one steps schedule per actuator.
  std::mt19937 rng(options.seed);
  std::vector<std::vector<double>> held(options.holds);
  std::vector<std::vector<std::pair<double, double>>> steps(inputs.size());
  for (int h = 0; h < options.holds; ++h) {
    for (std::size_t k = 0; k < inputs.size(); ++k) {
      const double v = statics::workspace_uniform(rng, inputs[k].limits.first, inputs[k].limits.second);
      held[h].push_back(v);
      steps[k].emplace_back(h * options.hold_time, v);
    }
  }
  for (std::size_t k = 0; k < inputs.size(); ++k)
    *inputs[k].value = scene::ScalarSchedule(scene::ScalarSchedule::Kind::steps, steps[k]);

  DynamicSolveOptions solve = options.solve;
  solve.t_end = options.holds * options.hold_time;
  const long steps_per_hold = std::max(1L, std::lround(std::ceil(options.hold_time / solve.dt)));
  solve.output_every = static_cast<int>(std::max(1L, steps_per_hold / options.outputs_per_hold));
  const auto run = solve_dynamic(scene, solve);

  result::WorkspaceResult out;
  out.scene = scene.name;
  out.scheme = solve.scheme;
  out.nodes = solve.nodes;
  out.length = scene.rod.length;
  out.seed = options.seed;
  const lie::SE3 base_inv = scene.base.pose.inverse();
  for (std::size_t i = 0; i < run.t.size(); ++i) {
    result::WorkspaceSample sample;
    const int h = std::clamp(static_cast<int>(std::floor(run.t[i] / options.hold_time)), 0,
                             options.holds - 1);
    sample.inputs = held[h];
    sample.tip = base_inv * run.tip_position[i];
    sample.coordinates = statics::workspace_coordinates(sample.tip, scene.rod.length);
    sample.converged = sample.tip.allFinite();
    out.samples.push_back(std::move(sample));
  }
  out.failed = run.converged ? 0 : 1;
  // the state recorded at a failure is not a reached tip
  if (!run.converged && !out.samples.empty()) out.samples.back().converged = false;
  out.bounds = statics::fit_workspace_bounds(out.samples);
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rodlab::solvers::dynamics
