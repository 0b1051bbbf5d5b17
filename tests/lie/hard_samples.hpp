#pragma once
// Shared fixtures of the tests/lie property suites (the manif / Sophus pattern, see
// spec/architecture.md "Lessons from the anchors"):
//   - Random: a portable generator on a fixed seed (never the clock);
//   - the hard sample sets of rotation vectors, twists and group elements;
//   - Worst: worst-case tracking, so a failing property names its worst sample and error;
//   - long double Bernoulli numbers B_k / k!, the exact reference of the dexp^-1 series and of
//     the coefficient functions e and f (used by test_dexp and test_coefficients).
// Include after <boost/test/unit_test.hpp> (each test file defines BOOST_TEST_MODULE first).
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "rodlab/lie/coefficients.hpp"
#include "rodlab/lie/se3.hpp"
#include "rodlab/lie/so3.hpp"

namespace rodlab::lie::testing {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kEps = std::numeric_limits<double>::epsilon();
inline constexpr std::uint32_t kSeed = 20240611u;
/// Tolerance of the algebraic identities, relative to 1 + |reference| (or to the natural scale
/// of the operands where stated): 1e-14 = 45 eps leaves room for the O(10) roundings of a
/// composition of 3x3 / 6x6 products and quaternion conversions. Measured maxima are logged.
inline constexpr double kAlgebraTol = 1e-14;

// ---------------------------------------------------------------------------------------------
// Random numbers. Only the raw output of std::mt19937 is used: its sequence is fixed by the
// standard, whereas std::uniform_real_distribution & co. are implementation-defined, so the
// samples are the same on every platform.
class Random {
 public:
  explicit Random(std::uint32_t seed = kSeed) : gen_(seed) {}

