#define BOOST_TEST_MODULE small_angle
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rodlab/lie/small_angle.hpp"

// The small-angle kernels (lie/small_angle.hpp, used by the `variational` scheme) against the
// general functions they replace: coefficients e, f, c, SE3::exp, SE3::log and
// se3::dexp_inv_transpose_apply and se3::dexp_inv_apply (themselves tested against long-double series in test_dexp.cpp
// and test_coefficients.cpp). Angles from 0 to 0.3 rad, dense around the branch points
// kTinyAngle, kBcdShortAngle and kSmallAngle, random directions, translations of 1e-3..1. Tolerances: the
// coefficients to 2 eps relative; group elements and vectors to 4 eps relative to their size
// (the short series drop terms below 1e-17; the rest is rounding in a different order).

namespace {

using namespace rodlab::lie;
namespace sa = rodlab::lie::small_angle;
constexpr double kEps = std::numeric_limits<double>::epsilon();

std::vector<double> angles() {
  std::vector<double> t{0.0, 1e-300, 1e-20, 1e-12, 1e-8, 1e-6, 1e-4, 1e-3};
  for (double s : {sa::kTinyAngle, sa::kBcdShortAngle, sa::kSmallAngle, 2.0 * std::atan(std::sqrt(0.0158)),
                   2.0 * std::atan(1e-2)})
    for (double r : {1 - 1e-3, 1 - 1e-9, 1.0, 1 + 1e-9, 1 + 1e-3}) t.push_back(s * r);
  for (int i = 1; i <= 300; ++i) t.push_back(0.3 * i / 300.0);
  return t;
}

std::vector<Vector6> twists() {
  std::mt19937 rng(20261121u);
  std::normal_distribution<double> n;
  std::vector<Vector6> out;
  for (double t : angles())
    for (double scale : {1e-3, 1.0}) {
      Vector3 w(n(rng), n(rng), n(rng));
      w *= t / w.norm();
      out.push_back(se3::join(w, scale * Vector3(n(rng), n(rng), n(rng))));
    }
  return out;
}

double rel(double a, double b) { return a == b ? 0.0 : std::abs(a - b) / std::abs(b); }

}  // namespace

BOOST_AUTO_TEST_CASE(coefficients_match_the_general_functions) {
  double worst_e = 0, worst_f = 0, worst_c = 0;
  for (double t : angles()) {
    const auto k = sa::ef(t * t);
    worst_e = std::max(worst_e, rel(k.e, coefficients::e(t)));
    worst_f = std::max(worst_f, rel(k.f, coefficients::f(t)));
    worst_c = std::max(worst_c, rel(sa::c(t * t), coefficients::c(t)));
  }
  BOOST_TEST_MESSAGE("max relative error / eps: e " << worst_e / kEps << ", f " << worst_f / kEps
                                                     << ", c " << worst_c / kEps);
  BOOST_TEST(worst_e <= 2 * kEps);
  BOOST_TEST(worst_f <= 2 * kEps);
  BOOST_TEST(worst_c <= 2 * kEps);
}

