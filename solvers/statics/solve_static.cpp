#include "rodlab/solvers/statics/solve_static.hpp"

#include <chrono>
#include <stdexcept>

#include "rodlab/solvers/schemes.hpp"
#include "rodlab/solvers/statics/chebyshev.hpp"
#include "rodlab/solvers/statics/kinsol_collocation.hpp"
#include "rodlab/solvers/statics/shooting.hpp"

namespace rodlab::solvers::statics {
namespace {

std::optional<RkmkMethod> rkmk_method(const std::string& scheme) {
  if (scheme == "rkmk-euler-explicit") return RkmkMethod::euler_explicit;
  if (scheme == "rkmk-euler-implicit") return RkmkMethod::euler_implicit;
  if (scheme == "rkmk-midpoint-explicit") return RkmkMethod::midpoint_explicit;
  if (scheme == "rkmk-midpoint-implicit") return RkmkMethod::midpoint_implicit;
  if (scheme == "rkmk-rk4") return RkmkMethod::rk4;
  return std::nullopt;
}

}  // namespace

result::StaticResult solve_static(const StaticProblem& problem, const StaticSolveOptions& options) {
  const auto info = find_scheme(options.scheme);
  if (!info || info->problem != Problem::statics)
    throw std::invalid_argument("unknown statics scheme '" + options.scheme + "' (valid: " +
                                scheme_names(Problem::statics) + ")");
  if (options.nodes < 2) throw std::invalid_argument("nodes must be >= 2");
  const auto start = std::chrono::steady_clock::now();
  result::StaticResult out;
  if (const auto method = rkmk_method(options.scheme)) {
    out = solve_shooting(problem, *method, {options.nodes, options.tol, options.max_iterations});
  } else if (options.scheme == "chebyshev") {
    out = solve_chebyshev(problem, {options.nodes, options.tol, options.max_iterations});
  } else if (options.scheme == "kinsol") {
    KinsolCollocationOptions kinsol;
    kinsol.nodes = options.nodes;
    kinsol.tol = options.tol;
    kinsol.max_iterations = options.max_iterations;
    out = solve_kinsol_collocation(problem, kinsol);
  } else {
    throw std::invalid_argument("scheme '" + options.scheme + "' is not available yet; it arrives with " +
                                std::string(info->arrives));
  }
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.scheme = options.scheme;
  return out;
}

result::StaticResult solve_static(const scene::Scene& scene, const StaticSolveOptions& options) {
  return solve_static(StaticProblem::from_scene(scene, options.time), options);
}

}  // namespace rodlab::solvers::statics