  /// Uniform in [0, 1) with 53 random bits.
  double uniform() {
    const std::uint64_t hi = gen_() >> 5;  // 27 bits
    const std::uint64_t lo = gen_() >> 6;  // 26 bits
    return static_cast<double>((hi << 26) | lo) * 0x1.0p-53;
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Log-uniform in [lo, hi) (magnitudes spanning decades).
  double log_uniform(double lo, double hi) { return lo * std::pow(hi / lo, uniform()); }

  /// Uniform on the unit sphere (Archimedes: z uniform in [-1, 1], azimuth uniform).
  Vector3 unit_vector() {
    const double z = uniform(-1.0, 1.0);
    const double phi = uniform(0.0, 2.0 * kPi);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return Vector3(r * std::cos(phi), r * std::sin(phi), z);
  }
  /// Unit vector orthogonal to u (|u| > 0).
  Vector3 unit_vector_orthogonal_to(const Vector3& u) {
    const Vector3 n = u.normalized();
    for (;;) {
      const Vector3 r = unit_vector();
      const Vector3 perp = r - r.dot(n) * n;
      if (perp.norm() > 0.1) return perp.normalized();
    }
  }
  /// Axis uniform on the sphere, angle uniform in [0, pi).
  Vector3 rotation_vector() {
    const Vector3 axis = unit_vector();
    return uniform(0.0, kPi) * axis;
  }
  /// Linear part of a twist: random direction, magnitude log-uniform in [1e-3, 10).
  Vector3 linear_part() {
    const Vector3 axis = unit_vector();
    return log_uniform(1e-3, 10.0) * axis;
  }
  Vector6 twist() {
    const Vector3 w = rotation_vector();
    return se3::join(w, linear_part());
  }
  /// Uniform (Haar) rotation, Shoemake's subgroup algorithm.
  SO3 rotation() {
    const double u1 = uniform(), u2 = uniform(0.0, 2.0 * kPi), u3 = uniform(0.0, 2.0 * kPi);
    const double s1 = std::sqrt(1.0 - u1), s2 = std::sqrt(u1);
    return SO3::from_quaternion(
        Quaternion(s2 * std::cos(u3), s1 * std::sin(u2), s1 * std::cos(u2), s2 * std::sin(u3)));
  }
  SE3 transform() {
    const SO3 R = rotation();
    return SE3(R, linear_part());
  }

 private:
  std::mt19937 gen_;
};

// ---------------------------------------------------------------------------------------------
// Hard sample sets.
template <class T>
struct Labelled {
  std::string label;
  T value;
};

inline std::string describe(double x) {
  std::ostringstream s;
  s.precision(17);
  s << x;
  return s.str();
}

/// Rotation vectors: zero, tiny, each switch point * (1 +/- 1e-3), within 1e-6 and 1e-9 of pi
/// (both sides, and pi itself), mid-range tangents 4, 5, 6 (|omega| < 2 pi, where dexp^-1 exists),
/// large tangents 20 and 30 rad, then 200 random ones (axis uniform, angle uniform in [0, pi)).
/// Axes of the special magnitudes come from the same fixed-seed generator.
inline const std::vector<Labelled<Vector3>>& rotation_vectors() {
  static const std::vector<Labelled<Vector3>> samples = [] {
    Random rng(kSeed);
    std::vector<Labelled<Vector3>> s;
    auto add = [&](const std::string& label, double angle) {
      s.push_back({label + " |w|=" + describe(angle), angle * rng.unit_vector()});
    };
    s.push_back({"zero", Vector3::Zero()});
    add("tiny", 1e-12);
    add("tiny", 1e-8);
    std::vector<double> switches(coefficients::kSwitchPoints.begin(),
                                 coefficients::kSwitchPoints.end());
    std::sort(switches.begin(), switches.end());
    switches.erase(std::unique(switches.begin(), switches.end()), switches.end());
    for (double sw : switches) {
      add("switch " + describe(sw) + "*(1-1e-3)", sw * (1.0 - 1e-3));
      add("switch " + describe(sw) + "*(1+1e-3)", sw * (1.0 + 1e-3));
    }
    for (double d : {1e-6, 1e-9}) {
      add("pi-" + describe(d), kPi - d);
      add("pi+" + describe(d), kPi + d);
    }
    add("pi", kPi);
    s.push_back({"pi about x |w|=pi", Vector3(kPi, 0.0, 0.0)});
    for (double t : {4.0, 5.0, 6.0}) add("mid", t);
    for (double t : {20.0, 30.0}) add("large", t);
    for (int i = 0; i < 200; ++i)
      s.push_back({"random #" + std::to_string(i), rng.rotation_vector()});
    return s;
  }();
  return samples;
}

/// Twists: every rotation vector above combined with three linear parts of random magnitude
/// in [1e-3, 10): random direction, parallel to omega and perpendicular to omega
/// (omega . nu = 0 switches off the (omega . nu) terms of SE(3) dexp).
inline const std::vector<Labelled<Vector6>>& twists() {
  static const std::vector<Labelled<Vector6>> samples = [] {
    Random rng(kSeed + 1);
    std::vector<Labelled<Vector6>> s;
    for (const auto& [label, w] : rotation_vectors()) {
      const Vector3 axis = w.norm() > 0.0 ? Vector3(w.normalized()) : rng.unit_vector();
      s.push_back({label + ", nu random", se3::join(w, rng.linear_part())});
      s.push_back({label + ", nu || w", se3::join(w, rng.log_uniform(1e-3, 10.0) * axis)});
      const Vector3 perp = rng.unit_vector_orthogonal_to(axis);
      s.push_back({label + ", nu _|_ w", se3::join(w, rng.log_uniform(1e-3, 10.0) * perp)});
    }
    return s;
  }();
  return samples;
}

/// Subset of samples whose rotation part has norm in [lo, hi].
template <class V>
std::vector<Labelled<V>> with_angle(const std::vector<Labelled<V>>& samples, double lo, double hi) {
  std::vector<Labelled<V>> out;
  for (const auto& s : samples) {
    const double t = s.value.template head<3>().norm();
    if (t >= lo && t <= hi) out.push_back(s);
  }
  return out;
}

/// Rotations: exp of every rotation vector sample (so near pi, beyond pi and large tangents),
/// the exact half-turns diag(1,-1,-1) and diag(-1,-1,1) from matrices, and 100 Haar-random ones.
inline const std::vector<Labelled<SO3>>& rotations() {
  static const std::vector<Labelled<SO3>> samples = [] {
    Random rng(kSeed + 2);
    std::vector<Labelled<SO3>> s;
    for (const auto& [label, w] : rotation_vectors())
      s.push_back({"exp(" + label + ")", SO3::exp(w)});
    s.push_back({"half turn about x", SO3::from_matrix(Vector3(1.0, -1.0, -1.0).asDiagonal())});
    s.push_back({"half turn about z", SO3::from_matrix(Vector3(-1.0, -1.0, 1.0).asDiagonal())});
    for (int i = 0; i < 100; ++i) s.push_back({"Haar #" + std::to_string(i), rng.rotation()});
    return s;
  }();
  return samples;
}

/// Rigid transforms: each rotation above with a random translation (|p| in [1e-3, 10)), plus the
/// identity and a pure translation.
inline const std::vector<Labelled<SE3>>& transforms() {
  static const std::vector<Labelled<SE3>> samples = [] {
    Random rng(kSeed + 3);
    std::vector<Labelled<SE3>> s;
    s.push_back({"identity", SE3::identity()});
    s.push_back({"translation", SE3::translation(rng.linear_part())});
    for (const auto& [label, R] : rotations())
      s.push_back({label + ", p random", SE3(R, rng.linear_part())});
    return s;
  }();
  return samples;
}

// ---------------------------------------------------------------------------------------------
// Error measures and worst-case reporting.

/// max |a - b| over all entries; NaN propagates (a NaN anywhere fails every check).
template <class A, class B>
double max_abs_diff(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  return (a - b).cwiseAbs().template maxCoeff<Eigen::PropagateNaN>();
}
template <class A>
double max_abs(const Eigen::MatrixBase<A>& a) {
  return a.cwiseAbs().template maxCoeff<Eigen::PropagateNaN>();
}
/// The error measure of the algebraic identities: max |value - reference| / (1 + max |reference|),
/// i.e. a test "err <= tol" means |value - reference| <= tol (1 + |reference|) entrywise.
template <class A, class B>
double scaled_error(const Eigen::MatrixBase<A>& value, const Eigen::MatrixBase<B>& reference) {
  return max_abs_diff(value, reference) / (1.0 + max_abs(reference));
}

/// Tracks the largest error of one property over a sample set and the sample where it occurred.
class Worst {
 public:
  explicit Worst(std::string property) : property_(std::move(property)) {}