BOOST_AUTO_TEST_CASE(exp_log_and_dexp_inv_transpose_match) {
  std::mt19937 rng(7u);
  std::normal_distribution<double> n;
  double worst_exp = 0, worst_log = 0, worst_k = 0, worst_dt = 0, worst_di = 0;
  for (const Vector6& xi : twists()) {
    const SE3 a = sa::exp(xi), b = SE3::exp(xi);
    const double qa = (a.rotation().quaternion().coeffs() - b.rotation().quaternion().coeffs()).norm();
    const double pa = (a.translation() - b.translation()).norm() / std::max(b.translation().norm(), 1e-300);
    worst_exp = std::max({worst_exp, qa, pa});

    sa::EF k;
    const Vector6 la = sa::log(b, k), lb = b.log();
    worst_log = std::max(worst_log, (la - lb).norm() / std::max(lb.norm(), 1e-300));
    const double t = lb.head<3>().norm();
    worst_k = std::max({worst_k, rel(k.e, coefficients::e(t)), rel(k.f, coefficients::f(t))});

    const Vector6 lambda(n(rng), n(rng), n(rng), n(rng), n(rng), n(rng));
    const Vector6 da = sa::dexp_inv_transpose_apply(xi, lambda),
                  db = se3::dexp_inv_transpose_apply(xi, lambda);
    worst_dt = std::max(worst_dt, (da - db).norm() / db.norm());
    const Vector6 ia = sa::dexp_inv_apply(xi, lambda), ib = se3::dexp_inv_apply(xi, lambda);
    worst_di = std::max(worst_di, (ia - ib).norm() / ib.norm());
  }
  BOOST_TEST_MESSAGE("max relative error / eps: exp " << worst_exp / kEps << ", log "
                     << worst_log / kEps << ", log's e, f " << worst_k / kEps
                     << ", dexp^-T " << worst_dt / kEps << ", dexp^-1 " << worst_di / kEps);
  BOOST_TEST(worst_exp <= 4 * kEps);
  BOOST_TEST(worst_log <= 4 * kEps);
  BOOST_TEST(worst_k <= 4 * kEps);
  BOOST_TEST(worst_dt <= 4 * kEps);
  BOOST_TEST(worst_di <= 4 * kEps);
}

// The dexp kernels with the short b, c, d1, d2 series (the staggered shooting march's inner loop)
// against se3::dexp_apply and se3::dexp_transpose_apply (themselves against the closed-form
// matrix in test_dexp.cpp), over the same twists, large angles included (fall back).
BOOST_AUTO_TEST_CASE(dexp_and_its_transpose_match) {
  std::mt19937 rng(11u);
  std::normal_distribution<double> n;
  double worst = 0.0, worst_t = 0.0;
  for (const Vector6& xi : twists()) {
    const Vector6 y(n(rng), n(rng), n(rng), n(rng), n(rng), n(rng));
    const sa::BCD k = sa::bcd(xi.head<3>().squaredNorm());
    const Vector6 a = sa::dexp_apply(xi, y, k), b = se3::dexp_apply(xi, y);
    const Vector6 at = sa::dexp_transpose_apply(xi, y, k), bt = se3::dexp_transpose_apply(xi, y);
    worst = std::max(worst, (a - b).norm() / b.norm());
    worst_t = std::max(worst_t, (at - bt).norm() / bt.norm());
  }
  BOOST_TEST_MESSAGE("max relative error / eps: dexp " << worst / kEps << ", dexp^T " << worst_t / kEps);
  BOOST_TEST(worst <= 4 * kEps);
  BOOST_TEST(worst_t <= 4 * kEps);
}

// Beyond the bounds every kernel defers to the general function: identical results.
BOOST_AUTO_TEST_CASE(large_angles_fall_back) {
  const Vector6 xi = se3::join(Vector3(0.3, -1.2, 2.0), Vector3(0.1, 0.2, -0.3));
  const SE3 a = sa::exp(xi), b = SE3::exp(xi);
  BOOST_TEST((a.rotation().quaternion().coeffs() - b.rotation().quaternion().coeffs()).norm() == 0.0);
  BOOST_TEST((a.translation() - b.translation()).norm() == 0.0);
  BOOST_TEST((sa::log(b) - b.log()).norm() == 0.0);
  const Vector6 lambda = Vector6::LinSpaced(6, -1.0, 2.0);
  BOOST_TEST((sa::dexp_inv_transpose_apply(xi, lambda) - se3::dexp_inv_transpose_apply(xi, lambda)).norm() <=
             4 * kEps * lambda.norm());
  BOOST_TEST((sa::dexp_inv_apply(xi, lambda) - se3::dexp_inv_apply(xi, lambda)).norm() <=
             4 * kEps * lambda.norm());
}
