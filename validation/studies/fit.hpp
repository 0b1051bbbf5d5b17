#pragma once
// The observed order of a convergence sequence: the least-squares slope of log(error) against
// log(h) (h = L / (N - 1) for a refinement in nodes, h = dt for one in time) on its asymptotic
// range. The rule (docs/studies.md "Order fit"):
//   1. only converged runs with a finite error above the rounding level,
//      error > kRoundingFactor * eps * scale (scale: the rod length or the reference tip
//      distance from the origin, whichever is larger), take part;
//   2. the points are sorted from coarse to fine; while more than three remain and the local
//      order of the coarsest pair differs from the median of the finer local orders by more
//      than kPreasymptoticTolerance (relative), the coarsest point is dropped (pre-asymptotic);
//   3. with at least two points left, the slope of the least-squares line is the order.
#include <limits>
#include <string>
#include <vector>

namespace rodlab::validation::study {

inline constexpr double kRoundingFactor = 1e3;
inline constexpr double kPreasymptoticTolerance = 0.2;

struct FitPoint {
  double h = 0.0;      ///< step (ds or dt) > 0
  double error = 0.0;  ///< error >= 0
  bool usable = true;  ///< converged and measured
};

struct OrderFit {
  double order = std::numeric_limits<double>::quiet_NaN();  ///< NaN: no fit
  std::vector<bool> used;                                   ///< per input point
  int points = 0;
  std::string note;  ///< why there is no fit, or what was dropped
};

/// `floor`: the rounding level (errors at or below it are left out).
OrderFit fit_order(const std::vector<FitPoint>& points, double floor);

/// kRoundingFactor * eps * scale.
double rounding_floor(double scale);

}  // namespace rodlab::validation::study
