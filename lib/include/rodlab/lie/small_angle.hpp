#pragma once
// Small-angle SE(3) kernels for explicit integrators (the `variational` scheme steps every node
// and segment with rotation angles far below 0.25 rad: dt |omega| ~ 1e-5..1e-3, ds |kappa| ~
// 1e-3..1e-1). They compute the same quantities as SE3::exp, SE3::log and
// se3::dexp_inv_transpose_apply, to rounding, but cheaper:
//   - the coefficient functions c, e, f (coefficients.hpp) are short Taylor series in t^2
//     (6-7 terms below kSmallAngle, 3-4 terms below kTinyAngle), taken from t^2 without the
//     sqrt and inlined (the general functions have short branches of 6-8 terms below
//     coefficients::kShortSwitch = 0.25 too, then 12-, 22- and 50-term series up to their switch
//     points); the first dropped term is below 1e-17 relative at the bound (checked in
//     tests/lie/test_small_angle.cpp against the general functions to 2 eps);
//   - log uses atan(x)/x as a 9-term series in x^2 = tan^2(theta/2) instead of atan2, and no sqrt;
//   - log_with_coefficients returns e and f of the segment's own angle, so a scheme that needs
//     both log(G) and dexp^-T_{log G} evaluates them once.
// Above the bounds every function falls back to the general one (same result to rounding).
#include <array>

#include "rodlab/lie/coefficients.hpp"
#include "rodlab/lie/se3.hpp"

namespace rodlab::lie::small_angle {

/// |omega| below which the short series are used.
inline constexpr double kSmallAngle = 0.25;
/// |omega| below which the shortest e, f series are used (Newton on (3.42): dt |omega| ~ 1e-4).
inline constexpr double kTinyAngle = 0.01;

namespace detail {
template <std::size_t N, std::size_t M>
constexpr std::array<double, N> head(const std::array<double, M>& a) {
  std::array<double, N> h{};
  for (std::size_t i = 0; i < N; ++i) h[i] = a[i];
  return h;
}
// Coefficients of the general series (coefficients.hpp), truncated: the first dropped term at
// t = kSmallAngle (t^2 = 0.0625) is e: 9.5e-18, f: 1.8e-19, c: 2.7e-19 relative; at
// t = kTinyAngle (t^2 = 1e-4): e: 1.0e-17, f: 2e-22.
inline constexpr auto kE6 = head<6>(coefficients::detail::series_e<6>());
inline constexpr auto kF7 = head<7>(coefficients::detail::series_f<7>());
inline constexpr auto kE3 = head<3>(coefficients::detail::series_e<3>());
inline constexpr auto kF4 = head<4>(coefficients::detail::series_f<4>());
inline constexpr auto kC6 = head<6>(coefficients::detail::series_c<6>());
inline constexpr auto kC3 = head<3>(coefficients::detail::series_c<3>());  // t < kTinyAngle: 2.8e-18
// atan(x)/x = sum (-1)^k x^2k / (2k + 1); x <= tan(kSmallAngle / 2) = 0.1257: the first dropped
// term (k = 9) is 3.3e-18.
inline constexpr auto kAtan9 = [] {
  std::array<double, 9> a{};
  for (int k = 0; k < 9; ++k) a[k] = (k % 2 ? -1.0 : 1.0) / (2.0 * k + 1.0);
  return a;
}();
inline constexpr auto kAtan5 = head<5>(kAtan9);
// sin(h)/h = sum (-1)^k h^2k / (2k+1)! and cos(h) = sum (-1)^k h^2k / (2k)!, h = t/2 <= 0.125:
// seven terms (first dropped: below 1e-20 and 3e-20), four below kTinyAngle (h <= 0.005: 4e-25,
// 6e-24).
inline constexpr auto kSinc7 = [] {
  std::array<double, 7> s{};
  for (int k = 0; k < 7; ++k)
    s[k] = (k % 2 ? -1.0 : 1.0) / coefficients::detail::factorial(2 * k + 1);
  return s;
}();
inline constexpr auto kCos7 = [] {
  std::array<double, 7> s{};
  for (int k = 0; k < 7; ++k) s[k] = (k % 2 ? -1.0 : 1.0) / coefficients::detail::factorial(2 * k);
  return s;
}();
inline constexpr auto kSinc4 = head<4>(kSinc7);
inline constexpr auto kCos4 = head<4>(kCos7);
}  // namespace detail

/// log's bound on tan^2(theta / 2) for the series, tan(kSmallAngle / 2)^2 = 0.01580...
inline constexpr double kLogX2 = 0.0158;

/// The coefficients e(t) and f(t) of dexp^-1 (coefficients.hpp) from t^2.
struct EF {
  double e, f;
};
[[gnu::always_inline]] inline EF ef(double t2) {
  using coefficients::detail::horner;
  if (t2 < kTinyAngle * kTinyAngle) return {horner(detail::kE3, t2), horner(detail::kF4, t2)};
  if (t2 < kSmallAngle * kSmallAngle) return {horner(detail::kE6, t2), horner(detail::kF7, t2)};
  const double t = std::sqrt(t2);
  return {coefficients::e(t), coefficients::f(t)};
}

/// coefficients::c(t) from t^2.
inline double c(double t2) {
  if (t2 < kTinyAngle * kTinyAngle) return coefficients::detail::horner(detail::kC3, t2);
  if (t2 < kSmallAngle * kSmallAngle) return coefficients::detail::horner(detail::kC6, t2);
  return coefficients::c(std::sqrt(t2));
}

/// se3::dexp_inv_transpose_apply with the coefficients of |xi.head<3>()| given.
[[gnu::always_inline]] inline Vector6 dexp_inv_transpose_apply(const Vector6& xi,
                                                               const Vector6& lambda,
                                                               const EF& k) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 m = lambda.head<3>(), f = lambda.tail<3>();
  const Vector3 w_m = w.cross(m), w_f = w.cross(f), v_f = v.cross(f);
  const Vector3 AinvT_m = m + 0.5 * w_m + k.e * w.cross(w_m);
  const Vector3 AinvT_f = f + 0.5 * w_f + k.e * w.cross(w_f);
  const Vector3 CT_f = 0.5 * v_f + k.e * (v.cross(w_f) + w.cross(v_f)) + w.dot(v) * k.f * w.cross(w_f);
  return se3::join(AinvT_m + CT_f, AinvT_f);
}

