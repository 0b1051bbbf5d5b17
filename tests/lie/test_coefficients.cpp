#define BOOST_TEST_MODULE coefficients
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "finite_difference.hpp"
#include "hard_samples.hpp"
#include "rodlab/lie/coefficients.hpp"

// The scalar coefficient functions a, b, c, d1, d2, e, f of rodlab/lie/coefficients.hpp
// (thesis (2.74)-(2.77), corrected; docs/conventions.md) against long double references, the
// derivative relations between them, and the Bernoulli and factorial tables of the series.
//
// References, in long double (64-bit mantissa, 11 bits more than double):
//   a = sin t / t and b = 2 sin^2(t/2) / t^2: direct, no cancellation at any t;
//   c, d1, d2, e, f: for t < 3 their Taylor series in t^2 (40 terms: the tails are below
//   3^80 / 83! ~ 1e-86 for c, d1, d2 and 2 (3 / 2 pi)^80 ~ 1e-26 for e, f), for t >= 3 their
//   closed forms (which lose at most ~2 bits to cancellation there). The series are derived here
//   independently of coefficients.hpp: c from sin, d1 = b'/t and d2 = c'/t by differentiating the
//   series of b and c term by term, e from the exact Bernoulli numbers, f = e'/t likewise.

namespace {

using namespace rodlab::lie;
using namespace rodlab::lie::testing;
using LD = long double;

constexpr LD kReferenceSwitch = 3.0L;
constexpr int kReferenceTerms = 40;

LD factorial(int n) {
  LD r = 1.0L;
  for (int i = 2; i <= n; ++i) r *= i;
  return r;
}
LD sign(int m) { return m % 2 == 0 ? 1.0L : -1.0L; }

/// Series coefficients g_m of g(t) = sum_m g_m t^(2m).
LD b_coef(int m) { return sign(m) / factorial(2 * m + 2); }  // (1 - cos t)/t^2
LD c_coef(int m) { return sign(m) / factorial(2 * m + 3); }  // (t - sin t)/t^3
// (t/2) cot(t/2) = sum_n (-1)^n B_2n t^2n / (2n)!, so 1 - (t/2) cot(t/2) = sum_{m>=0} (-1)^m
// B_(2m+2) ...
LD e_coef(int m) { return sign(m) * bernoulli_over_factorial_reference(2 * m + 2); }
/// Coefficients of g'(t)/t from those of g: d/dt t^(2m+2) / t = (2m+2) t^(2m).
template <class Coef>
auto derivative_over_t(Coef g) {
  return [g](int m) { return (2.0L * m + 2.0L) * g(m + 1); };
}

template <class Coef>
LD series(Coef coef, LD t) {
  const LD x = t * t;
  LD r = 0.0L;
  for (int m = kReferenceTerms - 1; m >= 0; --m) r = r * x + coef(m);
  return r;
}

LD a_ref(LD t) { return t == 0.0L ? 1.0L : std::sin(t) / t; }
LD b_ref(LD t) {
  const LD s = t == 0.0L ? 1.0L : std::sin(0.5L * t) / (0.5L * t);
  return 0.5L * s * s;
}
LD c_ref(LD t) {
  return t < kReferenceSwitch ? series(c_coef, t) : (t - std::sin(t)) / (t * t * t);
}
LD d1_ref(LD t) {
  return t < kReferenceSwitch ? series(derivative_over_t(b_coef), t)
                              : (a_ref(t) - 2.0L * b_ref(t)) / (t * t);
}
LD d2_ref(LD t) {
  return t < kReferenceSwitch ? series(derivative_over_t(c_coef), t)
                              : (b_ref(t) - 3.0L * c_ref(t)) / (t * t);
}
LD e_ref(LD t) {
  if (t < kReferenceSwitch) return series(e_coef, t);
  const LD u = 0.5L * t;
  return (1.0L - u * std::cos(u) / std::sin(u)) / (t * t);
}
LD f_ref(LD t) {
  if (t < kReferenceSwitch) return series(derivative_over_t(e_coef), t);
  // e = h / t^2 with h = 1 - u cot u, u = t/2: e' = h'/t^2 - 2h/t^3, h' = (u / sin^2 u - cot u)/2.
  const LD u = 0.5L * t, s = std::sin(u), co = std::cos(u);
  const LD h = 1.0L - u * co / s, hp = 0.5L * (u / (s * s) - co / s);
  return (hp * t - 2.0L * h) / (t * t * t * t);
}

/// theta samples: 0, 1e-12, 1e-8, 1e-4, a dense grid of 6000 points in (0, 6), and around each
/// switch point: switch * (1 +/- 1e-3), the switch itself and its lower neighbour, and
/// switch * (1 + k 1e-4), k = -10..10.
struct Theta {
  double t;
  bool near_switch;
};
const std::vector<Theta>& thetas() {
  static const std::vector<Theta> samples = [] {
    std::vector<Theta> s;
    for (double t : {0.0, 1e-12, 1e-8, 1e-4}) s.push_back({t, false});
    for (int k = 1; k < 6000; ++k) s.push_back({6.0 * k / 6000.0, false});
    for (double sw : coefficients::kSwitchPoints) {
      for (double t : {sw * (1.0 - 1e-3), sw * (1.0 + 1e-3), sw, std::nextafter(sw, 0.0)})
        s.push_back({t, true});
      for (int k = -10; k <= 10; ++k) s.push_back({sw * (1.0 + 1e-4 * k), true});
    }
    return s;
  }();
  return samples;
}

/// Relative error in units of eps = 2^-52 (1 ulp of a number in [1, 2)).
double ulps(double value, LD reference) {
  return static_cast<double>(std::abs(static_cast<LD>(value) - reference) / std::abs(reference) /
                             kEps);
}

/// Checks fn against ref on every theta sample: relative error <= 8 eps (~1.8e-15) everywhere,
/// and separately around the switch points (no accuracy dip), logging both maxima.
void check_against_reference(const std::string& name, double (*fn)(double), LD (*ref)(LD)) {
  Worst everywhere(name + " relative error [eps], all theta"),
      at_switch(name + " relative error [eps], near switch points");
  for (const auto& [t, near_switch] : thetas()) {
    const double err = ulps(fn(t), ref(static_cast<LD>(t)));
    everywhere.update(err, "theta = " + describe(t));
    if (near_switch) at_switch.update(err, "theta = " + describe(t));
  }
  everywhere.check(8.0);
  at_switch.check(8.0);
}

}  // namespace

