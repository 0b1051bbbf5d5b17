// LQR (solvers/control/lqr.hpp): the finite-horizon gains against the minimiser of the whole
// quadratic program (the inputs of all steps at once), the DARE against the scalar closed form
// and its own residual, and the infinite-horizon gain as the limit of the finite one.
#define BOOST_TEST_MODULE control_lqr
#include <boost/test/unit_test.hpp>

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "rodlab/solvers/control/lqr.hpp"

namespace c = rodlab::solvers::control;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

/// A damped two-mass chain (4 states, 1 input), time step 0.1.
void plant(MatrixXd& A, MatrixXd& B) {
  A.resize(4, 4);
  A << 0.98, 0.1, 0.01, 0.0,  //
      -0.3, 0.95, 0.05, 0.0,  //
      0.0, 0.0, 0.99, 0.1,    //
      0.05, 0.0, -0.2, 0.97;
  B.resize(4, 1);
  B << 0.0, 0.1, 0.0, 0.02;
}

}  // namespace

// u_0 = -K_0 x_0 equals the first input of the minimiser of the stacked quadratic program
// J(U) = sum x_i^T Q x_i + u_i^T R u_i + x_N^T Q_end x_N with x_i linear in (x_0, U) (reference:
// the normal equations, to 1e-10), and the cost to go x_0^T S_0 x_0 equals its minimum.
BOOST_AUTO_TEST_CASE(finite_horizon_equals_the_stacked_quadratic_program) {
  MatrixXd A, B;
  plant(A, B);
  const int n = 4, m = 1, N = 8;
  const MatrixXd Q = MatrixXd::Identity(n, n), R = 0.5 * MatrixXd::Identity(m, m);
  const MatrixXd Q_end = 3.0 * MatrixXd::Identity(n, n);
  const c::FiniteHorizonLqr lqr = c::finite_horizon_lqr(A, B, Q, R, Q_end, N);
  VectorXd x0(n);
  x0 << 1.0, -0.5, 0.3, 0.2;
  // x_i = A^i x0 + sum_(j<i) A^(i-1-j) B u_j: X = F x0 + G U
  MatrixXd F((N + 1) * n, n), G = MatrixXd::Zero((N + 1) * n, N * m);
  MatrixXd Ai = MatrixXd::Identity(n, n);
  for (int i = 0; i <= N; ++i) {
    F.block(i * n, 0, n, n) = Ai;
    Ai = A * Ai;
  }
  for (int i = 1; i <= N; ++i)
    for (int j = 0; j < i; ++j) {
      MatrixXd P = MatrixXd::Identity(n, n);
      for (int k = 0; k < i - 1 - j; ++k) P = A * P;
      G.block(i * n, j * m, n, m) = P * B;
    }
  MatrixXd Qbar = MatrixXd::Zero((N + 1) * n, (N + 1) * n);
  for (int i = 0; i < N; ++i) Qbar.block(i * n, i * n, n, n) = Q;
  Qbar.block(N * n, N * n, n, n) = Q_end;
  const MatrixXd Rbar = MatrixXd::Identity(N * m, N * m) * 0.5;
  const MatrixXd H = G.transpose() * Qbar * G + Rbar;
  const VectorXd U = H.ldlt().solve(-G.transpose() * Qbar * F * x0);
  const VectorXd u0 = -lqr.K[0] * x0;
  BOOST_TEST(std::abs(u0[0] - U[0]) < 1e-10);
  const VectorXd X = F * x0 + G * U;
  const double J = X.dot(Qbar * X) + U.dot(Rbar * U);
  BOOST_TEST(std::abs(x0.dot(lqr.S[0] * x0) - J) < 1e-10 * J);
  BOOST_TEST(lqr.S.size() == static_cast<std::size_t>(N + 1));
  BOOST_TEST(lqr.K.size() == static_cast<std::size_t>(N));
}

// Scalar DARE s = q + a^2 s - (a b s)^2 / (r + b^2 s): b^2 s^2 + (r - a^2 r - q b^2) s - q r = 0,
// the positive root (closed form), for a stable and an unstable a.
BOOST_AUTO_TEST_CASE(scalar_dare_is_the_closed_form) {
  for (double a : {0.9, 1.2}) {
    const double b = 0.5, q = 2.0, r = 0.3;
    const double p = r - a * a * r - q * b * b;
    const double s = (-p + std::sqrt(p * p + 4 * b * b * q * r)) / (2 * b * b);
    const auto d = c::solve_dare(MatrixXd::Constant(1, 1, a), MatrixXd::Constant(1, 1, b),
                                 MatrixXd::Constant(1, 1, q), MatrixXd::Constant(1, 1, r));
    BOOST_TEST_REQUIRE(d.converged);
    BOOST_TEST(std::abs(d.S(0, 0) - s) < 1e-12 * s);
    BOOST_TEST(std::abs(a - b * d.K(0, 0)) < 1.0);  // closed loop stable
  }
}

// The chain: the DARE residual vanishes (to 1e-10 of |S|), the closed loop A - B K is stable, and
// the finite-horizon gain K_0 tends to K as the horizon grows (to 1e-8 at N = 400).
BOOST_AUTO_TEST_CASE(dare_residual_stability_and_the_long_horizon_limit) {
  MatrixXd A, B;
  plant(A, B);
  const MatrixXd Q = MatrixXd::Identity(4, 4), R = MatrixXd::Identity(1, 1) * 0.1;
  const auto d = c::solve_dare(A, B, Q, R);
  BOOST_TEST_REQUIRE(d.converged);
  BOOST_TEST_MESSAGE("SDA iterations " << d.iterations);
  const MatrixXd S = d.S;
  const MatrixXd residual = Q + A.transpose() * S * A -
                            A.transpose() * S * B * (R + B.transpose() * S * B).inverse() *
                                B.transpose() * S * A -
                            S;
  BOOST_TEST(residual.norm() < 1e-10 * S.norm());
  const Eigen::VectorXcd eig = (A - B * d.K).eigenvalues();
  for (int i = 0; i < eig.size(); ++i) BOOST_TEST(std::abs(eig[i]) < 1.0);
  const auto finite = c::finite_horizon_lqr(A, B, Q, R, Q, 400);
  BOOST_TEST((finite.K[0] - d.K).norm() < 1e-8 * d.K.norm());
}

BOOST_AUTO_TEST_CASE(bad_sizes_are_refused) {
  MatrixXd A, B;
  plant(A, B);
  BOOST_CHECK_THROW(c::finite_horizon_lqr(A, B, MatrixXd::Identity(3, 3), MatrixXd::Identity(1, 1),
                                          MatrixXd::Identity(4, 4), 5),
                    std::invalid_argument);
  BOOST_CHECK_THROW(c::finite_horizon_lqr(A, B, MatrixXd::Identity(4, 4), MatrixXd::Identity(1, 1),
                                          MatrixXd::Identity(4, 4), 0),
                    std::invalid_argument);
}