/// se3::dexp_inv_transpose_apply(xi, lambda). Forced inline: the discrete Legendre transform of
/// `variational` calls it once or twice per node and step, and GCC kept it out of line (18 % of
/// the step at N = 100, perf, session 5).
[[gnu::always_inline]] inline Vector6 dexp_inv_transpose_apply(const Vector6& xi,
                                                               const Vector6& lambda) {
  return dexp_inv_transpose_apply(xi, lambda, ef(xi.head<3>().squaredNorm()));
}

/// se3::dexp_inv_apply with the coefficients of |xi.head<3>()| given: dexp^-1_xi y = [A^-1 y_w;
/// C y_w + A^-1 y_v], A^-1 = I - W/2 + e W^2, C = -V/2 + e (W V + V W) + (w.v) f W^2.
[[gnu::always_inline]] inline Vector6 dexp_inv_apply(const Vector6& xi, const Vector6& y,
                                                     const EF& k) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 yw = y.head<3>(), yv = y.tail<3>();
  const Vector3 w_yw = w.cross(yw), v_yw = v.cross(yw);
  const Vector3 top = yw - 0.5 * w_yw + k.e * w.cross(w_yw);
  const Vector3 Ainv_yv = yv - 0.5 * w.cross(yv) + k.e * w.cross(w.cross(yv));
  const Vector3 C_yw = -0.5 * v_yw + k.e * (w.cross(v_yw) + v.cross(w_yw)) + w.dot(v) * k.f * w.cross(w_yw);
  return se3::join(top, C_yw + Ainv_yv);
}

/// se3::dexp_inv_apply(xi, y) (the chart ODE of Lie-group collocation: one interval's angle).
[[gnu::always_inline]] inline Vector6 dexp_inv_apply(const Vector6& xi, const Vector6& y) {
  return dexp_inv_apply(xi, y, ef(xi.head<3>().squaredNorm()));
}

/// |omega| below which bcd() takes 4-term series (a staggered segment's ds |kappa|, 0.005 .. 0.05
/// in the example scenes).
inline constexpr double kBcdShortAngle = 0.05;

/// The coefficients b, c, d1, d2 of dexp (coefficients.hpp) from t^2: 4-term series below
/// kBcdShortAngle (first dropped terms at t^2 = 0.0025: b 2.2e-17, c 6e-18, d1 1e-17, d2 4e-18
/// relative), 7-term series below kSmallAngle (at t^2 = 0.0625: b 6.8e-19, c 2.7e-19, d1 5e-20,
/// d2 4e-21), the general functions above. The staggered shooting march evaluates them about
/// four times per segment and shot (bench_dynamics: the 4-term tier saves 5 % of its step).
struct BCD {
  double b, c, d1, d2;
};
namespace detail {
inline constexpr auto kB7 = [] {  // (1 - cos t) / t^2 = sum (-1)^k t^2k / (2k + 2)!
  std::array<double, 7> s{};
  for (int k = 0; k < 7; ++k) s[k] = (k % 2 ? -1.0 : 1.0) / coefficients::detail::factorial(2 * k + 2);
  return s;
}();
inline constexpr auto kC7 = head<7>(coefficients::detail::series_c<7>());
inline constexpr auto kD1_7 = head<7>(coefficients::detail::series_d1<7>());
inline constexpr auto kD2_7 = head<7>(coefficients::detail::series_d2<7>());
inline constexpr auto kB4 = head<4>(kB7);
inline constexpr auto kC4 = head<4>(kC7);
inline constexpr auto kD1_4 = head<4>(kD1_7);
inline constexpr auto kD2_4 = head<4>(kD2_7);
}  // namespace detail
inline BCD bcd(double t2) {
  using coefficients::detail::horner;
  if (t2 < kBcdShortAngle * kBcdShortAngle)
    return {horner(detail::kB4, t2), horner(detail::kC4, t2), horner(detail::kD1_4, t2),
            horner(detail::kD2_4, t2)};
  if (t2 < kSmallAngle * kSmallAngle)
    return {horner(detail::kB7, t2), horner(detail::kC7, t2), horner(detail::kD1_7, t2),
            horner(detail::kD2_7, t2)};
  const double t = std::sqrt(t2);
  return {coefficients::b(t), coefficients::c(t), coefficients::d1(t), coefficients::d2(t)};
}

