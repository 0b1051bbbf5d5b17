#define BOOST_TEST_MODULE chebyshev_operators
#include <boost/test/unit_test.hpp>

// Chebyshev-Lobatto points, differentiation matrix (thesis (2.102), negative-sum diagonal),
// its inverse with an initial value (integration), Clenshaw-Curtis weights and barycentric
// interpolation (solvers/common/chebyshev_operators.hpp).
// References: the Chebyshev polynomials T_k (2.95)-(2.98) and their derivatives k U_{k-1}, whose
// values are known in closed form; the exact integrals of t^k; the closed-form diagonal of
// (2.102) as a cross-check of the negative-sum diagonal.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rodlab/solvers/common/chebyshev_operators.hpp"

namespace {

using namespace rodlab::solvers;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using std::numbers::pi;

/// T_k(t) and T_k'(t) by the recurrence (2.98) and its derivative.
void chebyshev_T(int k, double t, double& T, double& dT) {
  double T0 = 1.0, T1 = t, d0 = 0.0, d1 = 1.0;
  if (k == 0) {
    T = 1.0;
    dT = 0.0;
    return;
  }
  for (int j = 2; j <= k; ++j) {
    const double T2 = 2.0 * t * T1 - T0, d2 = 2.0 * T1 + 2.0 * t * d1 - d0;
    T0 = T1;
    T1 = T2;
    d0 = d1;
    d1 = d2;
  }
  T = T1;
  dT = d1;
}

const int kSizes[] = {2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 24, 25, 32, 40, 41, 60, 64};

}  // namespace

BOOST_AUTO_TEST_CASE(points_are_increasing_symmetric_lobatto_points) {
  for (int n : kSizes) {
    const VectorXd t = chebyshev_lobatto_points(n);
    const int m = n - 1;
    BOOST_TEST(t[0] == -1.0);
    BOOST_TEST(t[m] == 1.0);
    for (int j = 0; j < n; ++j) {
      BOOST_TEST(t[m - j] == -t[j]);  // exactly
      BOOST_TEST(std::abs(t[j] + std::cos(j * pi / m)) <= 1e-15);  // cos(j pi / m) is a few ulps off itself
      if (j > 0) BOOST_TEST(t[j] > t[j - 1]);
    }
  }
  BOOST_CHECK_THROW(chebyshev_lobatto_points(1), std::invalid_argument);
  BOOST_CHECK_THROW(chebyshev_differentiation_matrix(0), std::invalid_argument);
}

// D p = p' at the nodes for every polynomial of degree <= n - 1, tested on each T_k, k <= n - 1,
// with the error scaled by max |T_k'| = k^2 (attained at t = +-1).
BOOST_AUTO_TEST_CASE(differentiation_is_exact_on_polynomials) {
  double worst = 0.0;
  for (int n : kSizes) {
    const VectorXd t = chebyshev_lobatto_points(n);
    const MatrixXd D = chebyshev_differentiation_matrix(n);
    for (int k = 0; k < n; ++k) {
      VectorXd f(n), df(n);
      for (int j = 0; j < n; ++j) chebyshev_T(k, t[j], f[j], df[j]);
      const double scale = std::max(1.0, static_cast<double>(k) * k);
      const double err = (D * f - df).lpNorm<Eigen::Infinity>() / scale;
      worst = std::max(worst, err);
      BOOST_TEST_CONTEXT("n = " << n << ", k = " << k) { BOOST_TEST(err <= 1e-12); }
    }
  }
  BOOST_TEST_MESSAGE("worst scaled error of D on T_k, k < n <= 64: " << worst);
}

