#pragma once
// Damped Newton for small dense nonlinear systems F(x) = 0 (shooting unknowns, collocation
// blocks): finite-difference Jacobian, Broyden updates while they keep converging, and a
// backtracking line search on |F|_2. Non-convergence is a status, never an exception.
#include <functional>
#include <string>

#include <Eigen/Core>

namespace rodlab::solvers {

/// F writes the residual for x and returns false when it cannot be evaluated (non-finite).
using Residual = std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd& F)>;

struct NewtonOptions {
  double tol = 1e-10;           ///< stop when |F|_inf <= tol
  int max_iterations = 50;
  double fd_step = 1e-7;        ///< relative forward-difference step (x is assumed O(1) scaled)
  bool broyden = true;          ///< rank-one updates between finite-difference Jacobians
  /// Optional cheaper approximation of F used only for the finite-difference Jacobian (e.g. a
  /// coarse discretisation of the same equations); Broyden updates then correct it.
  Residual jacobian_residual;
  /// Optional Jacobian of F at x (F = F(x) given), instead of forward differences of F: e.g.
  /// one that knows which unknowns each residual depends on (multiple_shooting.hpp). False
  /// where it cannot be evaluated. Broyden updates it as they would the finite differences.
  std::function<bool(const Eigen::VectorXd& x, const Eigen::VectorXd& F, Eigen::MatrixXd& J)>
      jacobian;
  /// Optional rounding level of the residual at x: where a fresh Jacobian's step finds no
  /// descent at |F|_inf <= rounding_floor(x), the solve counts as converged (a tolerance below
  /// that level cannot be met by any iterate; multiple_shooting.cpp).
  std::function<double(const Eigen::VectorXd& x)> rounding_floor;
  /// Optional accuracy of the unknowns (0: off). While |F|_inf <= tol but the Newton step with
  /// the Jacobian in hand, |J^-1 F|_inf, is longer than this, Newton goes on (full steps, Broyden
  /// updates) as long as they lower |F|_2. A residual ill-conditioned in x then still gives x to
  /// this accuracy, up to its rounding level: a clamped Cosserat tip's position error costs EA / L
  /// of axial force, 16 (L / D)^2 = 1600 times the force scale for the Table 2.1 rod
  /// (docs/statics.md "Stopping where the tip is clamped").
  double step_tol = 0.0;
};

struct NewtonResult {
  Eigen::VectorXd x, F;
  double residual_norm = 0.0;   ///< |F|_inf at x
  int iterations = 0;
  int evaluations = 0;          ///< calls of F, including those of the Jacobians
  int backtracks = 0;           ///< accepted steps that the line search had to shorten
  bool converged = false;
  std::string reason;           ///< why not, when not converged
};

NewtonResult solve_newton(const Residual& F, Eigen::VectorXd x0, const NewtonOptions& options);

}  // namespace rodlab::solvers
