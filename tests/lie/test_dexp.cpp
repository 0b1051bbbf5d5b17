#define BOOST_TEST_MODULE dexp
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "finite_difference.hpp"
#include "hard_samples.hpp"
#include "rodlab/lie/se3.hpp"
#include "rodlab/lie/so3.hpp"

// dexp and dexp^-1 on SO(3) and SE(3): closed forms against long double series, the dexp
// convention against finite differences of exp, the Jacobians of exp and log, and the truncated
// series used by RKMK (thesis (2.71)-(2.77), (2.84); docs/conventions.md).
//
// THE CONVENTION (thesis (2.71), (2.84); Iserles et al. 2000). dexp_x = sum_k ad_x^k / (k+1)!.
// For a curve x(s) = x0 + s d in the algebra,
//     (d/ds exp(x)) exp(x)^-1 = hat(dexp_x d)          (left-trivialised), and
//     exp(x)^-1 (d/ds exp(x)) = hat(dexp_{-x} d)       (right-trivialised).
// The rod uses the right-trivialised form: g = g_i exp(theta), g' = g hat(xi) gives
// dexp_{-theta} theta' = xi, i.e. theta' = dexp^-1_{-theta} xi (2.84). So
// se3::right_jacobian(x) = dexp(-x) and se3::left_jacobian(x) = dexp(x).

namespace {

using namespace rodlab::lie;
using namespace rodlab::lie::testing;

template <int N>
using MatrixL = Eigen::Matrix<long double, N, N>;

/// sum_{k < terms} coef(k) A^k in long double.
template <int N, class Coef>
MatrixL<N> power_series(const MatrixL<N>& A, const Coef& coef, int terms) {
  MatrixL<N> sum = MatrixL<N>::Zero(), power = MatrixL<N>::Identity();
  for (int k = 0; k < terms; ++k) {
    sum += coef(k) * power;
    power = power * A;
  }
  return sum;
}

long double inverse_factorial_shifted(int k) {  // 1 / (k+1)!
  long double r = 1.0L;
  for (int i = 2; i <= k + 1; ++i) r /= i;
  return r;
}

// dexp: 60 terms; the tail after ad^59 is below 8^60 / 61! * 60 |nu| ~ 1e-28 for |omega| <= 8,
// and the largest term (~ k |omega|^(k-1) |nu| / (k+1)! ~ 1e4) cancels to 1e4 eps_ld ~ 1e-15
// relative at worst, which is why the comparison stops at |omega| = 8 (at 20 rad it would be 1e-8).
constexpr int kDexpTerms = 60;
constexpr double kDexpSeriesMaxAngle = 8.0;
// dexp^-1: B_k/k! ~ 2 (2 pi)^-k, so the series converges like (|omega| / 2 pi)^k. 60 terms would
// leave (5 / 2 pi)^60 ~ 1e-6 at |omega| = 5; 240 terms leave 2 (5 / 2 pi)^240 * 240 |nu| ~ 1e-20.
constexpr int kDexpInvTerms = 240;
constexpr double kDexpInvSeriesMaxAngle = 5.0;

template <int N>
MatrixL<N> dexp_series_long_double(const Eigen::Matrix<double, N, N>& ad) {
  return power_series<N>(ad.template cast<long double>(), inverse_factorial_shifted, kDexpTerms);
}
template <int N>
MatrixL<N> dexp_inv_series_long_double(const Eigen::Matrix<double, N, N>& ad) {
  return power_series<N>(ad.template cast<long double>(), bernoulli_over_factorial_reference,
                         kDexpInvTerms);
}

template <class A, class B>
double long_double_error(const Eigen::MatrixBase<A>& value, const Eigen::MatrixBase<B>& reference) {
  const auto value_l = value.template cast<long double>();
  return static_cast<double>(max_abs_diff(value_l, reference) / (1.0L + max_abs(reference)));
}

/// A direction per twist sample, from the fixed seed.
const std::vector<Vector6>& directions() {
  static const std::vector<Vector6> d = [] {
    Random rng(kSeed + 20);
    std::vector<Vector6> out;
    for (std::size_t i = 0; i < twists().size(); ++i)
      out.push_back(se3::join(rng.unit_vector(), rng.unit_vector()));
    return out;
  }();
  return d;
}

/// max |A B - I|, |B A - I| relative to |A| |B| (the size of the rounding in the products).
template <int N>
double inverse_error(const Eigen::Matrix<double, N, N>& A, const Eigen::Matrix<double, N, N>& B) {
  const Eigen::Matrix<double, N, N> I = Eigen::Matrix<double, N, N>::Identity();
  return std::max(max_abs_diff(Eigen::Matrix<double, N, N>(A * B), I),
                  max_abs_diff(Eigen::Matrix<double, N, N>(B * A), I)) /
         (max_abs(A) * max_abs(B));
}

}  // namespace

