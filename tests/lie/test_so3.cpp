#define BOOST_TEST_MODULE so3
#include <boost/test/unit_test.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "hard_samples.hpp"
#include "rodlab/lie/so3.hpp"

// Property tests of rodlab::lie::SO3 over the hard sample set (tests/lie/hard_samples.hpp).
// Every check logs its measured maximum error and, on failure, the worst sample.

namespace {

using namespace rodlab::lie;
using namespace rodlab::lie::testing;
using Matrix3L = Eigen::Matrix<long double, 3, 3>;

/// Rodrigues' formula R = I + (sin t / t) W + ((1 - cos t) / t^2) W^2 in long double, written
/// without cancellation ((1 - cos t)/t^2 = 2 sin^2(t/2) / t^2): the independent reference of exp.
Matrix3L rodrigues_long_double(const Vector3& w) {
  const Eigen::Matrix<long double, 3, 1> wl = w.cast<long double>();
  const long double t = wl.norm();
  const Matrix3L W = so3::hat(w).cast<long double>();  // hat only copies entries: exact
  const long double a = t == 0.0L ? 1.0L : std::sin(t) / t;
  const long double s = t == 0.0L ? 1.0L : std::sin(0.5L * t) / (0.5L * t);
  const long double b = 0.5L * s * s;
  return Matrix3L::Identity() + a * W + b * W * W;
}

/// The rotation vector with angle in (-pi, pi] equivalent to w (long double wrap of |w|).
Vector3 wrapped_long_double(const Vector3& w) {
  const long double t = w.cast<long double>().norm();
  if (t == 0.0L) return w;
  const long double two_pi = 2.0L * std::numbers::pi_v<long double>;
  long double r = std::fmod(t, two_pi);
  if (r > std::numbers::pi_v<long double>) r -= two_pi;
  return (w.cast<long double>() * (r / t)).cast<double>();
}

const auto& samples() { return rotation_vectors(); }
const auto& group() { return rotations(); }

}  // namespace

// (1.4), (1.6), (1.9). vee(hat(w)) = w is exact (vee reads (W - W^T)/2, all operations exact);
// hat(a) b = a x b and vee([hat a, hat b]) = a x b to kAlgebraTol (1 + |a||b|): each entry is a
// sum of products of size <= |a||b|, rounded differently in the two evaluations.
BOOST_AUTO_TEST_CASE(hat_vee_and_cross_product) {
  Worst round_trip("vee(hat(w)) - w"), skew("hat(w) + hat(w)^T"), cross("hat(a) b - a x b"),
      bracket("vee([hat a, hat b]) - a x b (1.8), (1.9)");
  const auto& s = samples();
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vector3& a = s[i].value;
    const Vector3& b = s[(i + 1) % s.size()].value + Vector3(0.3, -0.2, 0.1);
    const std::string label = s[i].label + " x " + s[(i + 1) % s.size()].label;
    const Matrix3 A = so3::hat(a), B = so3::hat(b);
    const double scale = 1.0 + a.norm() * b.norm();
    round_trip.update(max_abs_diff(so3::vee(A), a), s[i].label);
    skew.update(max_abs(Matrix3(A + A.transpose())), s[i].label);
    cross.update(max_abs_diff(A * b, a.cross(b)) / scale, label);
    bracket.update(max_abs_diff(so3::vee(A * B - B * A), a.cross(b)) / scale, label);
  }
  round_trip.check(0.0);
  skew.check(0.0);
  cross.check(kAlgebraTol);
  bracket.check(kAlgebraTol);
}

