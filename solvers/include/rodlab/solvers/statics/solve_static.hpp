#pragma once
// One entry point for every statics scheme, by its name in the spec (rodlab schemes).
#include <string>

#include "rodlab/result/static_result.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/statics/static_problem.hpp"

namespace rodlab::solvers::statics {

struct StaticSolveOptions {
  std::string scheme = "rkmk-rk4";
  int nodes = 50;
  double tol = 1e-10;
  int max_iterations = 50;
  double time = 0.0;  ///< scene overload: actuator and tip-wrench schedules are evaluated here
  /// Wall-time guard [s] (common/deadline.hpp): the solve stops, not converged, once it has
  /// taken longer; 0: none.
  double max_wall_time = 0.0;
};

/// Solves and times one static equilibrium. Throws std::invalid_argument for an unknown or not
/// yet available scheme, or nodes < 2; non-convergence is reported in the result.
result::StaticResult solve_static(const StaticProblem& problem, const StaticSolveOptions& options);
result::StaticResult solve_static(const scene::Scene& scene, const StaticSolveOptions& options);

}  // namespace rodlab::solvers::statics
