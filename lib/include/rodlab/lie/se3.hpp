#pragma once
// SE(3): rigid transformations g = [R p; 0 1] (1.1), twists xi = [omega; nu] (1.5) and wrenches
// W = [moment; force], both as 6-vectors with the angular part first, as in the thesis.
//
// Conventions (docs/conventions.md, tested in tests/lie):
//   hat(xi) = [hat(omega) nu; 0 0]                         (1.5)
//   ad_xi   = [W 0; V W],  W = hat(omega), V = hat(nu)     (1.10)
//   Ad_g    = [R 0; hat(p) R  R]                           (1.13)
//   coadjoint: ad_xi^T and Ad_g^T map wrenches             (1.19), (2.34)
//   dexp_xi = sum_k ad_xi^k/(k+1)!, d/ds exp(x) = (dexp_x x')^ exp(x)   (2.71)
//           = [A 0; B A], A = so3::dexp(omega),
//             B = b V + c (WV + VW) + (omega . nu)(d1 W + d2 W^2)      (2.72), corrected
//   dexp^-1_xi = [A^-1 0; C A^-1],
//             C = -V/2 + e (WV + VW) + (omega . nu) f W^2
// B and C are the directional derivatives of A(W) and A(W)^-1 along V (the lower block of any
// power series in ad_xi is the Frechet derivative of the same series in W along V).
#include <utility>

#include <Eigen/Core>

#include "rodlab/lie/so3.hpp"

namespace rodlab::lie {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Matrix4 = Eigen::Matrix4d;

namespace se3 {

inline Vector3 angular(const Vector6& x) { return x.head<3>(); }
inline Vector3 linear(const Vector6& x) { return x.tail<3>(); }
inline Vector6 join(const Vector3& angular_part, const Vector3& linear_part) {
  Vector6 x;  // fixed-size block writes (a comma initializer would go through dynamic blocks)
  x.head<3>() = angular_part;
  x.tail<3>() = linear_part;
  return x;
}

/// (1.5): xi -> 4x4 matrix.
inline Matrix4 hat(const Vector6& xi) {
  Matrix4 X = Matrix4::Zero();
  X.topLeftCorner<3, 3>() = so3::hat(xi.head<3>());
  X.topRightCorner<3, 1>() = xi.tail<3>();
  return X;
}

/// Inverse of hat; reads the skew part of the rotation block.
inline Vector6 vee(const Matrix4& X) {
  return join(so3::vee(X.topLeftCorner<3, 3>()), X.topRightCorner<3, 1>());
}

/// (1.10): ad_xi = [W 0; V W]; ad_a b = [a^, b^] (1.8).
inline Matrix6 ad(const Vector6& xi) {
  Matrix6 A = Matrix6::Zero();
  const Matrix3 W = so3::hat(xi.head<3>());
  A.topLeftCorner<3, 3>() = W;
  A.bottomRightCorner<3, 3>() = W;
  A.bottomLeftCorner<3, 3>() = so3::hat(xi.tail<3>());
  return A;
}

/// ad_xi y without forming the matrix: [w x y_w; v x y_w + w x y_v].
inline Vector6 ad_apply(const Vector6& xi, const Vector6& y) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 yw = y.head<3>(), yv = y.tail<3>();
  return join(w.cross(yw), v.cross(yw) + w.cross(yv));
}

/// Coadjoint ad_xi^T lambda for a wrench lambda = [m; f]: [m x w + f x v; f x w].
inline Vector6 coad_apply(const Vector6& xi, const Vector6& lambda) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 m = lambda.head<3>(), f = lambda.tail<3>();
  return join(m.cross(w) + f.cross(v), f.cross(w));
}