// Group axioms on (R_i, R_i+1, R_i+2) over all rotation samples. Reference: matrix algebra.
// Matrix entries are <= 1 in magnitude, so errors are absolute; each side is a handful of
// quaternion products and a quaternion-to-matrix conversion: tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(group_axioms) {
  Worst assoc("(ab)c - a(bc)"), ident("aI - a, Ia - a"), inv("a a^-1 - I, a^-1 a - I"),
      product("matrix(ab) - matrix(a) matrix(b)"), action("a * v - matrix(a) v"),
      inverse_matrix("matrix(a^-1) - matrix(a)^-1, - matrix(a)^T"),
      orthonormal("R^T R - I, det R - 1");
  const auto& g = group();
  const Matrix3 I = Matrix3::Identity();
  for (std::size_t i = 0; i < g.size(); ++i) {
    const SO3& a = g[i].value;
    const SO3& b = g[(i + 1) % g.size()].value;
    const SO3& c = g[(i + 2) % g.size()].value;
    const std::string& label = g[i].label;
    const Matrix3 Ra = a.matrix();
    assoc.update(max_abs_diff(((a * b) * c).matrix(), (a * (b * c)).matrix()), label);
    ident.update(std::max(max_abs_diff((a * SO3::identity()).matrix(), Ra),
                          max_abs_diff((SO3::identity() * a).matrix(), Ra)),
                 label);
    inv.update(std::max(max_abs_diff((a * a.inverse()).matrix(), I),
                        max_abs_diff((a.inverse() * a).matrix(), I)),
               label);
    product.update(max_abs_diff((a * b).matrix(), Ra * b.matrix()), label);
    const Vector3 v = g[(i + 3) % g.size()].value.log() + Vector3(1.0, 2.0, -0.5);
    action.update(max_abs_diff(a * v, Ra * v) / (1.0 + v.norm()), label);
    inverse_matrix.update(std::max(max_abs_diff(a.inverse().matrix(), Matrix3(Ra.inverse())),
                                   max_abs_diff(a.inverse().matrix(), Matrix3(Ra.transpose()))),
                          label);
    orthonormal.update(
        std::max(max_abs_diff(Matrix3(Ra.transpose() * Ra), I), std::abs(Ra.determinant() - 1.0)),
        label);
  }
  for (Worst* w : {&assoc, &ident, &inv, &product, &action, &inverse_matrix, &orthonormal})
    w->check(kAlgebraTol);
}

// exp against Rodrigues' formula in long double and against Eigen::AngleAxis, for every rotation
// vector sample including 20 and 30 rad. Entries are <= 1 (absolute errors); the quaternion
// route of SO3::exp rounds a few times: tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(exp_matches_rodrigues_and_angle_axis) {
  Worst rodrigues("exp(w) - Rodrigues(w) [long double]"), angle_axis("exp(w) - AngleAxis(w)");
  for (const auto& [label, w] : samples()) {
    const Matrix3 R = SO3::exp(w).matrix();
    rodrigues.update(
        static_cast<double>(max_abs_diff(R.cast<long double>(), rodrigues_long_double(w))), label);
    const double t = w.norm();
    const Matrix3 R_aa =
        t == 0.0 ? Matrix3::Identity() : Eigen::AngleAxisd(t, w / t).toRotationMatrix();
    angle_axis.update(max_abs_diff(R, R_aa), label);
  }
  rodrigues.check(kAlgebraTol);
  angle_axis.check(kAlgebraTol);
}

// exp(log g) = g for every rotation (near pi, beyond pi, large tangents, exact half turns):
// entries <= 1, tolerance kAlgebraTol absolute. |log g| <= pi up to the rounding of the norm
// (pi (1 + 2 eps)). log(exp w) = w inside the injectivity radius |w| < pi, and for |w| >= pi
// log(exp w) is the wrapped vector (|w| mod 2 pi, computed in long double): error relative to
// 1 + |w|, tolerance kAlgebraTol (the angle 2 atan2(|v|, w) is well conditioned everywhere).
BOOST_AUTO_TEST_CASE(exp_log_round_trips) {
  Worst exp_log("exp(log g) - g"), angle("|log g| / pi - 1 (when > 0)"),
      log_exp("log(exp w) - w, |w| < pi"), wrapped("log(exp w) - wrap(w), |w| > pi");
  for (const auto& [label, g] : group()) {
    const Vector3 w = g.log();
    exp_log.update(max_abs_diff(SO3::exp(w).matrix(), g.matrix()), label);
    angle.update(std::max(0.0, w.norm() / kPi - 1.0), label);
  }
  for (const auto& [label, w] : samples()) {
    const double t = w.norm();
    if (std::abs(t - kPi) < 1e-12) continue;  // the exact half turns: see log_at_and_near_pi
    const Vector3 l = SO3::exp(w).log();
    (t < kPi ? log_exp : wrapped)
        .update(max_abs_diff(l, wrapped_long_double(w)) / (1.0 + t), label);
  }
  exp_log.check(kAlgebraTol);
  angle.check(2.0 * kEps);
  log_exp.check(kAlgebraTol);
  wrapped.check(kAlgebraTol);
}

