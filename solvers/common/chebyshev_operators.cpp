#include "rodlab/solvers/common/chebyshev_operators.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "rodlab/check.hpp"

namespace rodlab::solvers {
namespace {

using std::numbers::pi;

void check_points(int n) {
  RODLAB_THROW_UNLESS(n >= 2, "Chebyshev-Lobatto operators need at least 2 points, got {}", n);
}

/// (-1)^j / c_j: the barycentric weights of the points (c_0 = c_m = 2), up to a common factor.
double barycentric_weight(int j, int m) {
  const double sign = (j % 2 == 0) ? 1.0 : -1.0;
  return (j == 0 || j == m) ? 0.5 * sign : sign;
}

}  // namespace

Eigen::VectorXd chebyshev_lobatto_points(int n) {
  check_points(n);
  const int m = n - 1;
  Eigen::VectorXd t(n);
  for (int j = 0; j < n; ++j) t[j] = std::sin(pi * (2 * j - m) / (2.0 * m));
  t[0] = -1.0;
  t[m] = 1.0;
  return t;
}

Eigen::MatrixXd chebyshev_differentiation_matrix(int n) {
  check_points(n);
  const int m = n - 1;
  Eigen::MatrixXd D(n, n);
  std::vector<double> off;
  off.reserve(n);
  // Rows i <= m - i directly (the middle row of odd n only for j < m/2), the rest by the
  // centro-antisymmetry D_{m-i,m-j} = -D_ij.
  const int upper = (n + 1) / 2;
  for (int i = 0; i < upper; ++i) {
    off.clear();
    const bool middle = 2 * i == m;
    for (int j = 0; j < n; ++j) {
      if (j == i) continue;
      if (middle && j > i) {
        D(i, j) = -D(i, m - j);
      } else {
        // t_i - t_j = 2 sin(pi (i + j) / 2m) sin(pi (i - j) / 2m), free of cancellation.
        const double diff = 2.0 * std::sin(pi * (i + j) / (2.0 * m)) * std::sin(pi * (i - j) / (2.0 * m));
        D(i, j) = barycentric_weight(j, m) / (barycentric_weight(i, m) * diff);
      }
      off.push_back(D(i, j));
    }
    // Negative-sum diagonal (Baltensperger & Trummer), smallest magnitudes first.
    std::sort(off.begin(), off.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    double sum = 0.0;
    for (double v : off) sum += v;
    D(i, i) = -sum;
  }
  for (int i = upper; i < n; ++i)
    for (int j = 0; j < n; ++j) D(i, j) = -D(m - i, m - j);
  return D;
}

Eigen::MatrixXd chebyshev_integration_matrix(int n) {
  Eigen::MatrixXd D = chebyshev_differentiation_matrix(n);
  D.row(0).setZero();
  D(0, 0) = 1.0;
  Eigen::MatrixXd S = D.partialPivLu().inverse();
  S.row(0) = D.row(0);  // u(-1) = u_0 exactly (the inverse's first row is e_0 up to rounding)
  return S;
}

Eigen::VectorXd clenshaw_curtis_weights(int n) {
  check_points(n);
  const int m = n - 1;
  Eigen::VectorXd w(n);
  const bool even = m % 2 == 0;
  const double end = even ? 1.0 / (static_cast<double>(m) * m - 1.0) : 1.0 / (static_cast<double>(m) * m);
  for (int j = 0; j <= m / 2; ++j) {
    double value;
    if (j == 0) {
      value = end;
    } else {
      const double theta = pi * j / m;
      double v = 1.0;
      const int terms = even ? m / 2 - 1 : (m - 1) / 2;
      for (int k = 1; k <= terms; ++k) v -= 2.0 * std::cos(2.0 * k * theta) / (4.0 * k * k - 1.0);
      if (even) v -= std::cos(m * theta) / (static_cast<double>(m) * m - 1.0);
      value = 2.0 * v / m;
    }
    w[j] = value;
    w[m - j] = value;
  }
  return w;
}

Eigen::MatrixXd chebyshev_interpolation_matrix(int n, const Eigen::VectorXd& t) {
  const Eigen::VectorXd nodes = chebyshev_lobatto_points(n);
  const int m = n - 1;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(t.size(), n);
  for (Eigen::Index k = 0; k < t.size(); ++k) {
    int exact = -1;
    double denominator = 0.0;
    for (int j = 0; j < n; ++j) {
      const double d = t[k] - nodes[j];
      if (d == 0.0) {
        exact = j;
        break;
      }
      C(k, j) = barycentric_weight(j, m) / d;
      denominator += C(k, j);
    }
    if (exact >= 0) {
      C.row(k).setZero();
      C(k, exact) = 1.0;
    } else {
      C.row(k) /= denominator;
    }
  }
  return C;
}

ChebyshevLobatto chebyshev_lobatto(int n, double a, double b) {
  if (!(b > a)) throw std::invalid_argument("chebyshev_lobatto needs a < b");
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  ChebyshevLobatto out;
  out.s = (mid + half * chebyshev_lobatto_points(n).array()).matrix();
  out.s[0] = a;
  out.s[n - 1] = b;
  out.D = chebyshev_differentiation_matrix(n) / half;
  out.w = clenshaw_curtis_weights(n) * half;
  return out;
}

}  // namespace rodlab::solvers
