#pragma once
// A `chebyshev` statics solution that is kept and followed while the actuator inputs change, with
// the tip's sensitivity to the inputs: the forward model of inverse statics
// (control/inverse_statics.hpp), called once per residual and once per Jacobian evaluation.
//
// FOLLOWING. solve(u) sets the inputs (ActuatorTerm::input of every actuator, in the problem's
// order) and runs the collocation's Newton at load factor 1 from the last equilibrium x(u_old),
// moved by the first-order predictor x(u_old) + dx/du (u - u_old) when the sensitivity is known,
// with chord steps on the Newton matrix factorised there (refreshed when they stop contracting,
// as in solve_chebyshev). If that fails, or the layout no longer fits (a chart turns by more than
// 2 pi / 3), solve_chebyshev's full strategy runs from scratch (its guesses, continuation and
// element splits) and its solution is kept instead.
//
// SENSITIVITY (implicit function theorem; the exact counterpart of thesis (4.10),
// J = E_q - E_xi B_xi^-1 B_q). At a solution F(x, u) = 0 of the collocation system,
//     dx/du = -F_x^-1 F_u,   d p_tip/du = (d p_tip/dx) dx/du,
// with F_x the scheme's own Newton matrix evaluated at the solution and factorised by
// condensation (chebyshev_newton_matrix.hpp: exact up to its differenced node blocks, ~1e-10),
// F_u in closed form through the tendon law (an input moves the residual only through its
// actuator's axial force, dxi/dF_k = -(d law/d xi)^-1 c_k(xi) at fixed Lambda, and through a
// length-controlled actuator's target length; chebyshev.cpp, Collocation::input_jacobian), and
// d p_tip/dx applied as a central difference along dx/du (p_tip depends on x only through the
// charts' chain and the last node's theta). Cost: one Newton matrix and factorisation, one
// strain solve per node, m solves (m inputs). The factorisation is then kept for the next
// solve's chord steps.
#include <memory>
#include <span>
#include <string>

#include <Eigen/Core>

#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/statics/chebyshev.hpp"
#include "rodlab/solvers/statics/static_problem.hpp"

namespace rodlab::solvers::statics {

class ChebyshevTracker {
 public:
  using TipJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic>;

  /// Throws std::invalid_argument as solve_chebyshev does (bad nodes or elements).
  ChebyshevTracker(const StaticProblem& problem, const ChebyshevOptions& options);
  ~ChebyshevTracker();
  ChebyshevTracker(ChebyshevTracker&&) noexcept;
  ChebyshevTracker& operator=(ChebyshevTracker&&) noexcept;

  /// Number of inputs: one per actuator of the problem.
  int inputs() const;
  /// Sets the inputs and solves (above). Returns whether it converged; reason() says why not.
  /// Non-convergence leaves the last converged solution in place for the next warm start.
  bool solve(std::span<const double> inputs);
  /// Why the last solve did not converge (empty if it did).
  const std::string& reason() const;
  /// Newton iterations of the last solve (warm, or all attempts of a full solve).
  int iterations() const;
  /// Whether the last solve converged from the kept equilibrium (no full solve).
  bool warm() const;
  /// Tip position of the last converged solution (world frame).
  const Vector3& tip_position() const;
  /// d p_tip / d u at the last converged solution (3 x inputs(), world frame); `steps`: the
  /// central-difference step of each input for the scalars dF_k/du_k and d target/du_k (and a
  /// cable entry's row), about 1e-6 of its range. False if the Newton matrix is singular there
  /// (J is then left unchanged).
  bool tip_jacobian(std::span<const double> steps, TipJacobian& J);
  /// The full result of the last converged solution (allocates; not for the hot loop).
  result::StaticResult result() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rodlab::solvers::statics
