#include "rodlab/solvers/common/box_qp.hpp"

#include <cmath>

#include "rodlab/check.hpp"

namespace rodlab::solvers {
namespace {

double value(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, const Eigen::VectorXd& x) {
  return 0.5 * x.dot(H * x) + g.dot(x);
}

}  // namespace

BoxQpResult solve_box_qp(const Eigen::MatrixXd& H, const Eigen::VectorXd& g,
                         const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                         const Eigen::VectorXd& x0, const BoxQpOptions& options) {
  const Eigen::Index n = g.size();
  RODLAB_THROW_UNLESS(H.rows() == n && H.cols() == n && lower.size() == n && upper.size() == n &&
                          x0.size() == n,
                      "box QP: expected sizes {} (H {}x{}, bounds {} and {}, x0 {})", n, H.rows(),
                      H.cols(), lower.size(), upper.size(), x0.size());
  RODLAB_THROW_UNLESS((lower.array() <= upper.array()).all(), "box QP: lower bound above upper");
  BoxQpResult out;
  out.x = x0.cwiseMax(lower).cwiseMin(upper);
  out.free = Eigen::VectorXi::Ones(n);
  double f = value(H, g, out.x);
  const double scale = g.norm() + 1.0;
  for (out.iterations = 0; out.iterations < options.max_iterations; ++out.iterations) {
    const Eigen::VectorXd grad = g + H * out.x;
    // clamped: on a bound with the gradient pushing outward
    Eigen::Index n_free = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const bool clamped = (out.x[i] <= lower[i] && grad[i] > 0.0) ||
                           (out.x[i] >= upper[i] && grad[i] < 0.0);
      out.free[i] = clamped ? 0 : 1;
      n_free += out.free[i];
    }
    if (n_free == 0) return out;
    Eigen::MatrixXd Hff(n_free, n_free);
    Eigen::VectorXd gf(n_free);
    for (Eigen::Index i = 0, a = 0; i < n; ++i) {
      if (!out.free[i]) continue;
      for (Eigen::Index j = 0, b = 0; j < n; ++j)
        if (out.free[j]) Hff(a, b++) = H(i, j);
      gf[a++] = grad[i];
    }
    if (gf.norm() <= options.gradient_tolerance * scale) return out;
    const Eigen::LLT<Eigen::MatrixXd> llt(Hff);
    if (llt.info() != Eigen::Success) {
      out.ok = false;
      out.reason = "box QP: the free block of H is not positive definite";
      return out;
    }
    const Eigen::VectorXd step_free = -llt.solve(gf);  // Newton in the free variables
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0, a = 0; i < n; ++i)
      if (out.free[i]) dx[i] = step_free[a++];
    const double slope = grad.dot(dx);
    if (!(slope < 0.0)) return out;  // no descent left: stationary to rounding
    // projected Armijo line search
    double alpha = 1.0;
    Eigen::VectorXd trial;
    double f_trial = f;
    for (;;) {
      trial = (out.x + alpha * dx).cwiseMax(lower).cwiseMin(upper);
      f_trial = value(H, g, trial);
      if (f_trial - f <= options.armijo * grad.dot(trial - out.x)) break;
      alpha *= 0.5;
      if (alpha < options.min_step) {
        out.ok = false;
        out.reason = "box QP: the line search found no decrease";
        return out;
      }
    }
    const double decrease = f - f_trial;
    out.x = trial;
    f = f_trial;
    if (decrease <= 1e-14 * (std::abs(f) + 1e-300) && alpha == 1.0) return out;
  }
  out.ok = false;
  out.reason = "box QP: no convergence";
  return out;
}

}  // namespace rodlab::solvers