// dexp_x dexp^-1_x = I for |omega| <= 6 (dexp^-1 has its pole at |omega| = 2 pi; at 6 rad the
// entries of dexp^-1 reach ~1e3 for |nu| = 10). Error relative to |dexp| |dexp^-1|, the scale of
// the rounding of the products; tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(dexp_times_dexp_inv_is_identity) {
  Worst so3_w("so3 dexp dexp^-1 - I"), se3_w("se3 dexp dexp^-1 - I");
  for (const auto& [label, xi] : with_angle(twists(), 0.0, 6.0)) {
    const Vector3 w = xi.head<3>();
    so3_w.update(inverse_error<3>(so3::dexp(w), so3::dexp_inv(w)), label);
    se3_w.update(inverse_error<6>(se3::dexp(xi), se3::dexp_inv(xi)), label);
  }
  so3_w.check(kAlgebraTol);
  se3_w.check(kAlgebraTol);
}

// Closed forms against the defining series summed in long double: dexp for |omega| <= 8
// (60 terms), dexp^-1 for |omega| <= 5 (240 terms), see the constants above for why. Errors
// relative to 1 + max|reference|; tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(closed_forms_match_long_double_series) {
  Worst so3_dexp("so3::dexp - series"), se3_dexp("se3::dexp - series"),
      so3_inv("so3::dexp_inv - series"), se3_inv("se3::dexp_inv - series");
  for (const auto& [label, xi] : with_angle(twists(), 0.0, kDexpSeriesMaxAngle)) {
    const Vector3 w = xi.head<3>();
    so3_dexp.update(long_double_error(so3::dexp(w), dexp_series_long_double<3>(so3::hat(w))),
                    label);
    se3_dexp.update(long_double_error(se3::dexp(xi), dexp_series_long_double<6>(se3::ad(xi))),
                    label);
    if (w.norm() <= kDexpInvSeriesMaxAngle) {
      so3_inv.update(
          long_double_error(so3::dexp_inv(w), dexp_inv_series_long_double<3>(so3::hat(w))), label);
      se3_inv.update(
          long_double_error(se3::dexp_inv(xi), dexp_inv_series_long_double<6>(se3::ad(xi))), label);
    }
  }
  for (Worst* w : {&so3_dexp, &se3_dexp, &so3_inv, &se3_inv}) w->check(kAlgebraTol);
}

