#include "rodlab/scene/trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rodlab::scene {

std::pair<Vector3, Vector3> circle_axes(const Vector3& normal) {
  const Vector3 n = normal.normalized();
  const Vector3 reference = std::abs(n.x()) > std::numbers::sqrt2 / 2.0 ? Vector3::UnitY()
                                                                        : Vector3::UnitX();
  const Vector3 e1 = (reference - reference.dot(n) * n).normalized();
  return {e1, n.cross(e1)};
}

Vector3 position(const CircleTrajectory& circle, double t) {
  const auto [e1, e2] = circle_axes(circle.normal);
  const double phi = 2.0 * std::numbers::pi * std::clamp(t, 0.0, duration(circle)) / circle.period;
  return circle.center + circle.radius * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

Vector3 position(const Trajectory& trajectory, double t) { return position(trajectory.circle, t); }

double duration(const CircleTrajectory& circle) { return circle.laps * circle.period; }

double duration(const Trajectory& trajectory) { return duration(trajectory.circle); }

}  // namespace rodlab::scene
