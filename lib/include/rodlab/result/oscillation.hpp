#pragma once
// Reading an oscillation off a sampled signal (the validation report and the dynamics tests
// measure the first bending period of a released cantilever this way).
#include <cmath>
#include <limits>
#include <vector>

namespace rodlab::result {

/// Mean period of the signal x(t) from its upward crossings of its own mean (linear
/// interpolation between samples); NaN with fewer than two crossings.
inline double mean_period(const std::vector<double>& t, const std::vector<double>& x) {
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(x.size());
  std::vector<double> crossings;
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i - 1] < mean && x[i] >= mean)
      crossings.push_back(t[i - 1] + (mean - x[i - 1]) / (x[i] - x[i - 1]) * (t[i] - t[i - 1]));
  if (crossings.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

}  // namespace rodlab::result
