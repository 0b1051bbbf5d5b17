#pragma once
// Where a straight equilibrium bifurcates, measured with a statics scheme (docs/validation.md
// "literature"): the rod is loaded by lambda and nudged by a small imperfection h; its linear
// compliance c(lambda) = deflection / h has a simple pole at the critical load, so the stiffness
// 1 / c is analytic there and crosses zero. The measurement stays below the critical load (above
// it, load continuation from the straight rod would follow the buckled branch), fits a quadratic
// through the last three stiffnesses and moves towards its root: at 0.7, 0.8 and 0.9 of the
// guess, then half-way from the last load to each new estimate, until the gap is below 1e-3 of
// it (the last three points then lie within about 1 % of the root, where the quadratic's error
// is far below 1e-6; measured in docs/validation.md). The imperfection is scaled so that
// every deflection is about `deflection_target` (small enough that the response is linear to
// about its square, large enough to stand above the solver's tolerance).
#include <functional>
#include <optional>
#include <vector>

namespace rodlab::validation {

struct BifurcationPoint {
  double load = 0.0;
  double stiffness = 0.0;  ///< h / deflection
};

struct BifurcationLoad {
  double load = 0.0;                     ///< the critical load (root of the last quadratic)
  std::vector<BifurcationPoint> points;  ///< every measurement, in order
  bool ok = false;                       ///< every solve converged
};

/// `deflection(lambda, h)`: the response to load lambda with imperfection h, or nothing when the
/// solve did not converge.
BifurcationLoad bifurcation_load(
    const std::function<std::optional<double>(double lambda, double h)>& deflection, double guess,
    double deflection_target);

}  // namespace rodlab::validation