// The _apply forms equal the matrix forms, for all samples (dexp everywhere, dexp^-1 for
// |omega| < 2 pi, so up to 6 here); so3 dexp / dexp^-1 are the diagonal blocks of the se3 ones and
// the upper-right blocks vanish. Errors relative to (1 + |D|)(1 + |y|); tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(apply_forms_and_blocks) {
  Worst so3_apply("so3::dexp_apply - dexp y"), so3_inv_apply("so3::dexp_inv_apply - dexp_inv y"),
      se3_apply("se3::dexp_apply - dexp y"), se3_inv_apply("se3::dexp_inv_apply - dexp_inv y"),
      se3_inv_t_apply("se3::dexp_inv_transpose_apply - dexp_inv^T y"),
      se3_t_apply("se3::dexp_transpose_apply - dexp^T y"),
      blocks("se3 dexp, dexp_inv diagonal blocks - so3 ones"),
      zero_block("se3 dexp, dexp_inv upper-right block");
  const auto& x = twists();
  const auto& d = directions();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto& [label, xi] = x[i];
    const Vector6 y = 3.0 * d[i];
    const Vector3 w = xi.head<3>(), y3 = y.head<3>();
    const Matrix6 D = se3::dexp(xi);
    const Matrix3 A = so3::dexp(w);
    so3_apply.update(
        max_abs_diff(so3::dexp_apply(w, y3), Vector3(A * y3)) / ((1.0 + max_abs(A)) * 4.0), label);
    se3_apply.update(
        max_abs_diff(se3::dexp_apply(xi, y), Vector6(D * y)) / ((1.0 + max_abs(D)) * 4.0), label);
    se3_t_apply.update(max_abs_diff(se3::dexp_transpose_apply(xi, y), Vector6(D.transpose() * y)) /
                           ((1.0 + max_abs(D)) * 4.0),
                       label);
    double block = std::max(max_abs_diff(D.topLeftCorner<3, 3>(), A),
                            max_abs_diff(D.bottomRightCorner<3, 3>(), A)) /
                   (1.0 + max_abs(A));
    double zero = max_abs(D.topRightCorner<3, 3>());
    if (w.norm() < 6.01) {
      const Matrix6 Dinv = se3::dexp_inv(xi);
      const Matrix3 Ainv = so3::dexp_inv(w);
      so3_inv_apply.update(max_abs_diff(so3::dexp_inv_apply(w, y3), Vector3(Ainv * y3)) /
                               ((1.0 + max_abs(Ainv)) * 4.0),
                           label);
      se3_inv_apply.update(max_abs_diff(se3::dexp_inv_apply(xi, y), Vector6(Dinv * y)) /
                               ((1.0 + max_abs(Dinv)) * 4.0),
                           label);
      se3_inv_t_apply.update(max_abs_diff(se3::dexp_inv_transpose_apply(xi, y),
                                          Vector6(Dinv.transpose() * y)) /
                                 ((1.0 + max_abs(Dinv)) * 4.0),
                             label);
      block = std::max(block, std::max(max_abs_diff(Dinv.topLeftCorner<3, 3>(), Ainv),
                                       max_abs_diff(Dinv.bottomRightCorner<3, 3>(), Ainv)) /
                                  (1.0 + max_abs(Ainv)));
      zero = std::max(zero, max_abs(Dinv.topRightCorner<3, 3>()));
    }
    blocks.update(block, label);
    zero_block.update(zero, label);
  }
  for (Worst* w :
       {&so3_apply, &so3_inv_apply, &se3_apply, &se3_inv_apply, &se3_inv_t_apply, &se3_t_apply,
        &blocks})
    w->check(kAlgebraTol);
  zero_block.check(0.0);
}

