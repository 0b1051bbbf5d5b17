#pragma once
// Scalar coefficient functions of the rotation angle theta = |omega| used by exp, log, dexp and
// dexp^-1 on SO(3) and SE(3) (thesis (2.72)-(2.77), corrected; see docs/conventions.md).
//
//   a(t)  = sin t / t                               (2.74)
//   b(t)  = (1 - cos t) / t^2                       (2.75)
//   c(t)  = (1 - a(t)) / t^2 = (t - sin t) / t^3    (2.76)
//   d1(t) = (a - 2 b) / t^2 = b'(t) / t             (2.77, first coefficient of Q)
//   d2(t) = (b - 3 c) / t^2 = c'(t) / t             (2.77, second coefficient of Q)
//   e(t)  = (1 - (t/2) cot(t/2)) / t^2              (dexp^-1 on SO(3))
//   f(t)  = e'(t) / t                               (dexp^-1 on SE(3))
//
// a and b have no cancellation (b = sinc(t/2)^2 / 2); sin t / t comes from its series below
// kSincSwitch (cheaper than libm's sin, to below half an ulp) and directly above. c, d1, d2, e
// and f cancel catastrophically as t -> 0: below a switch point they are evaluated from their
// Taylor series in t^2 with enough terms that the truncation error at the switch point is below
// half an ulp, and the switch point is placed high enough that the closed form above it has lost
// at most a few ulps. So neither branch has an accuracy dip at the switch (unlike a low-order
// series switched at eps^(1/(degree+1)), which trades one error against the other). The series
// coefficients are generated from their closed forms below, not typed in.
#include <array>
#include <cmath>
#include <cstddef>

