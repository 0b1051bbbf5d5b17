#pragma once
// Broyden's method on the inverse of a sparse Jacobian: multiple shooting's Newton model
// (shooting_newton.hpp; staggered_shooting_stepper.cpp "multiple shooting"). Private to
// solvers/dynamics.
//
// Multiple shooting's Jacobian is block bidiagonal: interval i's 18 start unknowns reach only
// the jump at its start and what its march's end reaches, the next jump or the tip (a clamped
// tip's rows and the actuators' rows and columns are dense). The model keeps the inverse H of a
// fresh Jacobian J0 and Broyden's "good" rank-one updates of it (Sherman-Morrison),
//
//     H_(k+1) = H_k + (s_k - H_k y_k) s_k^T H_k / (s_k^T H_k y_k) = (I + u_k s_k^T) H_k
//
// (s_k a Newton step, y_k its change of the residual, u_k = (s_k - H_k y_k) / (s_k^T H_k y_k);
// C. T. Kelley, Iterative Methods for Linear and Nonlinear Equations, SIAM 1995, ch. 7), in one
// of two forms by the number of unknowns n = 6 + 18 (M - 1) + m:
// - n <= kDenseUnknowns: H itself, dense (n^2 flops a step, n^3 a fresh Jacobian);
// - above: KLU's factors of J0 (SuiteSparse; its rows in staircase order, so that partial
//   pivoting in that order fills only inside the staircase) and the pairs (u_k, s_k): one sparse
//   solve and 2 n k flops a step. After kMaxUpdates pairs the model asks for a fresh Jacobian.
// The same iterates in exact arithmetic. Measured (the undamped cantilever, N = 50, 300 steps,
// one core, docs/dynamics.md "Multiple shooting below the bound"): the dense form is 8-15 %
// faster at n = 24-78, the sparse 14 % faster at n = 114 and 14x at n = 564.
//
// A copy keeps the Jacobian and the updates and factorises the Jacobian again where it is first
// used (KLU's factors are not copyable; the factorisation is deterministic, so the copy's
// steps are the original's).
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace rodlab::solvers::dynamics {

class InverseBroyden {
 public:
  using Jacobian = Eigen::SparseMatrix<double>;
  using Vector = Eigen::VectorXd;

  /// Up to this many unknowns H is kept dense (measured crossover: above).
  static constexpr Eigen::Index kDenseUnknowns = 96;
  /// Update pairs the sparse form keeps before it asks for a fresh Jacobian (2 n doubles each;
  /// 32, 64 and 128 within 10 % of one another at n = 564).
  static constexpr int kMaxUpdates = 64;

  InverseBroyden();
  ~InverseBroyden();
  InverseBroyden(const InverseBroyden& o);
  InverseBroyden& operator=(const InverseBroyden& o);

  /// The Jacobian a fresh build fills (its pattern set by the caller), then refresh().
  Jacobian& jacobian() { return J_; }

  /// Inverts (dense) or factorises (sparse) the Jacobian and drops the updates; false if it is
  /// singular or not finite.
  bool refresh();

  /// Newton's step -H r.
  Vector step(const Vector& r);

  /// Broyden's update for the step s from the residual r (the last step's) to r_new; false
  /// once the sparse form keeps kMaxUpdates pairs (it then wants a fresh Jacobian). The sparse
  /// form makes one solve: H y = H r_new - H r, H r kept from step(r), and keeps the updated
  /// H r_new for the next step.
  bool update(const Vector& s, const Vector& r, const Vector& r_new);

 private:
  struct Factors;  // KLU's (inverse_broyden.cpp)

  bool dense() const { return J_.rows() <= kDenseUnknowns; }
  bool factorise();
  bool step_input_is(const Vector& r) const { return r.size() == at_.size() && r == at_; }
  /// The sparse form's H v: the factors' solve, then the updates in the order they were made.
  Vector apply(const Vector& v);

  Jacobian J_;
  Eigen::MatrixXd H_;  ///< the dense form's H
  std::vector<Vector> s_, u_;
  Vector at_, H_at_;  ///< the last residual the sparse H was applied to, and H applied to it
  std::unique_ptr<Factors> lu_;
};

}  // namespace rodlab::solvers::dynamics
