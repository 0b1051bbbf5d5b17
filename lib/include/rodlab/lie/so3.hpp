#pragma once
// SO(3): rotations, stored as a unit quaternion (renormalised on every composition, so det R
// and R^T R do not drift however many compositions are chained; see docs/conventions.md).
// Tangent vectors omega are in the body frame; hat/vee follow (1.4).
//
// dexp convention (thesis (2.71), (2.84); Iserles et al. 2000): for a curve x(s) in so(3),
//     d/ds exp(x) = (dexp_x x')^ exp(x)          (left-trivialised)
//     exp(x)^-1 d/ds exp(x) = (dexp_{-x} x')^     (right-trivialised),
// with dexp_x = sum_k ad_x^k / (k+1)! = I + b W + c W^2 (the "left Jacobian").
// dexp_{-x} is the "right Jacobian". dexp^-1_x = sum_k B_k/k! ad_x^k = I - W/2 + e W^2.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rodlab/lie/coefficients.hpp"

namespace rodlab::lie {

using Vector3 = Eigen::Vector3d;
using Matrix3 = Eigen::Matrix3d;
using Quaternion = Eigen::Quaterniond;

namespace so3 {

/// (1.4): omega -> the skew matrix with hat(a) b = a x b (1.6).
inline Matrix3 hat(const Vector3& w) {
  Matrix3 W;
  W << 0.0, -w.z(), w.y(),
       w.z(), 0.0, -w.x(),
       -w.y(), w.x(), 0.0;
  return W;
}

/// Inverse of hat; reads the skew-symmetric part (W - W^T)/2 so that it is exact on hat(w).
inline Vector3 vee(const Matrix3& W) {
  return 0.5 * Vector3(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1));
}

/// dexp_w y = y + b w x y + c w x (w x y), without forming a matrix.
inline Vector3 dexp_apply(const Vector3& w, const Vector3& y) {
  const double t = w.norm();
  const Vector3 wy = w.cross(y);
  return y + coefficients::b(t) * wy + coefficients::c(t) * w.cross(wy);
}

/// dexp^-1_w y = y - w x y / 2 + e w x (w x y); valid for |w| < 2 pi.
inline Vector3 dexp_inv_apply(const Vector3& w, const Vector3& y) {
  const double t = w.norm();
  const Vector3 wy = w.cross(y);
  return y - 0.5 * wy + coefficients::e(t) * w.cross(wy);
}

/// dexp_w = I + b(t) W + c(t) W^2 (thesis (2.72) with the ad coefficient b, see conventions).
inline Matrix3 dexp(const Vector3& w) {
  const double t = w.norm();
  const Matrix3 W = hat(w);
  return Matrix3::Identity() + coefficients::b(t) * W + coefficients::c(t) * W * W;
}

/// dexp^-1_w = I - W/2 + e(t) W^2, the inverse of dexp(w) for |w| < 2 pi.
inline Matrix3 dexp_inv(const Vector3& w) {
  const double t = w.norm();
  const Matrix3 W = hat(w);
  return Matrix3::Identity() - 0.5 * W + coefficients::e(t) * W * W;
}

}  // namespace so3

class SO3 {
 public:
  SO3() : q_(Quaternion::Identity()) {}

  static SO3 identity() { return SO3(); }

  /// exp(w^): q = (cos(t/2), sin(t/2)/t w). No cancellation anywhere, exact for large t.
  static SO3 exp(const Vector3& w) {
    const double half = 0.5 * w.norm();
    double c, s;  // cos(half), sin(half)/half
    coefficients::cos_sinc(half, c, s);
    return exp_from_half_angle(c, s, w);
  }
  /// exp(w^) from cos(t/2) and sin(t/2)/(t/2), t = |w|, computed by the caller (the small-angle
  /// kernels of small_angle.hpp evaluate them from t^2 without a square root).
  static SO3 exp_from_half_angle(double cos_half, double sinc_half, const Vector3& w) {
    const Vector3 v = 0.5 * sinc_half * w;
    return SO3(Quaternion(cos_half, v.x(), v.y(), v.z()), Unchecked{});
  }

  /// From a rotation matrix (assumed orthonormal with det +1; Eigen uses Shepperd's method).
  static SO3 from_matrix(const Matrix3& R) { return from_quaternion(Quaternion(R)); }

  /// From a quaternion of unit norm to rounding (as operator* leaves its product), kept as it
  /// is: the packed kernels of the variational step compose rotations themselves.
  static SO3 from_unit_quaternion(const Quaternion& q) { return SO3(q, Unchecked{}); }

  /// From any non-zero quaternion; it is normalised.
  static SO3 from_quaternion(const Quaternion& q) { return SO3(q.normalized(), Unchecked{}); }

  /// log: the rotation vector with |w| in [0, pi]. theta = 2 atan2(|v|, w) with w >= 0 is
  /// well conditioned everywhere, including near 0 and near pi.
  Vector3 log() const {
    const double sign = q_.w() < 0.0 ? -1.0 : 1.0;
    const double w = sign * q_.w();
    const Vector3 v = sign * q_.vec();
    const double n = v.norm();
    double scale;  // theta / n
    if (n < 1e-8) {
      // atan(x)/x = 1 - x^2/3 + ..., x = n/w <= 1e-8 (w ~ 1 here), exact to eps.
      scale = 2.0 / w * (1.0 - n * n / (3.0 * w * w));
    } else {
      scale = 2.0 * std::atan2(n, w) / n;
    }
    return scale * v;
  }

  Matrix3 matrix() const { return q_.toRotationMatrix(); }
  const Quaternion& quaternion() const { return q_; }

  SO3 inverse() const { return SO3(q_.conjugate(), Unchecked{}); }

  /// Composition; the product quaternion is pulled back onto the unit sphere with the
  /// first-order correction q (3 - |q|^2) / 2 (|q|^2 - 1 is O(eps), so the dropped term is
  /// O(eps^2); no division, which mattered in the explicit integrator's step).
  SO3 operator*(const SO3& other) const {
    Quaternion q = q_ * other.q_;
    const double n2 = q.squaredNorm();
    q.coeffs() *= 1.5 - 0.5 * n2;
    return SO3(q, Unchecked{});
  }
  SO3& operator*=(const SO3& other) { return *this = *this * other; }

  /// Rotates a vector: R v.
  Vector3 operator*(const Vector3& v) const { return q_ * v; }

  /// Ad_R = R (1.12).
  Matrix3 Ad() const { return matrix(); }

 private:
  struct Unchecked {};
  SO3(const Quaternion& q, Unchecked) : q_(q) {}
  Quaternion q_;
};

}  // namespace rodlab::lie
