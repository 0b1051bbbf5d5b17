#pragma once
// Good Broyden's method with full steps on a factorised Jacobian J0, in the recursion of
// Deuflhard's QNERR (P. Deuflhard, Newton Methods for Nonlinear Problems, Springer 2004,
// sec. 2.1.4). With full steps dx_k = -B_k^-1 F(x_k), Broyden's update of the secant model,
// B_(k+1) = B_k + F(x_(k+1)) <dx_k, .> / |dx_k|^2, has the inverse
//
//   B_(k+1)^-1 = (I + dx_(k+1) <dx_k, .> / |dx_k|^2) B_k^-1,
//
// so the next step needs J0's factors and the steps taken so far, never a matrix:
//
//   v = -J0^-1 F(x_(k+1));  v += dx_i <dx_(i-1), v> / |dx_(i-1)|^2 for i = 1..k;
//   alpha = <dx_k, v> / |dx_k|^2;  dx_(k+1) = v / (1 - alpha).
//
// <a, b> = sum (s_i a_i)(s_i b_i) with the unknowns' scaling s (KINSOL's u_scale), so the
// method is invariant to the unknowns' units. theta = |v| / |dx_k|, the contraction of the
// simplified step, monitors convergence: Deuflhard requires theta < 1/2. Private to
// solvers/common.
#include <cmath>

#include <Eigen/Core>

namespace rodlab::solvers {

class BroydenSteps {
 public:
  using Vector = Eigen::VectorXd;

  /// Room for `capacity` steps in the unknowns' scaling s (allocates when it grows; then no
  /// allocation), no step recorded.
  void reset(const Eigen::Ref<const Vector>& scale, int capacity) {
    if (steps_.rows() != scale.size() || steps_.cols() < capacity) {
      steps_.resize(scale.size(), capacity);
      duals_.resize(scale.size(), capacity);
    }
    if (norms_.size() < capacity) norms_.resize(capacity);
    weights_ = scale.cwiseAbs2();
    k_ = 0;
  }
  /// Forgets the steps (a new J0).
  void clear() { k_ = 0; }
  int size() const { return k_; }
  int capacity() const { return static_cast<int>(steps_.cols()); }

  /// Records the step dx_k just taken (dx_0: J0's own step -J0^-1 F(x_0)); at most capacity().
  void push(const Eigen::Ref<const Vector>& dx) {
    steps_.col(k_) = dx;
    duals_.col(k_) = weights_.cwiseProduct(dx);
    norms_[k_] = duals_.col(k_).dot(dx);
    duals_.col(k_) /= norms_[k_];
    ++k_;
  }

  /// v in: J0's simplified step -J0^-1 F(x_(k+1)); out: the secant step dx_(k+1). Returns
  /// theta = |v_in after the recursion| / |dx_k|, or +inf for a step that cannot be formed
  /// (alpha >= 1, or no step recorded).
  double next(Eigen::Ref<Vector> v) const {
    if (k_ == 0) return INFINITY;
    for (int i = 1; i < k_; ++i) v += steps_.col(i) * duals_.col(i - 1).dot(v);
    const double alpha = duals_.col(k_ - 1).dot(v);
    const double theta = std::sqrt(v.cwiseAbs2().dot(weights_) / norms_[k_ - 1]);
    if (!(alpha < 1.0)) return INFINITY;
    v /= 1.0 - alpha;
    return theta;
  }

 private:
  Eigen::MatrixXd steps_;  ///< dx_0 .. dx_(k-1), one per column
  Eigen::MatrixXd duals_;  ///< <dx_i, .> / |dx_i|^2 as vectors: s^2 dx_i / |dx_i|^2
  Eigen::VectorXd norms_;  ///< |dx_i|^2 in the scaled norm
  Eigen::VectorXd weights_;  ///< s_i^2
  int k_ = 0;
};

}  // namespace rodlab::solvers
