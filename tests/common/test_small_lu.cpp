#define BOOST_TEST_MODULE small_lu
#include <boost/test/unit_test.hpp>

// solve_partial_pivoting (solvers/common/small_lu.hpp), the tendon law's fixed-size solve,
// against Eigen's PartialPivLU of the same systems: random 3 x 3 and 6 x 6 matrices, with the
// diagonal in place and zeroed (every pivot an interchange), and the tendon law itself.

#include <random>

#include <Eigen/Dense>

#include "rodlab/solvers/common/small_lu.hpp"
#include "rodlab/solvers/common/tendon_law.hpp"

namespace {

template <int N>
void check_against_eigen(unsigned seed, bool zero_diagonal) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;
  Matrix A = Matrix::NullaryExpr([&] { return u(gen); });
  if (zero_diagonal) A.diagonal().setZero();
  const Vector b = Vector::NullaryExpr([&] { return u(gen); });
  const Vector x = rodlab::solvers::solve_partial_pivoting<N>(A, b);
  const Vector reference = A.partialPivLu().solve(b);
  const double backward = (A * x - b).norm() / (A.norm() * x.norm() + b.norm());
  const double difference = (x - reference).norm() / reference.norm();
  const double condition = A.norm() * A.inverse().norm();
  BOOST_TEST_MESSAGE(N << " x " << N << ", seed " << seed << ", zero diagonal " << zero_diagonal
                       << ": backward error " << backward << ", against Eigen " << difference
                       << " (condition " << condition << ")");
  BOOST_TEST(backward <= 1e-15);
  BOOST_TEST(difference <= 1e-15 * condition);  // both backward stable: within cond * eps
}

}  // namespace

BOOST_AUTO_TEST_CASE(solves_like_eigens_partial_pivoting) {
  for (unsigned seed = 1; seed <= 20; ++seed)
    for (const bool zero_diagonal : {false, true}) {
      check_against_eigen<3>(seed, zero_diagonal);
      check_against_eigen<6>(seed, zero_diagonal);
    }
}

BOOST_AUTO_TEST_CASE(the_tendon_law_solves_its_equation) {
  // Kt (xi - xi_ref) + F c(xi) = Lambda with a nonlinear c (a tendon's unit wrench-like
  // quadratic term): the residual at the returned strain is at rounding level.
  using rodlab::lie::Matrix6;
  using rodlab::lie::Vector6;
  Matrix6 Kt = Matrix6::Zero();
  Kt.diagonal() << 2e-3, 2e-3, 1.5e-3, 40.0, 40.0, 100.0;
  Vector6 xi_ref;
  xi_ref << 0.1, 0.0, 0.0, 0.0, 0.0, 1.0;
  Vector6 Lambda;
  Lambda << 1e-3, 2e-3, 5e-4, 0.5, -0.2, 3.0;
  auto tendons = [&](const Vector6& xi, Vector6& r, Matrix6& J) {
    // c(xi) = 0.01 (xi_0 xi_1, xi_1^2, 0, 0, xi_0, xi_5^2): its Jacobian below
    r[0] += 0.01 * xi[0] * xi[1];
    r[1] += 0.01 * xi[1] * xi[1];
    r[4] += 0.01 * xi[0];
    r[5] += 0.01 * xi[5] * xi[5];
    J(0, 0) += 0.01 * xi[1];
    J(0, 1) += 0.01 * xi[0];
    J(1, 1) += 0.02 * xi[1];
    J(4, 0) += 0.01;
    J(5, 5) += 0.02 * xi[5];
  };
  const Vector6 xi = rodlab::solvers::solve_tendon_law(Kt, xi_ref, Lambda, false, tendons);
  Vector6 r = Kt * (xi - xi_ref) - Lambda;
  Matrix6 J = Kt;
  tendons(xi, r, J);
  BOOST_TEST_MESSAGE("tendon law residual " << r.norm());
  BOOST_TEST(r.norm() <= 1e-13);  // |Kt| |xi| eps: 100 x 1 x 1e-16, with margin
}
