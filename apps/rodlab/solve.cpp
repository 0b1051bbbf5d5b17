#include "solve.hpp"

#include <stdexcept>
#include <string>

#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::cli {

result::StaticResult solve_static(const scene::Scene& scene, const StaticRun& run) {
  solvers::statics::StaticSolveOptions options;
  options.scheme = std::string(run.scheme.name);
  options.nodes = run.nodes;
  options.tol = run.tol;
  options.max_iterations = run.max_iterations;
  options.time = run.time;
  return solvers::statics::solve_static(scene, options);
}

result::DynamicResult solve_dynamic(const scene::Scene& scene, const DynamicRun& run) {
  solvers::dynamics::DynamicSolveOptions options;
  options.scheme = std::string(run.scheme.name);
  options.nodes = run.nodes;
  options.dt = run.dt.value;
  options.t_end = run.t_end;
  options.output_every = run.output_every;
  options.tol = run.tol;
  options.max_iterations = run.max_iterations;
  options.rtol = run.rtol;
  options.atol = run.atol;
  options.alpha = run.alpha;
  options.grid = run.grid;
  if (scene.dynamics) options.initial = scene.dynamics->initial;
  return solvers::dynamics::solve_dynamic(scene, options);
}

}  // namespace rodlab::cli