// The convention (see the top of this file), against central differences of the matrix exponential
// along x(s) = x0 + s d at s = 0 (step kFdStep = 1e-6):
//   left:  vee(D exp(x0)^-1) = dexp_{x0} d,    right: vee(exp(x0)^-1 D) = dexp_{-x0} d,
// with D = (exp(x0 + h d) - exp(x0 - h d)) / 2h, for SO(3) and SE(3) over all samples (including
// 20 and 30 rad). FD error ~ h^2 + eps |g| / h; tolerance 1e-8 (1 + |x0|). The swapped signs must
// fail: on every random sample with |omega| >= 0.1 (where dexp_x d and dexp_{-x} d differ by
// ~|omega| |d| / 2 >> 1e-8) the wrong-sign variant is off by more than 100x the tolerance, so a
// convention flip in se3.hpp cannot pass this test.
BOOST_AUTO_TEST_CASE(dexp_convention_left_and_right_trivialised) {
  constexpr double kTol = 1e-8;
  const double h = kFdStep;
  Worst so3_left("so3 left-trivialised: vee(D R^-1) - dexp_x d"),
      so3_right("so3 right: vee(R^-1 D) - dexp_{-x} d"),
      se3_left("se3 left: vee(D g^-1) - dexp_x d"),
      se3_right("se3 right: vee(g^-1 D) - dexp_{-x} d");
  int random_samples = 0;
  double min_wrong = std::numeric_limits<double>::infinity();
  std::string min_wrong_label;
  const auto& x = twists();
  const auto& dirs = directions();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto& [label, x0] = x[i];
    const Vector6& d = dirs[i];
    const double scale = 1.0 + x0.norm();
    // SE(3)
    const Matrix4 g_inv = SE3::exp(x0).inverse().matrix();
    const Matrix4 D = (SE3::exp(x0 + h * d).matrix() - SE3::exp(x0 - h * d).matrix()) / (2.0 * h);
    const Vector6 left = se3::vee(Matrix4(D * g_inv)), right = se3::vee(Matrix4(g_inv * D));
    se3_left.update(max_abs_diff(left, se3::dexp_apply(x0, d)) / scale, label);
    se3_right.update(max_abs_diff(right, se3::dexp_apply(-x0, d)) / scale, label);
    // SO(3)
    const Vector3 w = x0.head<3>(), dw = d.head<3>();
    const Matrix3 R = SO3::exp(w).matrix();
    const Matrix3 DR = (SO3::exp(w + h * dw).matrix() - SO3::exp(w - h * dw).matrix()) / (2.0 * h);
    so3_left.update(
        max_abs_diff(so3::vee(Matrix3(DR * R.transpose())), so3::dexp_apply(w, dw)) / scale, label);
    so3_right.update(
        max_abs_diff(so3::vee(Matrix3(R.transpose() * DR)), so3::dexp_apply(-w, dw)) / scale,
        label);
    // Wrong signs.
    if (label.rfind("random", 0) == 0 && w.norm() >= 0.1) {
      ++random_samples;
      const double err =
          std::min({max_abs_diff(left, se3::dexp_apply(-x0, d)),
                    max_abs_diff(right, se3::dexp_apply(x0, d)),
                    max_abs_diff(so3::vee(Matrix3(DR * R.transpose())), so3::dexp_apply(-w, dw)),
                    max_abs_diff(so3::vee(Matrix3(R.transpose() * DR)), so3::dexp_apply(w, dw))}) /
          scale;
      if (err < min_wrong) {
        min_wrong = err;
        min_wrong_label = label;
      }
    }
  }
  for (Worst* w : {&so3_left, &so3_right, &se3_left, &se3_right}) w->check(kTol);
  BOOST_TEST_MESSAGE("wrong-sign variants: smallest error "
                     << min_wrong << " over " << random_samples
                     << " random samples with |omega| >= 0.1, at [" << min_wrong_label << "]");
  BOOST_TEST(random_samples > 500);
  BOOST_TEST(min_wrong > 100.0 * kTol, "a wrong-sign variant passes within 100x the tolerance at ["
                                           << min_wrong_label << "]");
}

// dexp as the Jacobian of exp (thesis (2.71); manif's Jr / Jl), against central differences on the
// group: exp(x + d) = exp(x) exp(J_r d + O(d^2)) with J_r = right_jacobian(x) = dexp(-x), and
// exp(x + d) = exp(J_l d + O(d^2)) exp(x) with J_l = left_jacobian(x) = dexp(x). Same for SO(3)
// with so3::dexp(-w), so3::dexp(w). All samples; tolerance 1e-7 relative to 1 + max|J|
// (FD error ~1e-9, see finite_difference.hpp).
BOOST_AUTO_TEST_CASE(dexp_is_the_jacobian_of_exp) {
  Worst helpers("right_jacobian - dexp(-x), left_jacobian - dexp(x)"), se3_right("se3 J_r - FD"),
      se3_left("se3 J_l - FD"), so3_right("so3 J_r - FD"), so3_left("so3 J_l - FD");
  for (const auto& [label, xi] : twists()) {
    const Matrix6 Jr = se3::right_jacobian(xi), Jl = se3::left_jacobian(xi);
    helpers.update(std::max(max_abs_diff(Jr, se3::dexp(-xi)), max_abs_diff(Jl, se3::dexp(xi))),
                   label);
    const SE3 g = SE3::exp(xi);
    const Matrix6 fd_r =
        central_jacobian<6, 6>([&](const Vector6& d) { return right_minus(SE3::exp(xi + d), g); });
    const Matrix6 fd_l = central_jacobian<6, 6>(
        [&](const Vector6& d) { return SE3(SE3::exp(xi + d) * g.inverse()).log(); });
    se3_right.update(scaled_error(Jr, fd_r), label);
    se3_left.update(scaled_error(Jl, fd_l), label);

    const Vector3 w = xi.head<3>();
    const SO3 R = SO3::exp(w);
    const Matrix3 fd_rr =
        central_jacobian<3, 3>([&](const Vector3& d) { return right_minus(SO3::exp(w + d), R); });
    const Matrix3 fd_rl = central_jacobian<3, 3>(
        [&](const Vector3& d) { return SO3(SO3::exp(w + d) * R.inverse()).log(); });
    so3_right.update(scaled_error(so3::dexp(-w), fd_rr), label);
    so3_left.update(scaled_error(so3::dexp(w), fd_rl), label);
  }
  helpers.check(0.0);
  for (Worst* w : {&se3_right, &se3_left, &so3_right, &so3_left}) w->check(1e-7);
}