/// dexp_xi y (see the header comment), without forming a matrix.
inline Vector6 dexp_apply(const Vector6& xi, const Vector6& y) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 yw = y.head<3>(), yv = y.tail<3>();
  const double t = w.norm();
  const double b = coefficients::b(t), c = coefficients::c(t);
  const Vector3 w_yw = w.cross(yw);
  const Vector3 top = yw + b * w_yw + c * w.cross(w_yw);
  const Vector3 A_yv = yv + b * w.cross(yv) + c * w.cross(w.cross(yv));
  const Vector3 v_yw = v.cross(yw);
  const Vector3 B_yw = b * v_yw + c * (w.cross(v_yw) + v.cross(w_yw)) +
                       w.dot(v) * (coefficients::d1(t) * w_yw + coefficients::d2(t) * w.cross(w_yw));
  return join(top, B_yw + A_yv);
}

/// dexp_xi^T lambda for a wrench lambda = [m; f], without forming a matrix: with dexp_xi =
/// [A 0; B A] its transpose is [A^T B^T; 0 A^T], and A^T = A(-omega), B^T = B(-xi) (A even in
/// nothing but omega's sign, B odd; see dexp_apply). The inverse of dexp_inv_transpose_apply:
/// the stress sigma from the discrete stress lambda of (3.40).
inline Vector6 dexp_transpose_apply(const Vector6& xi, const Vector6& lambda) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 m = lambda.head<3>(), f = lambda.tail<3>();
  const double t = w.norm();
  const double b = coefficients::b(t), c = coefficients::c(t);
  const Vector3 w_m = w.cross(m), w_f = w.cross(f), v_f = v.cross(f);
  const Vector3 AT_m = m - b * w_m + c * w.cross(w_m);
  const Vector3 AT_f = f - b * w_f + c * w.cross(w_f);
  const Vector3 BT_f = -b * v_f + c * (w.cross(v_f) + v.cross(w_f)) +
                       w.dot(v) * (-coefficients::d1(t) * w_f + coefficients::d2(t) * w.cross(w_f));
  return join(AT_m + BT_f, AT_f);
}

/// dexp^-1_xi y, valid for |omega| < 2 pi, without forming a matrix.
inline Vector6 dexp_inv_apply(const Vector6& xi, const Vector6& y) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 yw = y.head<3>(), yv = y.tail<3>();
  const double t = w.norm();
  const double e = coefficients::e(t);
  const Vector3 w_yw = w.cross(yw);
  const Vector3 top = yw - 0.5 * w_yw + e * w.cross(w_yw);
  const Vector3 Ainv_yv = yv - 0.5 * w.cross(yv) + e * w.cross(w.cross(yv));
  const Vector3 v_yw = v.cross(yw);
  const Vector3 C_yw = -0.5 * v_yw + e * (w.cross(v_yw) + v.cross(w_yw)) +
                       w.dot(v) * coefficients::f(t) * w.cross(w_yw);
  return join(top, C_yw + Ainv_yv);
}

/// dexp^-T_xi lambda for a wrench lambda, without forming a matrix: the discrete conjugate
/// momentum and stress of the variational integrator ((3.40), (3.42)). With dexp^-1 = [A^-1 0;
/// C A^-1], its transpose is [A^-T C^T; 0 A^-T], A^-T = I + W/2 + e W^2,
/// C^T = V/2 + e (W V + V W) + (w.v) f W^2.
inline Vector6 dexp_inv_transpose_apply(const Vector6& xi, const Vector6& lambda) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 m = lambda.head<3>(), f = lambda.tail<3>();
  const double t = w.norm();
  const double e = coefficients::e(t);
  const Vector3 w_m = w.cross(m), w_f = w.cross(f), v_f = v.cross(f);
  const Vector3 AinvT_m = m + 0.5 * w_m + e * w.cross(w_m);
  const Vector3 AinvT_f = f + 0.5 * w_f + e * w.cross(w_f);
  const Vector3 CT_f = 0.5 * v_f + e * (v.cross(w_f) + w.cross(v_f)) +
                       w.dot(v) * coefficients::f(t) * w.cross(w_f);
  return join(AinvT_m + CT_f, AinvT_f);
}

