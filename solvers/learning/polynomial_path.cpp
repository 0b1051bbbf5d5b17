#include "rodlab/solvers/learning/polynomial_path.hpp"

#include <cmath>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {

PolynomialPath::PolynomialPath(const Vector3& p0, const Vector3& v0, const Vector3& p1,
                               const Vector3& v1, double T)
    : p0_(p0), v0_(v0), p1_(p1), T_(T) {
  RODLAB_THROW_UNLESS(std::isfinite(T) && T > 0.0, "polynomial path: duration must be > 0 (got {:g})",
                      T);
  const Vector3 D = p1 - p0 - v0 * T, E = v1 - v0;  // (header)
  c3_ = (4.0 * D - E * T) / (T * T * T);
  c4_ = (E * T - 3.0 * D) / (T * T * T * T);
}

Vector3 PolynomialPath::position(double t) const {
  if (t <= 0.0) return p0_;
  if (t >= T_) return p1_;
  return p0_ + t * (v0_ + t * t * (c3_ + t * c4_));
}

Vector3 PolynomialPath::velocity(double t) const {
  if (t < 0.0 || t > T_) return Vector3::Zero();
  return v0_ + t * t * (3.0 * c3_ + 4.0 * t * c4_);
}

}  // namespace rodlab::solvers::learning