// dexp^-1 as the Jacobian of log: log(g exp(d)) = log g + dexp^-1_{-log g} d + O(d^2) and
// log(exp(d) g) = log g + dexp^-1_{log g} d + O(d^2) (this is (2.84) with theta = log g). Central
// differences of log over all group samples whose |log g| <= pi - 1e-3: log jumps from omega to
// about -omega across the cut |omega| = pi, so an FD step must not cross it. Tolerance 1e-7
// relative to 1 + max|J|.
BOOST_AUTO_TEST_CASE(dexp_inv_is_the_jacobian_of_log) {
  Worst se3_right("se3 dexp^-1_{-log g} - FD of log(g exp(d))"),
      se3_left("se3 dexp^-1_{log g} - FD of log(exp(d) g)"), so3_right("so3 dexp^-1_{-log R} - FD"),
      so3_left("so3 dexp^-1_{log R} - FD");
  for (const auto& [label, g] : transforms()) {
    const Vector6 l = g.log();
    if (l.head<3>().norm() > kPi - 1e-3) continue;
    const Matrix6 fd_r =
        central_jacobian<6, 6>([&](const Vector6& d) { return SE3(g * SE3::exp(d)).log(); });
    const Matrix6 fd_l =
        central_jacobian<6, 6>([&](const Vector6& d) { return SE3(SE3::exp(d) * g).log(); });
    se3_right.update(scaled_error(se3::dexp_inv(-l), fd_r), label);
    se3_left.update(scaled_error(se3::dexp_inv(l), fd_l), label);
    const SO3& R = g.rotation();
    const Vector3 w = l.head<3>();
    const Matrix3 fd_rr =
        central_jacobian<3, 3>([&](const Vector3& d) { return SO3(R * SO3::exp(d)).log(); });
    const Matrix3 fd_rl =
        central_jacobian<3, 3>([&](const Vector3& d) { return SO3(SO3::exp(d) * R).log(); });
    so3_right.update(scaled_error(so3::dexp_inv(-w), fd_rr), label);
    so3_left.update(scaled_error(so3::dexp_inv(w), fd_rl), label);
  }
  for (Worst* w : {&se3_right, &se3_left, &so3_right, &so3_left}) w->check(1e-7);
}

// Truncated series (RKMK, thesis 2.6.1): explicit sums for q = 0, 1, 2
//   dexp_series:     I,  I + ad/2,  I + ad/2 + ad^2/6
//   dexp_inv_series: I,  I - ad/2,  I - ad/2 + ad^2/12
// and the _apply forms equal the matrix forms for q = 0..8. Errors relative to the size of the
// terms, (1 + |ad|)^q; tolerance kAlgebraTol.
BOOST_AUTO_TEST_CASE(truncated_series_explicit_and_apply) {
  Worst explicit_sums("series(x, q) - explicit sum, q <= 2"),
      apply("series_apply(x, y, q) - series(x, q) y");
  const auto& x = twists();
  const auto& d = directions();
  const Matrix6 I = Matrix6::Identity();
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto& [label, xi] = x[i];
    const Matrix6 A = se3::ad(xi), A2 = A * A;
    const double n = 1.0 + max_abs(A);
    const Matrix6 dexp_expected[3] = {I, I + A / 2.0, I + A / 2.0 + A2 / 6.0};
    const Matrix6 dexp_inv_expected[3] = {I, I - A / 2.0, I - A / 2.0 + A2 / 12.0};
    for (int q = 0; q <= 2; ++q) {
      const double scale = std::pow(n, q);
      explicit_sums.update(max_abs_diff(se3::dexp_series(xi, q), dexp_expected[q]) / scale,
                           label + ", dexp q=" + std::to_string(q));
      explicit_sums.update(max_abs_diff(se3::dexp_inv_series(xi, q), dexp_inv_expected[q]) / scale,
                           label + ", dexp_inv q=" + std::to_string(q));
    }
    for (int q = 0; q <= 8; ++q) {
      const double scale = std::pow(n, q) * max_abs(d[i]);
      apply.update(max_abs_diff(se3::dexp_series_apply(xi, d[i], q),
                                Vector6(se3::dexp_series(xi, q) * d[i])) /
                       scale,
                   label + ", dexp q=" + std::to_string(q));
      apply.update(max_abs_diff(se3::dexp_inv_series_apply(xi, d[i], q),
                                Vector6(se3::dexp_inv_series(xi, q) * d[i])) /
                       scale,
                   label + ", dexp_inv q=" + std::to_string(q));
    }
  }
  explicit_sums.check(kAlgebraTol);
  apply.check(kAlgebraTol);
}

