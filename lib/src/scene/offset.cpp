#include <algorithm>

#include "rodlab/scene/scene.hpp"

namespace rodlab::scene {

// Constant for one point; otherwise linear in s between the points, clamped at both ends.
Vector2 Offset::at(double s) const {
  if (points.empty()) return Vector2::Zero();
  if (points.size() == 1 || s <= points.front().first) return points.front().second;
  if (s >= points.back().first) return points.back().second;
  // first point with s_k > s; the routing's s strictly increase (checked by the loader)
  const auto upper = std::upper_bound(points.begin(), points.end(), s,
                                      [](double x, const auto& p) { return x < p.first; });
  const auto& [s0, r0] = *(upper - 1);
  const auto& [s1, r1] = *upper;
  const double w = (s - s0) / (s1 - s0);
  return r0 + w * (r1 - r0);
}

}  // namespace rodlab::scene
