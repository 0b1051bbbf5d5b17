#pragma once
// Two nodes or segments at once: the small-angle SE(3) kernels of lie/small_angle.hpp on pairs of
// values held lane by lane in SSE2 registers (a structure of arrays: `x` holds both lanes' x
// components), for the packed form of the plain variational step (variational_stepper.hpp,
// Variational::packed_pass) and the semi-discrete rod's segments (SemiDiscreteRod::segment_pair,
// collocation's and ida's f). Each kernel computes what its scalar namesake computes, with the
// same series where both lanes are below the scalar kernel's switch to a shorter one, else the
// longer (the results agree to rounding, tests/dynamics/test_variational_packed.cpp,
// test_semi_discrete_packed.cpp). The
// caller checks the angle bounds (small_angle::kSmallAngle, kLogX2) and falls back to the
// scalar kernels for a pair where either lane is above them. Private to solvers/dynamics.
//
// Why: the step is throughput-bound (splitting it into a segment pass and a node pass without
// packing changed nothing), and Eigen's 3-vectors cost shuffles in every cross product; on pairs
// every operation is one vertical SSE2 instruction for two nodes (the segment kernels alone,
// timed apart: 96 -> 45 ns per segment).
#include <array>
#include <cstddef>

#include "discrete_legendre.hpp"
#include "rodlab/lie/small_angle.hpp"

