#define BOOST_TEST_MODULE box_qp
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include <Eigen/Cholesky>

#include "rodlab/solvers/common/box_qp.hpp"

// rodlab/solvers/common/box_qp.hpp. Reference: enumeration of every active set (each unknown at
// lo, at hi or free, 3^n cases for n <= 6): the free unknowns' Newton system solved with the
// others at their bounds, the best feasible point kept. For a strictly convex QP that is the
// minimiser; the active-set solution must match its objective to 1e-12 (relative) and its point
// to 1e-8.

using namespace rodlab::solvers;

namespace {

double objective(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, const Eigen::VectorXd& x) {
  return 0.5 * x.dot(H * x) + g.dot(x);
}

Eigen::VectorXd enumerate(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const int n = static_cast<int>(g.size());
  int cases = 1;
  for (int k = 0; k < n; ++k) cases *= 3;
  Eigen::VectorXd best(n);
  double best_value = std::numeric_limits<double>::infinity();
  for (int c = 0; c < cases; ++c) {
    Eigen::VectorXd x(n);
    std::vector<int> free;
    for (int k = 0, code = c; k < n; ++k, code /= 3) {
      if (code % 3 == 0) x[k] = lo[k];
      else if (code % 3 == 1) x[k] = hi[k];
      else free.push_back(k), x[k] = 0.0;
    }
    if (!free.empty()) {
      const int f = static_cast<int>(free.size());
      Eigen::MatrixXd Hf(f, f);
      Eigen::VectorXd rhs(f);
      for (int i = 0; i < f; ++i) {
        rhs[i] = -g[free[i]];
        for (int k = 0; k < n; ++k)
          if (std::find(free.begin(), free.end(), k) == free.end()) rhs[i] -= H(free[i], k) * x[k];
        for (int j = 0; j < f; ++j) Hf(i, j) = H(free[i], free[j]);
      }
      const Eigen::VectorXd y = Hf.llt().solve(rhs);
      for (int i = 0; i < f; ++i) x[free[i]] = y[i];
    }
    if (((x.array() < lo.array() - 1e-12) || (x.array() > hi.array() + 1e-12)).any()) continue;
    const double value = objective(H, g, x);
    if (value < best_value) best_value = value, best = x;
  }
  return best;
}

}  // namespace

BOOST_AUTO_TEST_CASE(matches_enumeration_of_active_sets) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 1 + trial % 6;
    Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n + 2, n, [&] { return U(rng); });
    // Ill-conditioned ones too (a weight 1e-8 on the identity, as in inverse statics' 3 x 4).
    if (trial % 3 == 0) A = A.topRows(std::max(1, n - 1)).eval();
    Eigen::MatrixXd H = A.transpose() * A;
    H.diagonal().array() += trial % 3 == 0 ? 1e-8 : 1e-3;
    Eigen::VectorXd g(n), lo(n), hi(n), x0(n);
    for (int k = 0; k < n; ++k) {
      g[k] = 2.0 * U(rng);
      lo[k] = -0.5 + 0.4 * U(rng);
      hi[k] = lo[k] + 0.8 + 0.4 * U(rng);
      x0[k] = U(rng);  // any start: it is clamped
    }
    const auto r = solve_box_qp(H, g, lo, hi, x0);
    BOOST_TEST_REQUIRE(r.ok, "trial " << trial << ": " << r.reason);
    const Eigen::VectorXd& x = r.x;
    const Eigen::VectorXd ref = enumerate(H, g, lo, hi);
    const double f = objective(H, g, x), fr = objective(H, g, ref);
    BOOST_TEST(f <= fr + 1e-12 * std::max(1.0, std::abs(fr)), "trial " << trial);
    BOOST_TEST((x - ref).lpNorm<Eigen::Infinity>() <= 1e-8 / (trial % 3 == 0 ? 1e-4 : 1.0), "trial " << trial);
    BOOST_TEST(((x.array() >= lo.array()) && (x.array() <= hi.array())).all());
  }
}

BOOST_AUTO_TEST_CASE(bad_sizes_throw) {
  const Eigen::MatrixXd H = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd g = Eigen::VectorXd::Zero(2), lo = Eigen::VectorXd::Constant(2, 1.0),
                        hi = Eigen::VectorXd::Zero(2), x = Eigen::VectorXd::Zero(2);
  BOOST_CHECK_THROW(solve_box_qp(H, g, lo, hi, x), std::invalid_argument);  // lo > hi
  const Eigen::VectorXd g3 = Eigen::VectorXd::Zero(3);
  BOOST_CHECK_THROW(solve_box_qp(H, g3, hi, lo, x), std::invalid_argument);
}

// Closed forms: an interior minimiser is the Newton step -H^-1 g, all variables free; one
// variable whose minimiser (5) lies beyond its bound (1) is clamped there.
BOOST_AUTO_TEST_CASE(closed_forms) {
  Eigen::MatrixXd H(2, 2);
  H << 4, 1, 1, 3;
  Eigen::VectorXd g(2);
  g << 1, -2;
  const auto r = solve_box_qp(H, g, Eigen::VectorXd::Constant(2, -10),
                              Eigen::VectorXd::Constant(2, 10), Eigen::VectorXd::Zero(2));
  BOOST_REQUIRE(r.ok);
  BOOST_TEST((r.x - H.llt().solve(-g)).norm() < 1e-14);
  BOOST_TEST(r.free.sum() == 2);
  const auto one = solve_box_qp(Eigen::MatrixXd::Constant(1, 1, 2.0), Eigen::VectorXd::Constant(1, -10.0),
                                Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1),
                                Eigen::VectorXd::Zero(1));
  BOOST_REQUIRE(one.ok);
  BOOST_TEST(one.x[0] == 1.0);
  BOOST_TEST(one.free[0] == 0);
}
