#pragma once
// The random trajectories of the learning task `track` (thesis 4.4.2: "pick a random starting
// and ending point and generate small random initial and final velocities then a fourth-order
// polynomial is fit to those values"). Four conditions do not fix the five coefficients of a
// quartic; the fifth here is a zero initial acceleration (the path leaves its start smoothly):
//
//   p(t) = p0 + v0 t + c3 t^3 + c4 t^4,   0 <= t <= T,
//   c3 = (4 D - E T) / T^3,   c4 = (E T - 3 D) / T^4,   D = p1 - p0 - v0 T,   E = v1 - v0,
//
// so that p(0) = p0, p'(0) = v0, p''(0) = 0, p(T) = p1, p'(T) = v1. Before 0 the path waits at
// p0, after T at p1 (velocity zero there; v0 at 0 and v1 at T).
#include "rodlab/lie/se3.hpp"

namespace rodlab::solvers::learning {

using lie::Vector3;

class PolynomialPath {
 public:
  /// Throws std::invalid_argument unless T > 0.
  PolynomialPath(const Vector3& p0, const Vector3& v0, const Vector3& p1, const Vector3& v1,
                 double T);
  Vector3 position(double t) const;
  Vector3 velocity(double t) const;
  double duration() const { return T_; }

 private:
  Vector3 p0_, v0_, c3_, c4_, p1_;
  double T_;
};

}  // namespace rodlab::solvers::learning
