#include "rodlab/solvers/common/box_qp.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "rodlab/check.hpp"

namespace rodlab::solvers {

BoxQpResult solve_box_qp(const BoxQpMatrix& H, const BoxQpVector& g, const BoxQpVector& lo,
                         const BoxQpVector& hi, BoxQpVector& x, int max_passes) {
  const int n = static_cast<int>(g.size());
  RODLAB_THROW_UNLESS(n <= kMaxBoxQpSize, "box QP: at most {} unknowns, got {}", kMaxBoxQpSize, n);
  RODLAB_THROW_UNLESS(H.rows() == n && H.cols() == n && lo.size() == n && hi.size() == n && x.size() == n,
                      "box QP: expected sizes {} (H {} x {}, lo {}, hi {}, x {})", n, H.rows(), H.cols(),
                      lo.size(), hi.size(), x.size());
  RODLAB_THROW_UNLESS((lo.array() <= hi.array()).all(), "box QP: lo > hi");
  x = x.cwiseMax(lo).cwiseMin(hi);
  // active[k]: -1 held at lo, +1 held at hi, 0 free.
  Eigen::Matrix<int, Eigen::Dynamic, 1, 0, kMaxBoxQpSize, 1> active(n);
  const BoxQpVector grad0 = H * x + g;
  for (int k = 0; k < n; ++k)
    active[k] = (x[k] <= lo[k] && grad0[k] > 0.0) ? -1 : (x[k] >= hi[k] && grad0[k] < 0.0) ? 1 : 0;
  const double scale = std::max(1.0, H.diagonal().cwiseAbs().maxCoeff());
  BoxQpResult out;
  int free_index[kMaxBoxQpSize];
  BoxQpMatrix Hf;
  BoxQpVector rhs, d;
  Eigen::LLT<BoxQpMatrix> llt(n);
  bool stationary = false;  // x minimises the QP over the free unknowns (after a full step)
  for (out.passes = 1; out.passes <= max_passes; ++out.passes) {
    const BoxQpVector grad = H * x + g;
    int nf = 0;
    for (int k = 0; k < n; ++k)
      if (active[k] == 0) free_index[nf++] = k;
    // Newton step of the free unknowns, the others fixed: H_FF d_F = -grad_F.
    d.setZero(n);
    if (nf > 0 && !stationary) {
      Hf.resize(nf, nf);
      rhs.resize(nf);
      for (int i = 0; i < nf; ++i) {
        rhs[i] = -grad[free_index[i]];
        for (int j = 0; j < nf; ++j) Hf(i, j) = H(free_index[i], free_index[j]);
      }
      llt.compute(Hf);
      if (llt.info() != Eigen::Success) return out;  // not positive definite
      rhs = llt.solve(rhs);
      for (int i = 0; i < nf; ++i) d[free_index[i]] = rhs[i];
    }
    if (stationary || d.lpNorm<Eigen::Infinity>() <= 1e-14 * std::max(1.0, x.lpNorm<Eigen::Infinity>())) {
      stationary = false;
      // Stationary on the free set: release the active unknown with the worst multiplier.
      int worst = -1;
      double worst_value = 1e-14 * scale * std::max(1.0, x.lpNorm<Eigen::Infinity>());
      for (int k = 0; k < n; ++k) {
        const double wrong = active[k] == -1 ? -grad[k] : active[k] == 1 ? grad[k] : 0.0;
        if (wrong > worst_value) worst = k, worst_value = wrong;
      }
      if (worst < 0) {
        out.converged = true;
        return out;
      }
      active[worst] = 0;
      continue;
    }
    // Walk towards x + d until a bound blocks.
    double alpha = 1.0;
    int blocking = -1;
    for (int k = 0; k < n; ++k) {
      if (d[k] < 0.0 && (lo[k] - x[k]) / d[k] < alpha) alpha = (lo[k] - x[k]) / d[k], blocking = k;
      if (d[k] > 0.0 && (hi[k] - x[k]) / d[k] < alpha) alpha = (hi[k] - x[k]) / d[k], blocking = k;
    }
    x += std::max(0.0, alpha) * d;
    if (blocking >= 0) {
      active[blocking] = d[blocking] < 0.0 ? -1 : 1;
      x[blocking] = d[blocking] < 0.0 ? lo[blocking] : hi[blocking];
    } else {
      stationary = true;  // the full step: the free unknowns are optimal (up to rounding)
    }
    x = x.cwiseMax(lo).cwiseMin(hi);
  }
  return out;
}

}  // namespace rodlab::solvers
