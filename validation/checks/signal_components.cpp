// The matrix pencil method (signal_components.hpp).
#include "checks/signal_components.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

namespace rodlab::validation {

std::vector<SignalComponent> signal_components(const std::vector<double>& y, double dt, int order,
                                               double relative_floor) {
  const int n = static_cast<int>(y.size()), L = n / 3;
  if (order < 1 || 3 * order > n) throw std::invalid_argument("signal_components: bad order");
  Eigen::MatrixXd Y(n - L, L + 1);
  for (int i = 0; i < n - L; ++i)
    for (int j = 0; j <= L; ++j) Y(i, j) = y[i + j];
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(Y, Eigen::ComputeThinV);
  const Eigen::MatrixXd V = svd.matrixV().leftCols(order);
  const Eigen::MatrixXd pencil =
      V.topRows(L).completeOrthogonalDecomposition().solve(V.bottomRows(L));
  const Eigen::VectorXcd z = Eigen::EigenSolver<Eigen::MatrixXd>(pencil).eigenvalues();
  // Amplitudes: y_k = sum_i a_i z_i^k in the least-squares sense.
  Eigen::MatrixXcd Z(n, order);
  for (int i = 0; i < order; ++i) {
    std::complex<double> p(1.0, 0.0);
    for (int k = 0; k < n; ++k, p *= z[i]) Z(k, i) = p;
  }
  const Eigen::VectorXcd samples =
      Eigen::VectorXd::Map(y.data(), n).cast<std::complex<double>>();
  const Eigen::VectorXcd a = Z.completeOrthogonalDecomposition().solve(samples);
  std::vector<SignalComponent> out;
  double largest = 0.0;
  for (int i = 0; i < order; ++i) {
    const double phase = std::arg(z[i]);
    if (!(phase > 1e-9)) continue;  // the negative twin of a sinusoid, or an offset
    out.push_back({phase / (2 * std::numbers::pi * dt), 2.0 * std::abs(a[i]),
                   -std::log(std::abs(z[i])) / dt});
    largest = std::max(largest, out.back().amplitude);
  }
  std::erase_if(out, [&](const SignalComponent& c) {
    return c.amplitude < relative_floor * largest;
  });
  std::sort(out.begin(), out.end(), [](const auto& p, const auto& q) {
    return p.frequency_hz < q.frequency_hz;
  });
  return out;
}

}  // namespace rodlab::validation
