#include "studies/fit.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace rodlab::validation::study {

double rounding_floor(double scale) {
  return kRoundingFactor * std::numeric_limits<double>::epsilon() * scale;
}

OrderFit fit_order(const std::vector<FitPoint>& points, double floor) {
  OrderFit fit;
  fit.used.assign(points.size(), false);
  std::vector<std::size_t> idx;
  int rounding = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& p = points[i];
    if (!p.usable || !std::isfinite(p.error) || !(p.h > 0.0)) continue;
    if (p.error <= floor) {
      ++rounding;
      continue;
    }
    idx.push_back(i);
  }
  // Coarse to fine; equal steps keep their input order.
  std::stable_sort(idx.begin(), idx.end(),
                   [&](std::size_t a, std::size_t b) { return points[a].h > points[b].h; });
  auto local_order = [&](std::size_t a, std::size_t b) {
    return std::log(points[a].error / points[b].error) / std::log(points[a].h / points[b].h);
  };
  int dropped = 0;
  while (idx.size() > 3) {
    std::vector<double> finer;
    for (std::size_t k = 1; k + 1 < idx.size(); ++k)
      finer.push_back(local_order(idx[k], idx[k + 1]));
    std::nth_element(finer.begin(), finer.begin() + static_cast<long>(finer.size() / 2),
                     finer.end());
    const double med = finer[finer.size() / 2];
    const double first = local_order(idx[0], idx[1]);
    if (std::isfinite(first) && std::abs(first - med) <= kPreasymptoticTolerance * std::abs(med))
      break;
    idx.erase(idx.begin());
    ++dropped;
  }
  std::string note;
  if (rounding > 0) note += std::to_string(rounding) + " at the rounding level";
  if (dropped > 0)
    note += std::string(note.empty() ? "" : ", ") + std::to_string(dropped) + " pre-asymptotic";
  if (!note.empty()) note = "left out: " + note;
  if (idx.size() < 2 || points[idx.front()].h == points[idx.back()].h) {
    fit.note = "too few points above the rounding level" + (note.empty() ? "" : "; " + note);
    return fit;
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(idx.size());
  for (const auto i : idx) {
    const double x = std::log(points[i].h), y = std::log(points[i].error);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    fit.used[i] = true;
  }
  fit.order = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  fit.points = static_cast<int>(idx.size());
  fit.note = note;
  return fit;
}

}  // namespace rodlab::validation::study