/// dexp_xi as a 6x6 matrix (closed form).
inline Matrix6 dexp(const Vector6& xi) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const double t = w.norm();
  const Matrix3 W = so3::hat(w), V = so3::hat(v), W2 = W * W;
  const double b = coefficients::b(t), c = coefficients::c(t);
  Matrix6 D;
  const Matrix3 A = Matrix3::Identity() + b * W + c * W2;
  D.topLeftCorner<3, 3>() = A;
  D.topRightCorner<3, 3>().setZero();
  D.bottomRightCorner<3, 3>() = A;
  D.bottomLeftCorner<3, 3>() =
      b * V + c * (W * V + V * W) + w.dot(v) * (coefficients::d1(t) * W + coefficients::d2(t) * W2);
  return D;
}

/// dexp^-1_xi as a 6x6 matrix (closed form), valid for |omega| < 2 pi.
inline Matrix6 dexp_inv(const Vector6& xi) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const double t = w.norm();
  const Matrix3 W = so3::hat(w), V = so3::hat(v), W2 = W * W;
  const double e = coefficients::e(t);
  Matrix6 D;
  const Matrix3 Ainv = Matrix3::Identity() - 0.5 * W + e * W2;
  D.topLeftCorner<3, 3>() = Ainv;
  D.topRightCorner<3, 3>().setZero();
  D.bottomRightCorner<3, 3>() = Ainv;
  D.bottomLeftCorner<3, 3>() = -0.5 * V + e * (W * V + V * W) + w.dot(v) * coefficients::f(t) * W2;
  return D;
}

/// h -> ad_h^T s as a matrix: coad_matrix([m; f]) = [[m^, f^], [f^, 0]] (ad_h^T s =
/// coad_matrix(s) h; the linearisation of a wrench moved by a perturbed twist).
inline Matrix6 coad_matrix(const Vector6& s) {
  Matrix6 out = Matrix6::Zero();
  out.topLeftCorner<3, 3>() = so3::hat(s.head<3>());
  out.topRightCorner<3, 3>() = so3::hat(s.tail<3>());
  out.bottomLeftCorner<3, 3>() = so3::hat(s.tail<3>());
  return out;
}

/// h -> DT(y)[h] r, the derivative of T(y) = dexp^-1_y = I - ad_y / 2 + ad_y^2 / 12 - ...
/// applied to r, to the ad^2 term: ad_r h / 2 - (ad_{ad_y r} + ad_y ad_r) h / 12 (relative
/// truncation growing as |y|^3; tests/dynamics/test_segment_linearisation.cpp).
inline Matrix6 dexp_inv_derivative(const Vector6& y, const Vector6& r) {
  return 0.5 * ad(r) - (ad(ad_apply(y, r)) + ad(y) * ad(r)) / 12.0;
}

/// h -> (DT(x)[h])^T s to the same order: -coad_matrix(s) h / 2 + (ad_x^T coad_matrix(s) +
/// coad_matrix(ad_x^T s)) h / 12.
inline Matrix6 dexp_inv_transpose_derivative(const Vector6& x, const Vector6& s) {
  const Matrix6 adxT = ad(x).transpose();
  const Matrix6 Ss = coad_matrix(s);
  return -0.5 * Ss + (adxT * Ss + coad_matrix(adxT * s)) / 12.0;
}

/// Truncated series of order q (terms k = 0..q): sum_k ad_xi^k / (k+1)!  (for RKMK).
inline Vector6 dexp_series_apply(const Vector6& xi, const Vector6& y, int q) {
  Vector6 term = y, sum = coefficients::kInverseFactorialShifted[0] * y;
  for (int k = 1; k <= q; ++k) {
    term = ad_apply(xi, term);
    sum += coefficients::kInverseFactorialShifted[k] * term;
  }
  return sum;
}

/// Truncated series of order q: sum_k B_k/k! ad_xi^k (B_1 = -1/2). q = 0 gives the identity,
/// q = 2 gives I - ad/2 + ad^2/12, enough for a 4th-order RKMK method (q >= p - 2).
inline Vector6 dexp_inv_series_apply(const Vector6& xi, const Vector6& y, int q) {
  Vector6 term = y, sum = y;
  for (int k = 1; k <= q; ++k) {
    term = ad_apply(xi, term);
    const double beta = coefficients::kBernoulliOverFactorial[k];
    if (beta != 0.0) sum += beta * term;
  }
  return sum;
}

