#include "solve.hpp"

#include <stdexcept>
#include <string>

#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::cli {

result::StaticResult solve_static(const scene::Scene& scene, const StaticRun& run) {
  solvers::statics::StaticSolveOptions options;
  options.scheme = std::string(run.scheme.name);
  options.nodes = run.nodes;
  options.tol = run.tol;
  options.max_iterations = run.max_iterations;
  return solvers::statics::solve_static(scene, options);
}

result::DynamicResult solve_dynamic(const scene::Scene& /*scene*/, const DynamicRun& run) {
  // Dynamics solvers arrive with the dynamics issue (#4): dispatch on run.scheme.name here.
  throw std::logic_error("no dynamics solver is linked for scheme '" +
                         std::string(run.scheme.name) +
                         "' although the scheme catalogue marks it available");
}

}  // namespace rodlab::cli
