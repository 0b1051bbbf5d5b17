#pragma once
// Time schedules for actuator inputs and tip wrenches (interface spec section 3):
//   a constant, {steps: [[t0, v0], [t1, v1], ...]} (piecewise constant, v_k on [t_k, t_k+1)),
//   {ramp: [[t0, v0], [t1, v1], ...]} (piecewise linear).
// Before t0 the value is v0; after the last time it is the last value. Times never decrease;
// a ramp may repeat a time to jump.
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace rodlab::scene {

template <class Value>
class Schedule {
 public:
  enum class Kind { constant, steps, ramp };

  Schedule() : Schedule(Value{}) {}
  /* implicit */ Schedule(const Value& v) : kind_(Kind::constant), points_{{0.0, v}} {}
  Schedule(Kind kind, std::vector<std::pair<double, Value>> points)
      : kind_(kind), points_(std::move(points)) {}

  Kind kind() const { return kind_; }
  bool is_constant() const { return kind_ == Kind::constant; }
  const std::vector<std::pair<double, Value>>& points() const { return points_; }

  Value at(double t) const {
    if (kind_ == Kind::constant || t <= points_.front().first) return points_.front().second;
    if (t >= points_.back().first) return points_.back().second;
    // last k with t_k <= t
    std::size_t k = 0;
    while (k + 1 < points_.size() && points_[k + 1].first <= t) ++k;
    if (kind_ == Kind::steps) return points_[k].second;
    const auto& [t0, v0] = points_[k];
    const auto& [t1, v1] = points_[k + 1];
    const double w = (t - t0) / (t1 - t0);
    return Value(v0 + w * (v1 - v0));
  }

 private:
  Kind kind_;
  std::vector<std::pair<double, Value>> points_;
};

using ScalarSchedule = Schedule<double>;
using VectorSchedule = Schedule<Eigen::Vector3d>;

}  // namespace rodlab::scene
