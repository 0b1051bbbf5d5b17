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