// Each coefficient function against its long double reference: relative error <= 8 eps
// (about 1.8e-15) at every theta, including at the switch points between Taylor branch and
// closed form. The measured maxima are logged.
BOOST_AUTO_TEST_CASE(coefficient_a) { check_against_reference("a", coefficients::a, a_ref); }
BOOST_AUTO_TEST_CASE(coefficient_b) { check_against_reference("b", coefficients::b, b_ref); }
BOOST_AUTO_TEST_CASE(coefficient_c) { check_against_reference("c", coefficients::c, c_ref); }
BOOST_AUTO_TEST_CASE(coefficient_d1) { check_against_reference("d1", coefficients::d1, d1_ref); }
BOOST_AUTO_TEST_CASE(coefficient_d2) { check_against_reference("d2", coefficients::d2, d2_ref); }
BOOST_AUTO_TEST_CASE(coefficient_e) { check_against_reference("e", coefficients::e, e_ref); }
BOOST_AUTO_TEST_CASE(coefficient_f) { check_against_reference("f", coefficients::f, f_ref); }

// The reference itself: its series and closed forms agree on a grid in [1.5, 3] up to the
// reference switch t = 3, where both are accurate in long double (this guards the reference, not
// the code): relative difference <= 2e-17 (~ 0.1 eps; at t = 1.5 the long double closed form of f
// has lost ~6 of its 64 bits to cancellation).
BOOST_AUTO_TEST_CASE(reference_branches_agree) {
  Worst w("long double reference: series - closed form, relative");
  for (int k = 0; k <= 30; ++k) {
    const LD t = 1.5L + 0.05L * k;
    const LD a = a_ref(t), b = b_ref(t), u = 0.5L * t, tt = t * t;
    const LD c_closed = (t - std::sin(t)) / (tt * t);
    const LD pairs[5][2] = {
        {series(c_coef, t), c_closed},
        {series(derivative_over_t(b_coef), t), (a - 2.0L * b) / tt},
        {series(derivative_over_t(c_coef), t), (b - 3.0L * c_closed) / tt},
        {series(e_coef, t), (1.0L - u * std::cos(u) / std::sin(u)) / tt},
        {series(derivative_over_t(e_coef), t),
         (0.5L * (u / (std::sin(u) * std::sin(u)) - std::cos(u) / std::sin(u)) * t -
          2.0L * (1.0L - u * std::cos(u) / std::sin(u))) /
             (tt * tt)}};
    for (const auto& p : pairs)
      w.update(static_cast<double>(std::abs(p[0] - p[1]) / std::abs(p[1])),
               "t = " + describe(static_cast<double>(t)));
  }
  w.check(2e-17);
}