// The negative-sum diagonal kills constants to rounding, matches the closed form of (2.102)
// (t = -x reverses the sign of d/dx: D_00 = -(2 m^2 + 1)/6, D_mm = +(2 m^2 + 1)/6,
// D_jj = -t_j / (2 (1 - t_j^2)))
// and the matrix is exactly centro-antisymmetric.
BOOST_AUTO_TEST_CASE(diagonal_by_negative_sum_and_symmetry) {
  for (int n : kSizes) {
    const int m = n - 1;
    const VectorXd t = chebyshev_lobatto_points(n);
    const MatrixXd D = chebyshev_differentiation_matrix(n);
    const double norm = D.cwiseAbs().rowwise().sum().maxCoeff();
    BOOST_TEST((D * VectorXd::Ones(n)).lpNorm<Eigen::Infinity>() <= 1e-15 * norm);
    const double corner = (2.0 * m * m + 1.0) / 6.0;
    BOOST_TEST(D(0, 0) == -corner, boost::test_tools::tolerance(1e-13));
    BOOST_TEST(D(m, m) == corner, boost::test_tools::tolerance(1e-13));
    for (int j = 1; j < m; ++j) {
      const double closed = -t[j] / (2.0 * (1.0 - t[j] * t[j]));
      BOOST_TEST(std::abs(D(j, j) - closed) <= 1e-14 * norm);
    }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) BOOST_TEST(D(m - i, m - j) == -D(i, j));
    // (2.102)'s off-diagonal entries, in increasing order: (c_i/c_j) (-1)^(i+j) / (t_i - t_j).
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        if (i == j) continue;
        const double ci = (i == 0 || i == m) ? 2.0 : 1.0, cj = (j == 0 || j == m) ? 2.0 : 1.0;
        const double ref = ci / cj * ((i + j) % 2 ? -1.0 : 1.0) / (t[i] - t[j]);
        BOOST_TEST(std::abs(D(i, j) - ref) <= 1e-13 * std::abs(ref));
      }
  }
}

