#pragma once
// Single shooting for the statics BVP with an RKMK integrator: Newton on the base internal
// wrench Lambda(0) so that the tip conditions hold, started from the equilibrium of the
// undeformed rod (exact to first order in the loads). When that direct solve fails or is not
// trusted, a load continuation by multiple shooting of the same equations
// (multiple_shooting.hpp), and multiple shooting at the full load as the last resort.
#include <optional>
#include <span>
#include <vector>

#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/statics/rkmk.hpp"

namespace rodlab::solvers::statics {

struct ShootingOptions {
  int nodes = 50;
  double tol = 1e-10;
  int max_iterations = 50;
  /// Newton's first iterate Lambda(0) (the base's internal wrench [moment; force], body frame),
  /// instead of the rigid rod's: an equilibrium on a branch that the load continuation from the
  /// rest shape does not reach (a rod twisted through many turns between clamps whose poses
  /// alone do not say how many). The solve then keeps to that start: no load continuation.
  std::optional<Vector6> base_wrench_guess;
};

result::StaticResult solve_shooting(const StaticProblem& problem, RkmkMethod method,
                                    const ShootingOptions& options);

/// Lambda(0) of the undeformed rod in equilibrium with the loads (marching (2.34) back from
/// the tip with xi = xi*, `steps` RK4 steps, at least 4): the shooting's initial guess.
Vector6 rigid_base_wrench(const StaticProblem& problem, int steps);

/// The same equilibrium at the ascending arclengths s in [0, L] (the march is split there):
/// the collocation schemes' initial guess. Zero for a clamped tip.
std::vector<Vector6> rigid_wrench_profile(const StaticProblem& problem, std::span<const double> s,
                                          int steps);

}  // namespace rodlab::solvers::statics