// Near and at pi. log(exp w) with |w| = pi - d, d in {1e-6, 1e-9, 1e-12}, 50 random axes each
// plus the hard samples, from the stored quaternion (SO3::exp(w).log()) and through a rotation
// matrix (SO3::from_matrix(R).log(), Shepperd's method). Near pi the rotation vector is well
// conditioned in absolute terms: theta = 2 atan2(|v|, q_w) moves by 2 d(q_w), and the axis comes
// from the O(1) vector part, so both routes return w to a few eps absolute, not to 1e-9 * cond
// as a log through (R - R^T)/(2 sin theta) would. Tolerance kAlgebraTol absolute for both.
// At exactly pi (and for the exact half-turn matrices) log returns w or -w.
BOOST_AUTO_TEST_CASE(log_at_and_near_pi) {
  Worst quaternion_route("log(exp w) - w, |w| = pi - d"),
      matrix_route("log(R(w)) - w via matrix, |w| = pi - d"),
      at_pi("min |log(exp w) -/+ w|, |w| = pi");
  std::vector<Labelled<Vector3>> near_pi;
  Random rng(kSeed + 10);
  for (double d : {1e-6, 1e-9, 1e-12})
    for (int i = 0; i < 50; ++i)
      near_pi.push_back(
          {"pi-" + describe(d) + " axis #" + std::to_string(i), (kPi - d) * rng.unit_vector()});
  for (const auto& s : samples()) near_pi.push_back(s);
  for (const auto& [label, w] : near_pi) {
    const double t = w.norm();
    if (std::abs(t - kPi) < 1e-13) {
      const Vector3 l = SO3::exp(w).log();
      const Vector3 l_matrix = SO3::from_matrix(SO3::exp(w).matrix()).log();
      for (const Vector3& x : {l, l_matrix})
        at_pi.update(std::min(max_abs_diff(x, w), max_abs_diff(x, Vector3(-w))), label);
    } else if (kPi - t > 0.0 && kPi - t <= 1.1e-6) {
      quaternion_route.update(max_abs_diff(SO3::exp(w).log(), w), label);
      matrix_route.update(max_abs_diff(SO3::from_matrix(SO3::exp(w).matrix()).log(), w), label);
    }
  }
  for (int axis = 0; axis < 3; ++axis) {
    Matrix3 R = -Matrix3::Identity();
    R(axis, axis) = 1.0;
    const Vector3 expected = kPi * Vector3::Unit(axis);
    const Vector3 l = SO3::from_matrix(R).log();
    at_pi.update(std::min(max_abs_diff(l, expected), max_abs_diff(l, Vector3(-expected))),
                 "half turn about axis " + std::to_string(axis));
  }
  quaternion_route.check(kAlgebraTol);
  matrix_route.check(kAlgebraTol);
  at_pi.check(kAlgebraTol);
}

// (1.11), (1.12): Ad_R = R and R hat(x) R^T = hat(R x). Entries of order |x|; tolerance
// kAlgebraTol (1 + |x|).
BOOST_AUTO_TEST_CASE(adjoint) {
  Worst ad_is_R("Ad() - matrix()"), conjugation("R hat(x) R^T - hat(R x)");
  const auto& g = group();
  const auto& s = samples();
  for (std::size_t i = 0; i < g.size(); ++i) {
    const SO3& R = g[i].value;
    const Vector3& x = s[i % s.size()].value;
    const Matrix3 M = R.matrix();
    ad_is_R.update(max_abs_diff(R.Ad(), M), g[i].label);
    conjugation.update(
        max_abs_diff(Matrix3(M * so3::hat(x) * M.transpose()), so3::hat(R * x)) / (1.0 + x.norm()),
        g[i].label + " on " + s[i % s.size()].label);
  }
  ad_is_R.check(0.0);
  conjugation.check(kAlgebraTol);
}
