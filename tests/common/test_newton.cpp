#define BOOST_TEST_MODULE newton
#include <boost/test/unit_test.hpp>

// solve_newton (solvers/common/newton.hpp), the damped Newton of the statics' shooting, on
// systems with a known root x*: F(x) = A (x - x*) + 0.1 (x - x*)^3 (componentwise cube), A
// random and diagonally dominant, from x* + 0.5. Five, six and seven unknowns: six (the
// single-shooting statics' base wrench) take the fixed-size QR step, the others the dynamic
// one (newton.cpp newton_step); both must reach the root to the residual tolerance.

#include <random>

#include <Eigen/Dense>

#include "rodlab/solvers/common/newton.hpp"

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

void check_root(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MatrixXd A = MatrixXd::NullaryExpr(n, n, [&] { return u(gen); });
  A.diagonal().array() += 2 * n;  // diagonally dominant by a margin >= n
  const VectorXd root = VectorXd::NullaryExpr(n, [&] { return u(gen); });
  const rodlab::solvers::Residual F = [&](const VectorXd& x, VectorXd& out) {
    const VectorXd d = x - root;
    out = A * d + 0.1 * d.array().cube().matrix();
    return true;
  };
  rodlab::solvers::NewtonOptions options;
  options.tol = 1e-13;
  const auto result = rodlab::solvers::solve_newton(F, VectorXd(root.array() + 0.5), options);
  const double error = (result.x - root).lpNorm<Eigen::Infinity>();
  BOOST_TEST_MESSAGE(n << " unknowns, seed " << seed << ": " << result.iterations
                       << " iterations, root error " << error);
  BOOST_TEST(result.converged);
  BOOST_TEST(result.residual_norm <= 1e-13);
  // |x - x*| <= |A^-1|_inf |F|_inf to first order, |A^-1|_inf <= 1 / n (the margin)
  BOOST_TEST(error <= 1e-12);
  BOOST_TEST(result.iterations <= 12);
}

}  // namespace

BOOST_AUTO_TEST_CASE(reaches_the_root_with_and_without_the_fixed_size_step) {
  for (int n : {5, 6, 7})
    for (unsigned seed : {1u, 2u, 3u}) check_root(n, seed);
}

// NewtonOptions::step_tol: where one unknown shows in one row alone, 1e-7 times as strongly as
// the others (a clamped Cosserat tip's position error against its axial force is 1/1600:
// docs/statics.md "Stopping where the tip is clamped"), the residual's tolerance alone stops up
// to 1e7 tol from the root. With step_tol = tol the root error is held to tol (Newton goes on
// while the step with the Jacobian in hand is longer). Reference: the known root; the same solves
// without step_tol must miss it by more than 10 tol (the case exercises the rule).
BOOST_AUTO_TEST_CASE(step_tolerance_holds_the_unknowns_of_an_ill_conditioned_residual) {
  double worst_without = 0.0, worst_with = 0.0;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u, 6u}) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 6;
    MatrixXd A = MatrixXd::NullaryExpr(n, n, [&] { return 0.1 * u(gen); });
    A.diagonal().array() += 1.0;
    A.col(n - 1).head(n - 1).setZero();  // the last unknown shows in the last row alone,
    A.row(n - 1) *= 1e-7;                // and weakly
    const VectorXd root = VectorXd::NullaryExpr(n, [&] { return u(gen); });
    const rodlab::solvers::Residual F = [&](const VectorXd& x, VectorXd& out) {
      VectorXd d = x - root;
      d[n - 1] += d[n - 1] * d[n - 1];  // nonlinear in the weak unknown alone
      out = A * d;
      return true;
    };
    rodlab::solvers::NewtonOptions options;
    options.tol = 1e-10;
    for (const double step_tol : {0.0, 1e-10}) {
      options.step_tol = step_tol;
      const auto r = rodlab::solvers::solve_newton(F, VectorXd(root.array() + 0.5), options);
      BOOST_TEST(r.converged);
      BOOST_TEST(r.residual_norm <= 1e-10);
      const double error = (r.x - root).lpNorm<Eigen::Infinity>();
      BOOST_TEST_MESSAGE("seed " << seed << ", step_tol " << step_tol << ": " << r.iterations
                                 << " iterations, root error " << error);
      double& worst = step_tol > 0 ? worst_with : worst_without;
      worst = std::max(worst, error);
    }
  }
  BOOST_TEST(worst_without > 1e-9);  // the premise: the residual's tolerance alone misses
  BOOST_TEST(worst_with <= 1e-10);
}