namespace rodlab::solvers::dynamics::packed {

using D2 = double __attribute__((vector_size(16)));  ///< two lanes
using Mask = long __attribute__((vector_size(16)));  ///< lane comparisons: 0 or -1

inline D2 splat(double a) { return D2{a, a}; }
inline bool any(Mask m) { return (m[0] | m[1]) != 0; }
/// v, or its first lane alone where the pair is one node in both lanes (`both` false): what a
/// pair adds to a sum over nodes.
inline D2 counted(D2 v, bool both) { return both ? v : D2{v[0], 0.0}; }

struct V3 {
  D2 x, y, z;
};
inline V3 operator+(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator-(const V3& a) { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(D2 s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3 operator*(double s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline D2 dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
/// Componentwise product with a constant diagonal (d[0..2]).
inline V3 diag(const double* d, const V3& a) { return {d[0] * a.x, d[1] * a.y, d[2] * a.z}; }

/// A twist or a wrench of each lane: head (angular, moment) and tail (linear, force).
struct V6 {
  V3 w, v;
};
inline V6 operator+(const V6& a, const V6& b) { return {a.w + b.w, a.v + b.v}; }
inline V6 operator-(const V6& a, const V6& b) { return {a.w - b.w, a.v - b.v}; }
inline V6 operator*(D2 s, const V6& a) { return {s * a.w, s * a.v}; }
inline V6 operator*(double s, const V6& a) { return {s * a.w, s * a.v}; }
inline D2 dot(const V6& a, const V6& b) { return dot(a.w, b.w) + dot(a.v, b.v); }
/// Componentwise product with a constant diagonal of six (a Vector6's data).
inline V6 diag(const double* d, const V6& a) { return {diag(d, a.w), diag(d + 3, a.v)}; }
/// op on each component pair of a and b.
template <class Op>
inline V6 lanewise(const V6& a, const V6& b, Op op) {
  return {{op(a.w.x, b.w.x), op(a.w.y, b.w.y), op(a.w.z, b.w.z)},
          {op(a.v.x, b.v.x), op(a.v.y, b.v.y), op(a.v.z, b.v.z)}};
}
/// Lanes of `yes` where m is set, of `no` elsewhere.
inline V6 select(Mask m, const V6& yes, const V6& no) {
  return lanewise(yes, no, [m](D2 a, D2 b) { return m ? a : b; });
}

inline V6 load(const lie::Vector6& a, const lie::Vector6& b) {
  return {{D2{a[0], b[0]}, D2{a[1], b[1]}, D2{a[2], b[2]}},
          {D2{a[3], b[3]}, D2{a[4], b[4]}, D2{a[5], b[5]}}};
}
inline lie::Vector6 lane(const V6& x, int l) {
  lie::Vector6 a;
  a << x.w.x[l], x.w.y[l], x.w.z[l], x.v.x[l], x.v.y[l], x.v.z[l];
  return a;
}

/// Unit quaternions (w, x, y, z) and poses of each lane.
struct Q {
  D2 w, x, y, z;
};
struct Pose {
  Q q;
  V3 p;
};
inline Pose load(const lie::SE3& a, const lie::SE3& b) {
  const auto& qa = a.rotation().quaternion();
  const auto& qb = b.rotation().quaternion();
  const lie::Vector3& pa = a.translation();
  const lie::Vector3& pb = b.translation();
  return {{D2{qa.w(), qb.w()}, D2{qa.x(), qb.x()}, D2{qa.y(), qb.y()}, D2{qa.z(), qb.z()}},
          {D2{pa.x(), pb.x()}, D2{pa.y(), pb.y()}, D2{pa.z(), pb.z()}}};
}
inline lie::SE3 lane(const Pose& g, int l) {
  return lie::SE3(
      lie::SO3::from_unit_quaternion(lie::Quaternion(g.q.w[l], g.q.x[l], g.q.y[l], g.q.z[l])),
      lie::Vector3(g.p.x[l], g.p.y[l], g.p.z[l]));
}

// Pairs kept packed across the passes of a step are indexed by their first node or segment:
// pair p holds 2p and 2p + 1 (or, for the exponentials, 2p - 1 and 2p). A pass that takes the
// pairs one node later reads them shifted.

/// op on each component pair of a and b.
template <class Op>
inline Pose lanewise(const Pose& a, const Pose& b, Op op) {
  return {{op(a.q.w, b.q.w), op(a.q.x, b.q.x), op(a.q.y, b.q.y), op(a.q.z, b.q.z)},
          {op(a.p.x, b.p.x), op(a.p.y, b.p.y), op(a.p.z, b.p.z)}};
}
/// The pair (a[1], b[0]) from two consecutive pairs a, b: a pair one node later. `both` false:
/// (a[1], a[1]).
template <class T>
inline T shifted(const T& a, const T& b, bool both) {
  return lanewise(a, b, [both](D2 x, D2 y) {
    return both ? __builtin_shuffle(x, y, Mask{1, 2}) : __builtin_shuffle(x, Mask{1, 1});
  });
}
/// The pair (a[l], a[l]).
template <class T>
inline T lane_twice(const T& a, int l) {
  return lanewise(a, a, [l](D2 x, D2) { return __builtin_shuffle(x, Mask{l, l}); });
}
/// R v and R^T v (Eigen's form: v + 2 w (u x v) + 2 u x (u x v), u the vector part).
inline V3 rotate(const Q& q, const V3& v) {
  const V3 u{q.x, q.y, q.z};
  V3 uv = cross(u, v);
  uv = uv + uv;
  return v + q.w * uv + cross(u, uv);
}
inline Q conjugate(const Q& q) { return {q.w, -q.x, -q.y, -q.z}; }

/// The Hamilton product a b.
inline Q product(const Q& a, const Q& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
          a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y + a.y * b.w + a.z * b.x - a.x * b.z,
          a.w * b.z + a.z * b.w + a.x * b.y - a.y * b.x};
}
/// SO3::operator*: the product pulled back onto the unit sphere by (3 - |q|^2) / 2.
inline Q multiply(const Q& a, const Q& b) {
  const Q q = product(a, b);
  const D2 s = 1.5 - 0.5 * (q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  return {s * q.w, s * q.x, s * q.y, s * q.z};
}
/// SE3::operator*.
inline Pose compose(const Pose& a, const Pose& b) {
  return {multiply(a.q, b.q), a.p + rotate(a.q, b.p)};
}
/// SE3::inverse() * b.
inline Pose inverse_compose(const Pose& a, const Pose& b) {
  const Q ct = conjugate(a.q);
  return compose({ct, -rotate(ct, a.p)}, b);
}
/// a^-1 b c (the segment b moved by its end nodes' steps a, c: (3.38)) with one rotation and
/// one normalisation fewer than inverse_compose(a, b) and compose: R_a^T (p_b - p_a) is one
/// rotation, and the product is normalised once (R_a^T R_b is unit to rounding, which the
/// rotation of p_c by it keeps). The variational step 4 % faster (bench_dynamics, session 28);
/// its results move by rounding (tests/dynamics/test_variational_packed.cpp).
inline Pose inverse_compose(const Pose& a, const Pose& b, const Pose& c) {
  const Q ct = conjugate(a.q);
  const Q t = product(ct, b.q);
  return {multiply(t, c.q), rotate(ct, b.p - a.p) + rotate(t, c.p)};
}

/// SE3::coAd_apply: Ad_g^T W = [R^T (m - p x f); R^T f].
inline V6 coAd_apply(const Pose& g, const V6& W) {
  const Q ct = conjugate(g.q);
  return {rotate(ct, W.w - cross(g.p, W.v)), rotate(ct, W.v)};
}
/// SE3Adjoints::inverse_Ad_apply: Ad_{g^-1} xi = [R^T w; R^T (v - p x w)].
inline V6 inverse_Ad_apply(const Pose& g, const V6& xi) {
  const Q ct = conjugate(g.q);
  return {rotate(ct, xi.w), rotate(ct, xi.v - cross(g.p, xi.w))};
}
/// se3::coad_apply: ad_xi^T lambda = [m x w + f x v; f x w].
inline V6 coad_apply(const V6& xi, const V6& lambda) {
  return {cross(lambda.w, xi.w) + cross(lambda.v, xi.v), cross(lambda.v, xi.w)};
}

template <std::size_t N>
inline D2 horner(const std::array<double, N>& c, D2 x) {
  D2 r = splat(c[N - 1]);
  for (std::size_t k = N - 1; k-- > 0;) r = r * x + c[k];
  return r;
}

/// small_angle::ef on both lanes, |w|^2 = t2 below kSmallAngle^2: the short series where both
/// lanes are below kTinyAngle (as the scalar kernel there), else the longer one.
inline void coefficients_ef(D2 t2, D2& e, D2& f) {
  namespace sa = lie::small_angle;
  if (!any(!(t2 < sa::kTinyAngle * sa::kTinyAngle))) {
    e = horner(sa::detail::kE3, t2);
    f = horner(sa::detail::kF4, t2);
  } else {
    e = horner(sa::detail::kE6, t2);
    f = horner(sa::detail::kF7, t2);
  }
}

/// small_angle::exp, both lanes' |w|^2 below kSmallAngle^2 (the caller checks `t2`).
inline Pose exp(const V6& xi, D2 t2) {
  namespace detail = lie::small_angle::detail;
  const D2 h2 = 0.25 * t2;
  const bool tiny = !any(!(t2 < lie::small_angle::kTinyAngle * lie::small_angle::kTinyAngle));
  const D2 sh = tiny ? horner(detail::kSinc4, h2) : horner(detail::kSinc7, h2);
  const D2 ch = tiny ? horner(detail::kCos4, h2) : horner(detail::kCos7, h2);
  const V3 wv = cross(xi.w, xi.v);
  const D2 b = 0.5 * sh * sh, c = tiny ? horner(detail::kC3, t2) : horner(detail::kC6, t2);
  const V3 u = (0.5 * sh) * xi.w;
  return {{ch, u.x, u.y, u.z}, xi.v + b * wv + c * cross(xi.w, wv)};
}

/// small_angle::log of both lanes with the coefficients e, f of their angles; `small` is
/// cleared where a lane is above small_angle::kLogX2 (then the result is not to be used).
inline V6 log(const Pose& g, D2& e, D2& f, bool& small) {
  namespace detail = lie::small_angle::detail;
  const D2 sign = g.q.w < 0.0 ? splat(-1.0) : splat(1.0);
  const D2 qw = sign * g.q.w;
  const V3 qv{sign * g.q.x, sign * g.q.y, sign * g.q.z};
  const D2 inv_qw = 1.0 / qw;
  const D2 x2 = dot(qv, qv) * (inv_qw * inv_qw);  // tan^2(theta / 2)
  small = !any(!(x2 < lie::small_angle::kLogX2));
  const D2 atan_x_over_x =
      any(!(x2 < 1e-4)) ? horner(detail::kAtan9, x2) : horner(detail::kAtan5, x2);
  const V3 w = (2.0 * inv_qw * atan_x_over_x) * qv;
  coefficients_ef(dot(w, w), e, f);
  const V3 wp = cross(w, g.p);
  return {w, g.p - 0.5 * wp + e * cross(w, wp)};
}

/// small_angle::dexp_inv_transpose_apply with the coefficients e, f of |xi.w|.
inline V6 dexp_inv_transpose_apply(const V6& xi, const V6& lambda, D2 e, D2 f) {
  const V3& w = xi.w;
  const V3& v = xi.v;
  const V3 w_m = cross(w, lambda.w), w_f = cross(w, lambda.v), v_f = cross(v, lambda.v);
  const V3 AinvT_m = lambda.w + 0.5 * w_m + e * cross(w, w_m);
  const V3 AinvT_f = lambda.v + 0.5 * w_f + e * cross(w, w_f);
  const V3 CT_f = 0.5 * v_f + e * (cross(v, w_f) + cross(w, v_f)) + (dot(w, v) * f) * cross(w, w_f);
  return {AinvT_m + CT_f, AinvT_f};
}

/// small_angle::dexp_inv_apply with the coefficients e, f of |xi.w|: [A^-1 y_w; C y_w + A^-1 y_v].
inline V6 dexp_inv_apply(const V6& xi, const V6& y, D2 e, D2 f) {
  const V3& w = xi.w;
  const V3& v = xi.v;
  const V3 w_yw = cross(w, y.w), v_yw = cross(v, y.w);
  const V3 top = y.w - 0.5 * w_yw + e * cross(w, w_yw);
  const V3 Ainv_yv = y.v - 0.5 * cross(w, y.v) + e * cross(w, cross(w, y.v));
  const V3 C_yw = -0.5 * v_yw + e * (cross(w, v_yw) + cross(v, w_yw)) +
                  (dot(w, v) * f) * cross(w, w_yw);
  return {top, C_yw + Ainv_yv};
}

/// solve_legendre (discrete_legendre.hpp) with a diagonal mass matrix M on both lanes: (3.42)
/// for eta from the momentum mu, eta on entry the velocity that solved it for mu_old; the same
/// iterates and tests, with the contraction bound `contraction` of M. Each lane stops by its own
/// tests. Returns 1 when both lanes converged, 0 when one did not within max_iterations, -1 when
/// an iterate left the small-angle bound; eta is changed only when both converged (else the
/// caller solves the lanes with the scalar kernel, which also names a lane that diverges).
inline int solve_legendre(const double* M, const double* M_inv,
                          const LegendreContraction& contraction, double tol, int max_iterations,
                          double dt, const V6& mu, const V6& mu_old, V6& eta) {
  const V6 eta_old = eta;
  // the first-order Jacobian at the iterate x (M x given)
  auto newton_step = [&](const V6& r, const V6& x, const V6& Mx) {
    const V6 y = diag(M_inv, r);
    const V6 By = coad_apply(x, r) + coad_apply(y, Mx);
    return y + (0.5 * dt) * diag(M_inv, By);
  };
  V6 x = eta_old - newton_step(mu_old - mu, eta_old, diag(M, eta_old));
  V6 result = x;
  Mask done = {0, 0};
  const double tol2 = tol * tol;
  using C = LegendreContraction;
  const bool bounded = contraction.cw2 >= 0.0;
  const double dt2 = dt * dt;
  for (int it = 1; it < max_iterations; ++it) {
    const V6 dx = dt * x;
    const D2 t2 = dot(dx.w, dx.w);
    if (any(!(t2 < lie::small_angle::kSmallAngle * lie::small_angle::kSmallAngle))) return -1;
    const V6 Mx = diag(M, x);
    D2 e, f;
    coefficients_ef(t2, e, f);
    const V6 r = dexp_inv_transpose_apply(dx, Mx, e, f) - mu;
    const V6 y = diag(M_inv, r);
    const D2 y2 = dot(y, r), x2 = dot(x, Mx);  // |y|_M^2, |x|_M^2
    Mask first = ~done & (y2 <= 0.25 * tol2 * x2);
    // LegendreContraction's S2 and its two tests' factors, lane by lane, where the plain test
    // did not end the solve
    D2 S2 = splat(1.0);
    if (bounded && !((done | first)[0] && (done | first)[1])) {
      S2 = contraction.S2(dt2, dot(x.w, x.w), dot(x.v, x.v));
      const Mask in_range = (S2 <= C::kRange) & (y2 <= C::kZerothRange * x2);
      first |= ~done & in_range & (C::zeroth_order_bound(S2) * y2 <= 0.25 * tol2 * x2);
    }
    result = select(first, x - y, result);
    done |= first;
    if (done[0] && done[1]) {  // most pairs, at the first iteration
      eta = result;
      return 1;
    }
    const V6 step = newton_step(r, x, Mx);
    x = x - step;
    const D2 s2 = dot(step, diag(M, step)), xn2 = dot(x, diag(M, x));
    const D2 newton = (S2 <= C::kRange) & (s2 <= C::kNewtonRange * xn2)
                          ? contraction.newton_bound(S2)
                          : splat(1.0);
    const Mask second = ~done & (newton * s2 <= tol2 * xn2);
    result = select(second, x, result);
    done |= second;
    if (done[0] && done[1]) {
      eta = result;
      return 1;
    }
  }
  return 0;
}

}  // namespace rodlab::solvers::dynamics::packed
