#include "rodlab/solvers/statics/solve_static.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/registry.hpp"

namespace rodlab::solvers::statics {

result::StaticResult solve_static(const StaticProblem& problem, const StaticSolveOptions& options) {
  const SchemeInfo& scheme = scheme_for(options.scheme, Problem::statics);
  RODLAB_THROW_UNLESS(options.nodes >= min_nodes(Problem::statics), "nodes must be >= {}",
                      min_nodes(Problem::statics));
  RODLAB_THROW_UNLESS(options.max_wall_time >= 0.0 && std::isfinite(options.max_wall_time),
                      "max_wall_time must be >= 0 (got {:g})", options.max_wall_time);
  const auto start = std::chrono::steady_clock::now();
  result::StaticResult out;
  try {
    const DeadlineScope deadline(options.max_wall_time);
    out = static_solver(scheme.id)(problem, options);
  } catch (const WallTimeExceeded& e) {
    out = result::StaticResult{};
    out.converged = false;
    out.reason = e.what();
  }
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.scheme = options.scheme;
  return out;
}

result::StaticResult solve_static(const scene::Scene& scene, const StaticSolveOptions& options) {
  return solve_static(StaticProblem::from_scene(scene, options.time), options);
}

}  // namespace rodlab::solvers::statics