namespace rodlab::lie::coefficients {

namespace detail {

constexpr double factorial(int n) {
  double r = 1.0;
  for (int i = 2; i <= n; ++i) r *= i;
  return r;
}

// Bernoulli numbers scaled by k!: beta_k = B_k / k!, the Taylor coefficients of x / (e^x - 1)
// (with B_1 = -1/2). Recurrence: sum_{j=0}^{m} beta_j / (m + 1 - j)! = 0 for m >= 1.
// The sum cancels (its largest terms are ~7 |beta_m|), so the recurrence is run in long double
// and rounded to double once: run in double its errors reach ~50 eps at k = 10 and ~140 eps at
// k = 80, which also showed in the e and f series (tests/lie/test_coefficients.cpp).
template <std::size_t N>
constexpr std::array<double, N> bernoulli_over_factorial() {
  std::array<long double, N> beta{};
  beta[0] = 1.0L;
  for (std::size_t m = 1; m < N; ++m) {
    long double s = 0.0L;
    for (std::size_t j = 0; j < m; ++j) {
      long double fact = 1.0L;  // (m + 1 - j)!
      for (std::size_t i = 2; i <= m + 1 - j; ++i) fact *= static_cast<long double>(i);
      s += beta[j] / fact;
    }
    beta[m] = -s;
  }
  std::array<double, N> rounded{};
  for (std::size_t m = 0; m < N; ++m) rounded[m] = static_cast<double>(beta[m]);
  // Odd Bernoulli numbers beyond B_1 vanish; clear the rounding residue of the recurrence.
  for (std::size_t m = 3; m < N; m += 2) rounded[m] = 0.0;
  return rounded;
}

// Horner evaluation of sum_k coef[k] * x^k.
template <std::size_t N>
constexpr double horner(const std::array<double, N>& coef, double x) {
  double r = coef[N - 1];
  for (std::size_t k = N - 1; k-- > 0;) r = r * x + coef[k];
  return r;
}

// The same sum as E(x^2) + x O(x^2), two independent Horner chains: half the latency of horner
// for long series. Only for coefficients of one sign (for alternating ones E and x O cancel).
// The first M terms of the series (M <= N): the short branch below kShortSwitch.
template <std::size_t M, std::size_t N>
constexpr double horner_first(const std::array<double, N>& coef, double x) {
  static_assert(M >= 1 && M <= N);
  double r = coef[M - 1];
  for (std::size_t k = M - 1; k-- > 0;) r = r * x + coef[k];
  return r;
}

template <std::size_t N>
constexpr double horner_even_odd(const std::array<double, N>& coef, double x) {
  const double x2 = x * x;
  double even = 0.0, odd = 0.0;
  std::size_t k = N;
  if (k % 2 == 1) even = coef[--k];
  for (; k >= 2; k -= 2) {
    odd = odd * x2 + coef[k - 1];
    even = even * x2 + coef[k - 2];
  }
  return even + x * odd;
}

template <std::size_t N>
constexpr std::array<double, N> series_c() {  // (-1)^k / (2k+3)!
  std::array<double, N> s{};
  for (std::size_t k = 0; k < N; ++k) s[k] = (k % 2 ? -1.0 : 1.0) / factorial(2 * static_cast<int>(k) + 3);
  return s;
}
template <std::size_t N>
constexpr std::array<double, N> series_d1() {  // (-1)^(m+1) (2m+2) / (2m+4)!
  std::array<double, N> s{};
  for (std::size_t m = 0; m < N; ++m)
    s[m] = (m % 2 ? 1.0 : -1.0) * (2.0 * m + 2.0) / factorial(2 * static_cast<int>(m) + 4);
  return s;
}
template <std::size_t N>
constexpr std::array<double, N> series_d2() {  // (-1)^(m+1) (2m+2) / (2m+5)!
  std::array<double, N> s{};
  for (std::size_t m = 0; m < N; ++m)
    s[m] = (m % 2 ? 1.0 : -1.0) * (2.0 * m + 2.0) / factorial(2 * static_cast<int>(m) + 5);
  return s;
}
// (t/2) cot(t/2) = sum_n (-1)^n B_2n t^2n / (2n)!, so
// e(t) = sum_{m>=0} (-1)^m B_(2m+2) t^2m / (2m+2)!  (= 1/12 + t^2/720 + ...).
template <std::size_t N>
constexpr std::array<double, N> series_e() {
  constexpr auto beta = bernoulli_over_factorial<2 * N + 4>();
  std::array<double, N> s{};
  for (std::size_t m = 0; m < N; ++m) s[m] = (m % 2 ? -1.0 : 1.0) * beta[2 * m + 2];
  return s;
}
// f = e'/t: term-by-term derivative of e's series, f_k = 2 (k+1) e_(k+1).
template <std::size_t N>
constexpr std::array<double, N> series_f() {
  constexpr auto e = series_e<N + 1>();
  std::array<double, N> s{};
  for (std::size_t k = 0; k < N; ++k) s[k] = 2.0 * (k + 1.0) * e[k + 1];
  return s;
}

// sin(t)/t = sum (-1)^k t^2k / (2k + 1)!: sinc's and cos_sinc's branch below their switches.
inline constexpr auto kSincSeries = [] {
  std::array<double, 8> c{};
  for (int k = 0; k < 8; ++k) c[k] = (k % 2 ? -1.0 : 1.0) / factorial(2 * k + 1);
  return c;
}();

}  // namespace detail

/// Switch points: below them the Taylor branch is used. Exposed so tests can sample
/// theta = switch * (1 +/- 1e-3).
/// sin t / t: its series (8 terms, the first dropped t^16 / 17! = 6e-25 at 0.25) below, libm's
/// sin above. The series keeps the common small angles (one grid interval's rotation) off libm:
/// about 15 ns a call warm, and in a fresh process the first call faults libm's sin and its
/// tables in (docs/statics.md "Cold and warm solves").
inline constexpr double kSincSwitch = 0.25;
inline constexpr double kCSwitch = 1.0;        // c(t): 12 terms, truncation < 1e-25 at t = 1
// d2 = (b - 3c)/t^2 and f cancel up to ~7x at t = 2-2.5, where the closed forms were 15 eps off
// (tests/lie/test_coefficients.cpp); from t = 4 on they stay within ~5 eps, so their series run to 4.
inline constexpr double kDSwitch = 4.0;        // d1, d2: 18 terms, truncation < 1e-22 at t = 4
inline constexpr double kESwitch = 2.0;        // e(t): 22 terms (ratio (t/2pi)^2 = 0.1 at t = 2)
inline constexpr double kFSwitch = 4.0;        // f(t): 50 terms (ratio 0.41 at t = 4, tail < 1e-18)
/// SO3::exp evaluates cos_sinc at half the angle: its switch sits at |omega| = 2 kCosSincSwitch.
inline constexpr double kCosSincSwitch = 0.25;
/// Below this, c, d1, d2, e and f sum only the first terms of their series (the angles of one
/// grid interval or time step are almost always this small): the first term left out is below
/// 1e-19 of the sum (c: 6 terms, the next (t^2)^6 / 15! / (1/6) = 2.8e-19 at t = 0.25; d1, d2: 7;
/// e, f: 8, ratio (t / 2 pi)^2 = 1.6e-3 per term). 2-6x fewer operations than the long series.
inline constexpr double kShortSwitch = 0.25;
inline constexpr std::array<double, 7> kSwitchPoints{kSincSwitch, 2.0 * kCosSincSwitch, kCSwitch, kDSwitch, kESwitch,
                                                     kFSwitch, kShortSwitch};

/// sin(t)/t, accurate for every t (direct division has no cancellation for t > 0).
inline double sinc(double t) {
  if (std::abs(t) < kSincSwitch) return detail::horner(detail::kSincSeries, t * t);
  return std::sin(t) / t;
}

inline double a(double t) { return sinc(t); }

/// cos(t) and sin(t)/t together. Below kCosSincSwitch both come from their Taylor series
/// (truncation below 1e-19 there), which is several times cheaper than libm's sin and cos;
/// the stage rotations of Lie-group integrators are almost always this small.
inline void cos_sinc(double t, double& cos_t, double& sinc_t) {
  if (std::abs(t) < kCosSincSwitch) {
    static constexpr auto cos_series = [] {  // (-1)^k / (2k)!
      std::array<double, 9> c{};
      for (int k = 0; k < 9; ++k) c[k] = (k % 2 ? -1.0 : 1.0) / detail::factorial(2 * k);
      return c;
    }();
    const double t2 = t * t;
    sinc_t = detail::horner(detail::kSincSeries, t2);
    cos_t = detail::horner(cos_series, t2);
    return;
  }
  cos_t = std::cos(t);
  sinc_t = std::sin(t) / t;
}

/// (1 - cos t)/t^2 = sinc(t/2)^2 / 2: cancellation-free for every t.
inline double b(double t) {
  const double s = sinc(0.5 * t);
  return 0.5 * s * s;
}

inline double c(double t) {
  static constexpr auto coef = detail::series_c<12>();
  const double t2 = t * t;
  if (std::abs(t) < kShortSwitch) return detail::horner_first<6>(coef, t2);
  if (std::abs(t) < kCSwitch) return detail::horner(coef, t2);
  return (t - std::sin(t)) / (t * t * t);
}

inline double d1(double t) {
  static constexpr auto coef = detail::series_d1<18>();
  const double t2 = t * t;
  if (std::abs(t) < kShortSwitch) return detail::horner_first<7>(coef, t2);
  if (std::abs(t) < kDSwitch) return detail::horner(coef, t2);
  return (a(t) - 2.0 * b(t)) / t2;
}

inline double d2(double t) {
  static constexpr auto coef = detail::series_d2<18>();
  const double t2 = t * t;
  if (std::abs(t) < kShortSwitch) return detail::horner_first<7>(coef, t2);
  if (std::abs(t) < kDSwitch) return detail::horner(coef, t2);
  return (b(t) - 3.0 * c(t)) / t2;
}

/// (1 - (t/2) cot(t/2)) / t^2; pole at t = 2 pi (the end of the injectivity domain).
inline double e(double t) {
  static constexpr auto coef = detail::series_e<22>();
  const double t2 = t * t;
  if (std::abs(t) < kShortSwitch) return detail::horner_first<8>(coef, t2);
  if (std::abs(t) < kESwitch) return detail::horner(coef, t2);
  const double h = 0.5 * t;
  return (1.0 - h * std::cos(h) / std::sin(h)) / (t * t);
}

/// e'(t)/t. With u = t/2 and h(t) = 1 - u cot u: h' = (u / sin^2 u - cot u) / 2,
/// e' = h'/t^2 - 2 h/t^3, so f = h'/t^3 - 2 h/t^4.
inline double f(double t) {
  static constexpr auto coef = detail::series_f<50>();  // all positive
  if (std::abs(t) < kShortSwitch) return detail::horner_first<8>(coef, t * t);
  if (std::abs(t) < kFSwitch) return detail::horner_even_odd(coef, t * t);
  const double u = 0.5 * t;
  const double su = std::sin(u), cu = std::cos(u);
  const double h = 1.0 - u * cu / su;
  const double hp = 0.5 * (u / (su * su) - cu / su);
  const double t2 = t * t;
  return (hp * t - 2.0 * h) / (t2 * t2);
}

/// B_k / k! for k = 0..kMaxSeriesOrder (B_1 = -1/2): the coefficients of dexp^-1's series.
inline constexpr int kMaxSeriesOrder = 40;
inline constexpr auto kBernoulliOverFactorial = detail::bernoulli_over_factorial<kMaxSeriesOrder + 1>();
/// 1 / (k+1)! for k = 0..kMaxSeriesOrder: the coefficients of dexp's series.
inline constexpr auto kInverseFactorialShifted = [] {
  std::array<double, kMaxSeriesOrder + 1> s{};
  for (int k = 0; k <= kMaxSeriesOrder; ++k) s[k] = 1.0 / detail::factorial(k + 1);
  return s;
}();

}  // namespace rodlab::lie::coefficients
