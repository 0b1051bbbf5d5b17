// The box-constrained QP of control-limited DDP (solvers/control/box_qp.hpp) against closed
// forms (interior: -H^-1 g; one variable: the clamped minimiser) and against enumeration of
// every active set (3^n for n = 4: each variable free, at its lower or at its upper bound), which
// gives the exact optimum of a convex QP.
#define BOOST_TEST_MODULE control_box_qp
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <algorithm>
#include <vector>

#include <Eigen/Cholesky>

#include "rodlab/solvers/control/box_qp.hpp"

namespace c = rodlab::solvers::control;

namespace {

double value(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, const Eigen::VectorXd& x) {
  return 0.5 * x.dot(H * x) + g.dot(x);
}

/// The exact optimum by enumeration: for each assignment of the variables to {free, lower,
/// upper}, the minimiser over the free ones with the rest fixed, kept when feasible.
Eigen::VectorXd enumerate(const Eigen::MatrixXd& H, const Eigen::VectorXd& g,
                          const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const int n = static_cast<int>(g.size());
  double best = std::numeric_limits<double>::infinity();
  Eigen::VectorXd best_x;
  int combos = 1;
  for (int i = 0; i < n; ++i) combos *= 3;
  for (int code = 0; code < combos; ++code) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    std::vector<int> free;
    for (int i = 0, c = code; i < n; ++i, c /= 3) {
      if (c % 3 == 0) free.push_back(i);
      else x[i] = c % 3 == 1 ? lo[i] : hi[i];
    }
    if (!free.empty()) {
      const int f = static_cast<int>(free.size());
      Eigen::MatrixXd Hff(f, f);
      Eigen::VectorXd rhs(f);
      for (int a = 0; a < f; ++a) {
        rhs[a] = -g[free[a]];
        for (int i = 0; i < n; ++i)
          if (std::find(free.begin(), free.end(), i) == free.end()) rhs[a] -= H(free[a], i) * x[i];
        for (int b = 0; b < f; ++b) Hff(a, b) = H(free[a], free[b]);
      }
      const Eigen::VectorXd xf = Hff.llt().solve(rhs);
      for (int a = 0; a < f; ++a) x[free[a]] = xf[a];
    }
    if (((x - lo).array() < -1e-12).any() || ((hi - x).array() < -1e-12).any()) continue;
    const double v = value(H, g, x);
    if (v < best) best = v, best_x = x;
  }
  return best_x;
}

}  // namespace

BOOST_AUTO_TEST_CASE(interior_minimiser_is_the_newton_step) {
  Eigen::MatrixXd H(2, 2);
  H << 4, 1, 1, 3;
  Eigen::VectorXd g(2);
  g << 1, -2;
  const auto r = c::solve_box_qp(H, g, Eigen::VectorXd::Constant(2, -10),
                                 Eigen::VectorXd::Constant(2, 10), Eigen::VectorXd::Zero(2));
  BOOST_REQUIRE(r.ok);
  BOOST_TEST((r.x - H.llt().solve(-g)).norm() < 1e-14);
  BOOST_TEST(r.free.sum() == 2);
}

BOOST_AUTO_TEST_CASE(one_variable_is_clamped) {
  const Eigen::MatrixXd H = Eigen::MatrixXd::Constant(1, 1, 2.0);
  const Eigen::VectorXd g = Eigen::VectorXd::Constant(1, -10.0);  // minimiser 5, bound 1
  const auto r = c::solve_box_qp(H, g, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1),
                                 Eigen::VectorXd::Zero(1));
  BOOST_REQUIRE(r.ok);
  BOOST_TEST(r.x[0] == 1.0);
  BOOST_TEST(r.free[0] == 0);
}

// 200 random convex QPs in 4 variables (fixed seed), boxes that cut the unconstrained minimiser:
// the value equals the enumerated optimum to 1e-12 (relative) and the KKT signs hold.
BOOST_AUTO_TEST_CASE(random_problems_match_enumeration) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  int clamped_seen = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::MatrixXd M(4, 4);
    for (int i = 0; i < 16; ++i) M(i / 4, i % 4) = U(rng);
    const Eigen::MatrixXd H = M * M.transpose() + 0.1 * Eigen::MatrixXd::Identity(4, 4);
    Eigen::VectorXd g(4), lo(4), hi(4), x0(4);
    for (int i = 0; i < 4; ++i) {
      g[i] = 3 * U(rng);
      lo[i] = -std::abs(U(rng));
      hi[i] = std::abs(U(rng));
      x0[i] = U(rng);
    }
    const auto r = c::solve_box_qp(H, g, lo, hi, x0);
    BOOST_REQUIRE(r.ok);
    const Eigen::VectorXd x = enumerate(H, g, lo, hi);
    BOOST_TEST(std::abs(value(H, g, r.x) - value(H, g, x)) <= 1e-12 * (1 + std::abs(value(H, g, x))));
    const Eigen::VectorXd grad = g + H * r.x;
    for (int i = 0; i < 4; ++i) {
      if (r.x[i] <= lo[i]) BOOST_TEST(grad[i] >= -1e-10);
      else if (r.x[i] >= hi[i]) BOOST_TEST(grad[i] <= 1e-10);
      else BOOST_TEST(std::abs(grad[i]) <= 1e-9);
    }
    clamped_seen += 4 - r.free.sum();
  }
  BOOST_TEST(clamped_seen > 100);  // the bounds were active in most problems
}