/// se3::dexp_apply with the coefficients of |xi.head<3>()| given (the same for -xi).
inline Vector6 dexp_apply(const Vector6& xi, const Vector6& y, const BCD& k) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 yw = y.head<3>(), yv = y.tail<3>();
  const Vector3 w_yw = w.cross(yw), v_yw = v.cross(yw);
  const Vector3 top = yw + k.b * w_yw + k.c * w.cross(w_yw);
  const Vector3 A_yv = yv + k.b * w.cross(yv) + k.c * w.cross(w.cross(yv));
  const Vector3 B_yw = k.b * v_yw + k.c * (w.cross(v_yw) + v.cross(w_yw)) +
                       w.dot(v) * (k.d1 * w_yw + k.d2 * w.cross(w_yw));
  return se3::join(top, B_yw + A_yv);
}

/// se3::dexp_transpose_apply with the coefficients of |xi.head<3>()| given.
inline Vector6 dexp_transpose_apply(const Vector6& xi, const Vector6& lambda, const BCD& k) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const Vector3 m = lambda.head<3>(), f = lambda.tail<3>();
  const Vector3 w_m = w.cross(m), w_f = w.cross(f), v_f = v.cross(f);
  const Vector3 AT_m = m - k.b * w_m + k.c * w.cross(w_m);
  const Vector3 AT_f = f - k.b * w_f + k.c * w.cross(w_f);
  const Vector3 BT_f = -k.b * v_f + k.c * (w.cross(v_f) + v.cross(w_f)) +
                       w.dot(v) * (-k.d1 * w_f + k.d2 * w.cross(w_f));
  return se3::join(AT_m + BT_f, AT_f);
}

/// SE3::exp(xi).
[[gnu::always_inline]] inline SE3 exp(const Vector6& xi) {
  const Vector3 w = xi.head<3>(), v = xi.tail<3>();
  const double t2 = w.squaredNorm();
  if (t2 >= kSmallAngle * kSmallAngle) return SE3::exp(xi);
  // b(t) = sinc(t/2)^2 / 2 (cancellation-free); sinc(h) and cos(h) from their series in h^2 (no
  // square root; detail::kSinc7, kCos7)
  const double h2 = 0.25 * t2;
  const Vector3 wv = w.cross(v);
  const bool tiny = t2 < kTinyAngle * kTinyAngle;
  const double sh = tiny ? coefficients::detail::horner(detail::kSinc4, h2)
                         : coefficients::detail::horner(detail::kSinc7, h2);
  const double ch = tiny ? coefficients::detail::horner(detail::kCos4, h2)
                         : coefficients::detail::horner(detail::kCos7, h2);
  const double b = 0.5 * sh * sh, cc = c(t2);
  return SE3(SO3::exp_from_half_angle(ch, sh, w), v + b * wv + cc * w.cross(wv));
}

/// SE3::log of g, and the coefficients e, f of its rotation angle (for dexp^-T of the result).
[[gnu::always_inline]] inline Vector6 log(const SE3& g, EF& k) {
  const Quaternion& q = g.rotation().quaternion();
  const double sign = q.w() < 0.0 ? -1.0 : 1.0;
  const double qw = sign * q.w();
  const Vector3 qv = sign * q.vec();
  const double n2 = qv.squaredNorm();
  const double inv_qw = 1.0 / qw;                // the one division
  const double x2 = n2 * (inv_qw * inv_qw);  // tan^2(theta / 2)
  if (!(x2 < kLogX2)) {
    const Vector6 xi = g.log();
    k = ef(xi.head<3>().squaredNorm());
    return xi;
  }
  // x^2 < 1e-4 (theta < 0.02): five terms, the first dropped one is 9e-22.
  const double atan_x_over_x = x2 < 1e-4 ? coefficients::detail::horner(detail::kAtan5, x2)
                                          : coefficients::detail::horner(detail::kAtan9, x2);
  const double scale = 2.0 * inv_qw * atan_x_over_x;
  const Vector3 w = scale * qv;
  k = ef(w.squaredNorm());
  const Vector3& p = g.translation();
  const Vector3 wp = w.cross(p);
  return se3::join(w, p - 0.5 * wp + k.e * w.cross(wp));
}

/// SE3::log(g).
inline Vector6 log(const SE3& g) {
  EF k;
  return log(g, k);
}

}  // namespace rodlab::lie::small_angle
