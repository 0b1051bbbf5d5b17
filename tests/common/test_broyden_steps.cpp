#define BOOST_TEST_MODULE broyden_steps
#include <boost/test/unit_test.hpp>

// BroydenSteps (solvers/common/broyden_steps.hpp), the recursion of Deuflhard's QNERR for good
// Broyden's method with full steps on one factorised J0. References:
//   - the definition: Broyden's update of the secant matrix, B_(k+1) = B_k + (y_k - B_k s_k)
//     s_k^T D / (s_k^T D s_k) (D = diag(s^2), the unknowns' scaling), formed densely and solved
//     by LU at every step: the recursion must give the same steps to rounding;
//   - Gay's theorem (D. M. Gay, SIAM J. Numer. Anal. 16, 1979): on a linear system, good
//     Broyden's method with full steps reaches the root in at most 2n steps from any
//     nonsingular B_0, where the chord method on the same B_0 only contracts linearly.

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "../../solvers/common/broyden_steps.hpp"

using rodlab::solvers::BroydenSteps;
using Vector = Eigen::VectorXd;
using Matrix = Eigen::MatrixXd;

namespace {

/// A perturbed copy of A: (1 + eps_ij) A_ij, |eps| <= amplitude.
Matrix perturbed(const Matrix& A, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Matrix B = A;
  for (Eigen::Index i = 0; i < A.size(); ++i) B.data()[i] *= 1.0 + u(rng);
  return B;
}

/// A smooth nonlinear system with a root near x = 0: F(x) = A x + 0.3 sin(x) - b.
struct Smooth {
  Matrix A;
  Vector b;
  Vector operator()(const Vector& x) const { return A * x + 0.3 * x.array().sin().matrix() - b; }
  Matrix jacobian(const Vector& x) const {
    Matrix J = A;
    J.diagonal() += 0.3 * x.array().cos().matrix();
    return J;
  }
};

}  // namespace

BOOST_AUTO_TEST_CASE(recursion_matches_the_dense_secant_update) {
  const int n = 6;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Smooth F{Matrix::Identity(n, n) * 4.0, Vector(n)};
  for (int i = 0; i < n; ++i) {
    F.b[i] = u(rng);
    for (int j = 0; j < n; ++j) F.A(i, j) += 0.5 * u(rng);
  }
  Vector scale(n);
  for (int i = 0; i < n; ++i) scale[i] = std::pow(10.0, i % 3 - 1);  // 0.1, 1, 10
  const Matrix D = scale.cwiseAbs2().asDiagonal();
  const Matrix J0 = perturbed(F.jacobian(Vector::Zero(n)), 0.2, 11);
  const Eigen::PartialPivLU<Matrix> lu0(J0);

  BroydenSteps steps;
  steps.reset(scale, 21);
  Vector x = Vector::Zero(n), y = x;  // the recursion's and the dense method's iterates
  Matrix B = J0;
  Vector dx = -lu0.solve(F(x));
  steps.push(dx);
  double worst = 0.0;
  for (int k = 0; k < 20; ++k) {
    // dense: B_(k+1) = B_k + (F_(k+1) - F_k - B_k s) s^T D / (s^T D s), s the step taken
    const Vector s = -B.lu().solve(F(y));
    const Vector y1 = y + s;
    B += (F(y1) - F(y) - B * s) * (s.transpose() * D) / (s.transpose() * D * s);
    y = y1;
    const Vector dense_next = -B.lu().solve(F(y));
    // recursion
    x += dx;
    Vector v = -lu0.solve(F(x));
    const double theta = steps.next(v);
    BOOST_TEST(std::isfinite(theta));
    worst = std::max(worst, (v - dense_next).norm() / dense_next.norm());
    dx = v;
    steps.push(dx);
    if (dense_next.norm() < 1e-12) break;
  }
  BOOST_TEST_MESSAGE("largest relative difference of the steps: " << worst);
  BOOST_TEST(worst <= 1e-9);  // rounding, amplified by the steps' shrinking norms
  BOOST_TEST(F(x).norm() <= 1e-10);
}

BOOST_AUTO_TEST_CASE(linear_system_in_at_most_2n_steps) {
  const int n = 5;
  Matrix A(n, n);
  A << 4, 1, 0, 0, 1,   //
      1, 5, 2, 0, 0,    //
      0, 2, 6, 1, 0,    //
      0, 0, 1, 3, 1,    //
      1, 0, 0, 1, 4;
  const Vector b = Vector::LinSpaced(n, 1.0, 2.0);
  const Vector root = A.lu().solve(b);
  const Matrix B0 = perturbed(A, 0.4, 3);
  const Eigen::PartialPivLU<Matrix> lu0(B0);
  const Vector scale = Vector::LinSpaced(n, 0.5, 3.0);
  auto residual = [&](const Vector& x) { return Vector(A * x - b); };

  // Chord steps on B0 alone: linear contraction.
  Vector chord = Vector::Zero(n);
  for (int k = 0; k < 2 * n; ++k) chord -= lu0.solve(residual(chord));
  const double chord_error = (chord - root).norm() / root.norm();

  BroydenSteps steps;
  steps.reset(scale, 2 * n + 1);
  Vector x = Vector::Zero(n);
  Vector dx = -lu0.solve(residual(x));
  steps.push(dx);
  int taken = 0;
  while (taken < 2 * n) {
    x += dx;
    ++taken;
    if ((x - root).norm() <= 1e-12 * root.norm()) break;
    Vector v = -lu0.solve(residual(x));
    BOOST_TEST_REQUIRE(std::isfinite(steps.next(v)));
    dx = v;
    steps.push(dx);
  }
  BOOST_TEST_MESSAGE("Broyden: " << taken << " steps to 1e-12; chord after " << 2 * n
                                 << " steps: relative error " << chord_error);
  BOOST_TEST(taken <= 2 * n);
  BOOST_TEST((x - root).norm() <= 1e-12 * root.norm());
  BOOST_TEST(chord_error > 1e-8);  // the chord method is far from the root at that count
}

BOOST_AUTO_TEST_CASE(no_step_before_the_first_and_capacity) {
  BroydenSteps steps;
  steps.reset(Vector::Ones(3), 4);
  BOOST_TEST(steps.size() == 0);
  BOOST_TEST(steps.capacity() >= 4);
  Vector v = Vector::Ones(3);
  BOOST_TEST(std::isinf(steps.next(v)));  // no J0 step recorded: nothing to update from
  steps.push(Vector::Ones(3));
  BOOST_TEST(steps.size() == 1);
  // v = dx_0: alpha = 1, the secant matrix is singular along it.
  v = Vector::Ones(3);
  BOOST_TEST(std::isinf(steps.next(v)));
  steps.clear();
  BOOST_TEST(steps.size() == 0);
}