// The derivative relations of the definitions: d1 = b'(t)/t, d2 = c'(t)/t, f = e'(t)/t, with b',
// c', e' from Richardson-extrapolated central differences (4 D(h/2) - D(h)) / 3, h = 1e-3:
// truncation O(h^4) ~ 1e-13, rounding ~ eps |g| / (h |g'|), largest for e at t = 0.3 (e' = t f ~
// 1e-3 e): ~2e-11. Tolerance 1e-10 relative.
BOOST_AUTO_TEST_CASE(derivative_relations) {
  Worst w("d1 - b'/t, d2 - c'/t, f - e'/t (relative)");
  const double h = 1e-3;
  auto richardson = [h](double (*g)(double), double t) {
    return (4.0 * central_derivative(g, t, h / 2.0) - central_derivative(g, t, h)) / 3.0;
  };
  for (double t : {0.3, 1.0, 1.7, 2.2, 2.9}) {
    const std::string at = "t = " + describe(t);
    w.update(std::abs(coefficients::d1(t) - richardson(coefficients::b, t) / t) /
                 std::abs(coefficients::d1(t)),
             "d1, " + at);
    w.update(std::abs(coefficients::d2(t) - richardson(coefficients::c, t) / t) /
                 std::abs(coefficients::d2(t)),
             "d2, " + at);
    w.update(std::abs(coefficients::f(t) - richardson(coefficients::e, t) / t) /
                 std::abs(coefficients::f(t)),
             "f, " + at);
  }
  w.check(1e-10);
}

// The series tables: kBernoulliOverFactorial[k] = B_k / k! against the exact values (B_0..B_20 as
// rationals, listed in hard_samples.hpp) to 1e-14 relative, odd entries k >= 3 exactly 0; the
// entries k = 21..40 (from the same recurrence) against Euler's zeta formula, also 1e-14;
// kInverseFactorialShifted[k] = 1 / (k+1)! to 1e-15 relative.
BOOST_AUTO_TEST_CASE(series_tables) {
  Worst low("B_k/k!, k <= 20, relative"), high("B_k/k!, 21 <= k <= 40, relative"),
      odd("B_k/k!, odd k >= 3"), fact("1/(k+1)!, relative");
  for (int k = 0; k <= coefficients::kMaxSeriesOrder; ++k) {
    const LD exact = bernoulli_over_factorial_reference(k);
    const double value = coefficients::kBernoulliOverFactorial[static_cast<std::size_t>(k)];
    const std::string label = "k = " + std::to_string(k);
    if (exact == 0.0L) {
      odd.update(std::abs(value), label);
    } else {
      (k <= 20 ? low : high)
          .update(static_cast<double>(std::abs(value - exact) / std::abs(exact)), label);
    }
    const LD inv_fact = 1.0L / factorial(k + 1);
    fact.update(static_cast<double>(
                    std::abs(coefficients::kInverseFactorialShifted[static_cast<std::size_t>(k)] -
                             inv_fact) /
                    inv_fact),
                label);
  }
  low.check(1e-14);
  high.check(1e-14);
  odd.check(0.0);
  fact.check(1e-15);
}