// Clenshaw-Curtis: exact for t^k, k <= n - 1 (and k = n for odd n: degree m + 1 by symmetry for
// even m), positive, symmetric, summing to 2.
BOOST_AUTO_TEST_CASE(clenshaw_curtis_integrates_polynomials) {
  for (int n : kSizes) {
    const int m = n - 1;
    const VectorXd t = chebyshev_lobatto_points(n);
    const VectorXd w = clenshaw_curtis_weights(n);
    BOOST_TEST(w.sum() == 2.0, boost::test_tools::tolerance(1e-14));
    for (int j = 0; j < n; ++j) {
      BOOST_TEST(w[j] > 0.0);
      BOOST_TEST(w[m - j] == w[j]);
    }
    const int degree = m % 2 == 0 ? m + 1 : m;
    for (int k = 0; k <= degree; ++k) {
      double q = 0.0;
      for (int j = 0; j < n; ++j) q += w[j] * std::pow(t[j], k);
      const double exact = k % 2 ? 0.0 : 2.0 / (k + 1);
      BOOST_TEST_CONTEXT("n = " << n << ", k = " << k) { BOOST_TEST(std::abs(q - exact) <= 1e-14); }
    }
    // And T_k for the rest of the range: int T_k = 2 / (1 - k^2) for even k.
    for (int k = 0; k <= m; k += 2) {
      double q = 0.0, T, dT;
      for (int j = 0; j < n; ++j) {
        chebyshev_T(k, t[j], T, dT);
        q += w[j] * T;
      }
      BOOST_TEST(std::abs(q - 2.0 / (1.0 - static_cast<double>(k) * k)) <= 1e-14);
    }
  }
  // Known small cases: trapezoid (n = 2) and Simpson (n = 3).
  BOOST_TEST(clenshaw_curtis_weights(2)[0] == 1.0, boost::test_tools::tolerance(1e-15));
  const VectorXd simpson = clenshaw_curtis_weights(3);
  BOOST_TEST(simpson[0] == 1.0 / 3.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(simpson[1] == 4.0 / 3.0, boost::test_tools::tolerance(1e-15));
}

// The integration matrix inverts the collocation of u' = g with u(-1) given: for every T_k,
// k <= n - 1, S [T_k(-1); T_k'(t_1..t_{n-1})] = T_k at the nodes (error scaled by max |T_k'| =
// k^2, as for D), and D S g = g on rows 1..n-1 for any g.
BOOST_AUTO_TEST_CASE(integration_inverts_the_initial_value_collocation) {
  double worst = 0.0;
  for (int n : kSizes) {
    const VectorXd t = chebyshev_lobatto_points(n);
    const MatrixXd S = chebyshev_integration_matrix(n), D = chebyshev_differentiation_matrix(n);
    for (int k = 0; k < n; ++k) {
      VectorXd f(n), g(n);
      for (int j = 0; j < n; ++j) chebyshev_T(k, t[j], f[j], g[j]);
      g[0] = f[0];
      const double err = (S * g - f).lpNorm<Eigen::Infinity>() / std::max(1.0, static_cast<double>(k) * k);
      worst = std::max(worst, err);
      BOOST_TEST_CONTEXT("n = " << n << ", k = " << k) { BOOST_TEST(err <= 1e-12); }
    }
    const VectorXd g = VectorXd::LinSpaced(n, 0.3, -1.1);
    BOOST_TEST((D * (S * g) - g).tail(n - 1).lpNorm<Eigen::Infinity>() <= 1e-12 * n * n);
    BOOST_TEST((S * g)[0] == g[0]);  // exactly
  }
  BOOST_TEST_MESSAGE("worst scaled error of S on T_k, k < n <= 64: " << worst);
  BOOST_CHECK_THROW(chebyshev_integration_matrix(1), std::invalid_argument);
}

// Barycentric interpolation reproduces polynomials of degree <= n - 1 anywhere in [-1, 1] and
// is the identity at the nodes.
BOOST_AUTO_TEST_CASE(interpolation_reproduces_polynomials) {
  VectorXd targets(7);
  targets << -1.0, -0.93, -0.4, 0.0, 0.123, 0.77, 1.0;
  for (int n : kSizes) {
    const VectorXd t = chebyshev_lobatto_points(n);
    const MatrixXd C = chebyshev_interpolation_matrix(n, targets);
    for (Eigen::Index r = 0; r < targets.size(); ++r)
      BOOST_TEST(C.row(r).sum() == 1.0, boost::test_tools::tolerance(1e-14));
    for (int k = 0; k < n; ++k) {
      VectorXd f(n), exact(targets.size());
      double dT;
      for (int j = 0; j < n; ++j) chebyshev_T(k, t[j], f[j], dT);
      for (Eigen::Index r = 0; r < targets.size(); ++r) chebyshev_T(k, targets[r], exact[r], dT);
      BOOST_TEST((C * f - exact).lpNorm<Eigen::Infinity>() <= 1e-13);
    }
    const MatrixXd I = chebyshev_interpolation_matrix(n, t);
    BOOST_TEST((I - MatrixXd::Identity(n, n)).norm() == 0.0);
  }
}

// Mapped to [a, b]: ends exact, d/ds and the weights scaled, monomials in s differentiated and
// integrated exactly.
BOOST_AUTO_TEST_CASE(mapping_to_an_interval) {
  const double a = 0.0, b = 0.1;
  for (int n : {2, 5, 12, 24, 33}) {
    const auto op = chebyshev_lobatto(n, a, b);
    BOOST_TEST(op.s[0] == a);
    BOOST_TEST(op.s[n - 1] == b);
    for (int j = 1; j < n; ++j) BOOST_TEST(op.s[j] > op.s[j - 1]);
    for (int k = 0; k < n; ++k) {
      VectorXd f(n), df(n);
      for (int j = 0; j < n; ++j) {
        const double u = op.s[j] / b;  // (s / b)^k, derivative k (s/b)^(k-1) / b
        f[j] = std::pow(u, k);
        df[j] = k == 0 ? 0.0 : k * std::pow(u, k - 1) / b;
      }
      const double scale = std::max(1.0, 2.0 * k * k / b);
      BOOST_TEST((op.D * f - df).lpNorm<Eigen::Infinity>() <= 1e-12 * scale);
      BOOST_TEST(op.w.dot(f) == b / (k + 1), boost::test_tools::tolerance(1e-13));
    }
  }
  BOOST_CHECK_THROW(chebyshev_lobatto(5, 1.0, 1.0), std::invalid_argument);
}