  void update(double error, const std::string& sample) {
    if (!(error <= error_) && !std::isnan(error_)) {  // NaN sticks as the worst case
      error_ = error;
      sample_ = sample;
    }
    ++count_;
  }
  double error() const { return error_; }
  const std::string& sample() const { return sample_; }

  /// Logs the measured maximum and fails (naming the worst sample) unless it is <= tolerance.
  void check(double tolerance) const {
    BOOST_TEST_MESSAGE(property_ << ": max error " << error_ << " over " << count_
                                 << " samples (tolerance " << tolerance << "), worst at ["
                                 << sample_ << "]");
    BOOST_TEST(count_ > 0, property_ << ": no samples");
    BOOST_TEST(error_ <= tolerance, property_ << ": max error " << error_ << " > tolerance "
                                              << tolerance << " at sample [" << sample_ << "]");
  }

 private:
  std::string property_;
  std::string sample_ = "(none)";
  double error_ = 0.0;
  int count_ = 0;
};

// ---------------------------------------------------------------------------------------------
// Exact Bernoulli numbers, B_k / k! in long double (B_1 = -1/2), independent of the recurrence in
// coefficients.hpp: exact rationals for B_0..B_20 and, beyond, the Euler formula
//   B_2n / (2n)! = (-1)^(n+1) 2 zeta(2n) / (2 pi)^(2n),
// with zeta(2n) summed directly (for 2n >= 22 the tail after 60 terms is below 60^-21).
inline constexpr int kBernoulliReferenceMaxOrder = 400;

inline long double bernoulli_over_factorial_reference(int k) {
  static const std::vector<long double> table = [] {
    static constexpr std::array<std::array<long double, 2>, 21> kExact{
        {{1.0L, 1.0L},        {-1.0L, 2.0L}, {1.0L, 6.0L},       {0.0L, 1.0L},
         {-1.0L, 30.0L},      {0.0L, 1.0L},  {1.0L, 42.0L},      {0.0L, 1.0L},
         {-1.0L, 30.0L},      {0.0L, 1.0L},  {5.0L, 66.0L},      {0.0L, 1.0L},
         {-691.0L, 2730.0L},  {0.0L, 1.0L},  {7.0L, 6.0L},       {0.0L, 1.0L},
         {-3617.0L, 510.0L},  {0.0L, 1.0L},  {43867.0L, 798.0L}, {0.0L, 1.0L},
         {-174611.0L, 330.0L}}};
    std::vector<long double> beta(kBernoulliReferenceMaxOrder + 1, 0.0L);
    long double factorial = 1.0L;
    for (std::size_t k = 0; k < kExact.size(); ++k) {
      if (k >= 2) factorial *= static_cast<long double>(k);
      beta[k] = kExact[k][0] / kExact[k][1] / factorial;
    }
    const long double two_pi = 2.0L * std::numbers::pi_v<long double>;
    for (int k = 22; k <= kBernoulliReferenceMaxOrder; k += 2) {
      const long double exponent = static_cast<long double>(k);
      long double zeta = 0.0L;
      for (int j = 60; j >= 1; --j) zeta += std::pow(static_cast<long double>(j), -exponent);
      const long double sign = (k / 2) % 2 == 1 ? 1.0L : -1.0L;
      beta[static_cast<std::size_t>(k)] = sign * 2.0L * zeta / std::pow(two_pi, exponent);
    }
    return beta;
  }();
  return table.at(static_cast<std::size_t>(k));
}

}  // namespace rodlab::lie::testing