// Truncation order: |series(h x, q) - closed form(h x)| ~ C h^p, where p is the index of the first
// omitted non-zero term. For dexp every term is non-zero: p = q + 1. For dexp^-1 the odd Bernoulli
// numbers beyond B_1 vanish, so p = 2, 4, 4, 6 for q = 1, 2, 3, 4 (q = 2 and q = 3 have the same
// order; p is computed from the exact Bernoulli numbers). Observed order = least-squares slope of
// log error against log h over h = 0.1, 0.05, 0.025, on the 20 first random twists with
// 2 <= |omega| < pi (so that even the q = 4 errors, ~ (2 h)^6 / 30240, stay above 1e-13, far
// above rounding); must be within 0.2 of p.
BOOST_AUTO_TEST_CASE(truncated_series_order) {
  const std::vector<double> hs{0.1, 0.05, 0.025};
  std::vector<Labelled<Vector6>> xs;
  for (const auto& s : with_angle(twists(), 2.0, kPi))
    if (s.label.rfind("random", 0) == 0 && xs.size() < 20) xs.push_back(s);
  BOOST_TEST(xs.size() == 20u);
  auto slope = [&](const std::vector<double>& err) {
    double mx = 0, my = 0;
    for (std::size_t i = 0; i < hs.size(); ++i) {
      mx += std::log(hs[i]) / hs.size();
      my += std::log(err[i]) / hs.size();
    }
    double sxy = 0, sxx = 0;
    for (std::size_t i = 0; i < hs.size(); ++i) {
      sxy += (std::log(hs[i]) - mx) * (std::log(err[i]) - my);
      sxx += (std::log(hs[i]) - mx) * (std::log(hs[i]) - mx);
    }
    return sxy / sxx;
  };
  for (int q = 1; q <= 4; ++q) {
    int p_inv = q + 1;
    while (bernoulli_over_factorial_reference(p_inv) == 0.0L) ++p_inv;
    const int p_dexp = q + 1;
    Worst inv("dexp_inv_series order deviation, q=" + std::to_string(q) + ", expected " +
              std::to_string(p_inv)),
        fwd("dexp_series order deviation, q=" + std::to_string(q) + ", expected " +
            std::to_string(p_dexp));
    double min_err = 1.0;
    for (const auto& [label, xi] : xs) {
      std::vector<double> e_inv, e_fwd;
      for (double h : hs) {
        const Vector6 y = h * xi;
        e_inv.push_back(max_abs_diff(se3::dexp_inv_series(y, q), se3::dexp_inv(y)));
        e_fwd.push_back(max_abs_diff(se3::dexp_series(y, q), se3::dexp(y)));
        min_err = std::min({min_err, e_inv.back(), e_fwd.back()});
      }
      inv.update(std::abs(slope(e_inv) - p_inv), label);
      fwd.update(std::abs(slope(e_fwd) - p_dexp), label);
    }
    BOOST_TEST_MESSAGE("q=" << q << ": smallest truncation error " << min_err);
    BOOST_TEST(min_err > 1e-13);
    inv.check(0.2);
    fwd.check(0.2);
  }
}