/// Matrix forms of the truncated series (for Jacobians and tests).
inline Matrix6 dexp_series(const Vector6& xi, int q) {
  const Matrix6 A = ad(xi);
  Matrix6 term = Matrix6::Identity(), sum = Matrix6::Identity();
  for (int k = 1; k <= q; ++k) {
    term = term * A;
    sum += coefficients::kInverseFactorialShifted[k] * term;
  }
  return sum;
}
inline Matrix6 dexp_inv_series(const Vector6& xi, int q) {
  const Matrix6 A = ad(xi);
  Matrix6 term = Matrix6::Identity(), sum = Matrix6::Identity();
  for (int k = 1; k <= q; ++k) {
    term = term * A;
    sum += coefficients::kBernoulliOverFactorial[k] * term;
  }
  return sum;
}

}  // namespace se3

class SE3 {
 public:
  SE3() : R_(), p_(Vector3::Zero()) {}
  SE3(const SO3& R, const Vector3& p) : R_(R), p_(p) {}

  static SE3 identity() { return SE3(); }
  static SE3 translation(const Vector3& p) { return SE3(SO3(), p); }
  /// From a 4x4 homogeneous matrix whose rotation block is orthonormal.
  static SE3 from_matrix(const Matrix4& g) {
    return SE3(SO3::from_matrix(g.topLeftCorner<3, 3>()), g.topRightCorner<3, 1>());
  }

  /// exp(xi^) = [exp(w^)  dexp_w nu; 0 1].
  static SE3 exp(const Vector6& xi) {
    const Vector3 w = xi.head<3>();
    return SE3(SO3::exp(w), so3::dexp_apply(w, xi.tail<3>()));
  }

  /// log: omega = log R (|omega| <= pi), nu = dexp^-1_omega p.
  Vector6 log() const {
    const Vector3 w = R_.log();
    return se3::join(w, so3::dexp_inv_apply(w, p_));
  }

  const SO3& rotation() const { return R_; }
  const Vector3& translation() const { return p_; }
  Matrix3 rotation_matrix() const { return R_.matrix(); }

  Matrix4 matrix() const {
    Matrix4 g = Matrix4::Identity();
    g.topLeftCorner<3, 3>() = R_.matrix();
    g.topRightCorner<3, 1>() = p_;
    return g;
  }

  SE3 inverse() const {
    const SO3 Rt = R_.inverse();
    return SE3(Rt, -(Rt * p_));
  }

  SE3 operator*(const SE3& other) const { return SE3(R_ * other.R_, p_ + R_ * other.p_); }
  /// inverse() * other, with one rotation fewer: (R^T R_o, R^T (p_o - p)).
  SE3 inverse_times(const SE3& other) const {
    const SO3 Rt = R_.inverse();
    return SE3(Rt * other.R_, Rt * Vector3(other.p_ - p_));
  }
  SE3& operator*=(const SE3& other) { return *this = *this * other; }

  /// Acts on a point: R x + p.
  Vector3 operator*(const Vector3& x) const { return R_ * x + p_; }

  /// (1.13): Ad_g = [R 0; hat(p) R  R].
  Matrix6 Ad() const {
    const Matrix3 R = R_.matrix();
    Matrix6 A;
    A.topLeftCorner<3, 3>() = R;
    A.topRightCorner<3, 3>().setZero();
    A.bottomLeftCorner<3, 3>() = so3::hat(p_) * R;
    A.bottomRightCorner<3, 3>() = R;
    return A;
  }

  /// Ad_g xi = [R w; p x (R w) + R v] (transforms a twist, (1.17)).
  Vector6 Ad_apply(const Vector6& xi) const {
    const Vector3 Rw = R_ * Vector3(xi.head<3>());
    return se3::join(Rw, p_.cross(Rw) + R_ * Vector3(xi.tail<3>()));
  }

