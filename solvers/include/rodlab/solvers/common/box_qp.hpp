#pragma once
// The box-constrained quadratic program of control-limited DDP (Tassa, Mansard & Todorov,
// "Control-limited differential dynamic programming", ICRA 2014, Algorithm 1):
//
//   min_x  1/2 x^T H x + g^T x   subject to  lower <= x <= upper,   H symmetric positive definite,
//
// by projected Newton: the variables on a bound whose gradient pushes outward are clamped, a
// Newton step is taken in the free ones (Cholesky of H_ff), and a projected Armijo line search
// keeps the iterate in the box. It is the bounded step of every least-squares solver of the
// control chapter (docs/control.md: Ceres' projected bounds stalled there): inverse statics'
// Gauss-Newton, NLSQ-MPC's Levenberg-Marquardt, and the feed-forward of iLQR with input limits
// (whose feedback acts on the free set it returns).
#include <string>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace rodlab::solvers {

struct BoxQpResult {
  bool ok = true;
  std::string reason;  ///< H_ff not positive definite, no descent, no convergence
  int iterations = 0;
  Eigen::VectorXd x;
  /// free[i] != 0: x_i is not clamped at the solution
  Eigen::VectorXi free;
};

struct BoxQpOptions {
  int max_iterations = 100;
  double gradient_tolerance = 1e-10;  ///< on the free gradient's norm, relative to |g| + 1
  double min_step = 1e-22;            ///< the line search gives up below this step
  double armijo = 0.1;                ///< sufficient decrease
};

/// Solves the QP from x0 (clamped into the box). Throws std::invalid_argument for mismatched
/// sizes or lower > upper.
BoxQpResult solve_box_qp(const Eigen::MatrixXd& H, const Eigen::VectorXd& g,
                         const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                         const Eigen::VectorXd& x0, const BoxQpOptions& options = {});

}  // namespace rodlab::solvers