  /// Ad_g^T W = [R^T (m - p x f); R^T f] (transforms a wrench, (1.19), (2.35)).
  [[gnu::always_inline]] Vector6 coAd_apply(const Vector6& W) const {
    const SO3 Rt = R_.inverse();
    const Vector3 f = W.tail<3>();
    return se3::join(Rt * (Vector3(W.head<3>()) - p_.cross(f)), Rt * f);
  }

  /// Jacobians of c = a * b for right perturbations a exp(da), b exp(db), c exp(dc):
  /// dc/da = Ad_{b^-1}, dc/db = I.
  SE3 compose(const SE3& b, Matrix6* J_c_a, Matrix6* J_c_b) const {
    if (J_c_a) *J_c_a = b.inverse().Ad();
    if (J_c_b) J_c_b->setIdentity();
    return *this * b;
  }
  /// Jacobian of g^-1 for right perturbations: -Ad_g.
  SE3 inverse(Matrix6* J_inv_g) const {
    if (J_inv_g) *J_inv_g = -Ad();
    return inverse();
  }

 private:
  SO3 R_;
  Vector3 p_;
};

/// The two adjoint maps of a segment's G = (R, p) that a march applies to every node, with R
/// formed once as a matrix: SE3's own maps rotate each 3-vector with the quaternion, which
/// GCC keeps out of line (a fifth of the staggered shooting step; the semi-discrete rod's rhs,
/// bench_dynamics; forced inline: out of line the collocation step was 5 % slower). Equal to
/// G.inverse().Ad_apply and G.coAd_apply to rounding (tests/lie). R is kept, not R^T: the
/// combined map's R^T * columns then rounds as the march did before this class (a stored R^T
/// multiplies in another order: the staggered tip series changed in their last bits); the
/// single maps copy R^T into a local, which GCC keeps in registers (R_.transpose() * v went out
/// of line).
class SE3Adjoints {
 public:
  explicit SE3Adjoints(const SE3& g)
      : R_(g.rotation_matrix()), p_(g.translation()) {}
  /// Ad_{g^-1} xi = [R^T w; R^T (v - p x w)] (a twist of the far frame in the near one).
  [[gnu::always_inline]] Vector6 inverse_Ad_apply(const Vector6& xi) const {
    const Vector3 w = xi.head<3>();
    const Matrix3 Rt = R_.transpose();
    return se3::join(Rt * w, Rt * Vector3(xi.tail<3>() - p_.cross(w)));
  }
  /// Ad_g^T W = [R^T (m - p x f); R^T f] (SE3::coAd_apply).
  [[gnu::always_inline]] Vector6 coAd_apply(const Vector6& W) const {
    const Vector3 f = W.tail<3>();
    const Matrix3 Rt = R_.transpose();
    return se3::join(Rt * Vector3(W.head<3>() - p_.cross(f)), Rt * f);
  }
  /// Both, Ad_{g^-1} xi and Ad_g^T W, as one 3 x 4 product with R^T (where both vectors are at
  /// hand: the staggered shooting march).
  [[gnu::always_inline]] std::pair<Vector6, Vector6> inverse_Ad_and_coAd_apply(
      const Vector6& xi, const Vector6& W) const {
    Eigen::Matrix<double, 3, 4> columns;
    columns << xi.head<3>(), xi.tail<3>() - p_.cross(Vector3(xi.head<3>())),
        W.head<3>() - p_.cross(Vector3(W.tail<3>())), W.tail<3>();
    const Eigen::Matrix<double, 3, 4> rotated = R_.transpose() * columns;
    return {se3::join(rotated.col(0), rotated.col(1)), se3::join(rotated.col(2), rotated.col(3))};
  }

 private:
  Matrix3 R_;
  Vector3 p_;
};

namespace se3 {
/// Right Jacobian of exp: exp(xi + d) = exp(xi) exp(dexp_{-xi} d + O(d^2)).
inline Matrix6 right_jacobian(const Vector6& xi) { return dexp(-xi); }
/// Left Jacobian of exp: exp(xi + d) = exp(dexp_xi d + O(d^2)) exp(xi).
inline Matrix6 left_jacobian(const Vector6& xi) { return dexp(xi); }
}  // namespace se3

}  // namespace rodlab::lie
