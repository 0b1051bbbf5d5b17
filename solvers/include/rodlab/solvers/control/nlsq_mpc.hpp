#pragma once
// Nonlinear least-squares model predictive control (thesis 4.2.1, (4.12)-(4.13);
// docs/control.md "NLSQ-MPC"). Each control step plans the inputs u_0..u_(H-1) of the next H
// control steps from the plant's current state by minimising
//
//   sum_(k=1..H) w_k |p_k - p_des,k|^2 / L^2                           tracking, in task space
//                                                            (w_k = 1, w_H = w_terminal)
//   + w_rate sum_(k=0..H-1) |(u_k - u_(k-1)) / range|^2                input rate (u_(-1): applied)
//   + w_input sum_(k=0..H-1) |(u_k - lower) / range|^2                 input effort
//
// subject to lower <= u_k <= upper (the thesis: Matlab's lsqnonlin, trust-region-reflective), by
// Levenberg-Marquardt whose bounded subproblem is a box QP (box_qp.hpp) in the inputs scaled by
// their ranges. Ceres' Levenberg-Marquardt was tried first: with tensions on their lower bound
// (antagonistic cables) its projected steps reached gain ratios of 0.01-0.2 and no convergence in
// 20 iterations, where the same problem without bounds converged in 4 (docs/control.md). The
// Jacobian of the tip trajectory
// with respect to the H x m inputs is built from the linearisation's directional derivatives
// (linearisation.hpp): for each input u_j,i one derivative at step j and its propagation through
// steps j+1..H-1 along the nominal rollout, sum_j m (H - j) one-step derivatives, not (4 H + 1) H
// rollouts; once per plan, and again only after a step the model predicted poorly (otherwise
// Broyden's rank-one update). The plan is warm-started from the previous one shifted by a step;
// the first input is applied.
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rodlab/solvers/control/linearisation.hpp"
#include "rodlab/solvers/control/plant.hpp"

namespace rodlab::solvers::control {

struct MpcOptions {
  int horizon = 10;                ///< H >= 1 control steps
  double input_rate_weight = 1e-3; ///< w_rate (dimensionless; see above)
  double input_weight = 0.0;       ///< w_input
  double terminal_weight = 1.0;    ///< w_terminal, on the last step's tracking term
  int max_iterations = 20;         ///< Levenberg-Marquardt iterations (Jacobians) per plan
  double function_tolerance = 1e-6;  ///< a relative decrease of the cost below this ends a plan
  /// Start each plan from the last plan's Jacobian (its blocks d p_(k+1) / d u_j depend on
  /// k - j alone while the plant changes little over a control step), corrected by Broyden
  /// updates and replaced by an exact one after a poorly predicted or failed step; false: an
  /// exact Jacobian at every plan's start.
  bool reuse_jacobian = true;
  /// How the exact Jacobian is built: implicit_function chains each step's own linearisation
  /// (A_k, B_k, C_k, D_k; Plant::advance_linearised) where the scheme has one; finite_difference
  /// propagates directional derivatives of whole steps along the rollout.
  JacobianMethod jacobian = JacobianMethod::implicit_function;
};

/// One plan.
struct MpcPlan {
  bool ok = true;
  std::string reason;  ///< why no plan (every rollout failed, Ceres failed)
  int iterations = 0;  ///< Levenberg-Marquardt iterations
  int jacobians = 0;   ///< tip-trajectory Jacobians computed (the rest: Broyden updates)
  int rollouts = 0;    ///< rollouts of the horizon (trial steps included)
  double cost = 0.0;   ///< the cost above at the plan
  Eigen::VectorXd u;   ///< the first input (applied)
};

class NlsqMpc {
 public:
  NlsqMpc(const Plant& plant, const MpcOptions& options);

  /// Plans from the plant's current state for the targets p_des,1..H (world frame, one per
  /// step of the horizon); the plant is back in its state on return (its input unchanged).
  MpcPlan plan(Plant& plant, std::span<const Vector3> targets);

  /// The residuals of the cost above (3H tracking, Hm rate, Hm effort when w_input > 0) and,
  /// when J is not null, their Jacobian (residuals x Hm, columns in the order of U) at the plan
  /// U (u_0, ..., u_(H-1) stacked) from the plant's current state, which is restored. False
  /// (reason set) when a rollout fails. What the solver calls; public for checks.
  bool evaluate(Plant& plant, std::span<const Vector3> targets, const Eigen::VectorXd& U,
                Eigen::VectorXd& residuals, Eigen::MatrixXd* J, std::string& reason);

  /// Forgets the last plan: the next one starts from the plant's current input held.
  void reset(const Plant& plant);

  /// The whole planned input sequence (H x m, row k = u_k).
  const Eigen::MatrixXd& planned() const { return plan_; }
  const MpcOptions& options() const { return options_; }

 private:
  /// sqrt(w_k) of the tracking term of step k (0-based).
  double weight(int k) const {
    return k + 1 == options_.horizon ? std::sqrt(options_.terminal_weight) : 1.0;
  }
  /// Rolls U out from start_ (keeping each step's state) into the residuals; false with reason
  /// when a step fails.
  bool residuals(Plant& plant, std::span<const Vector3> targets, const Eigen::VectorXd& U,
                 Eigen::VectorXd& r, std::string& reason);
  /// The residuals' Jacobian along the last rollout: d p_k / d U from the linearisation, the
  /// rate and effort rows in closed form.
  bool jacobian(Plant& plant, Eigen::MatrixXd& J, std::string& reason);
  /// Its tracking rows by finite differences (directional derivatives along the rollout) or
  /// from the steps' own linearisations.
  bool differenced_tracking_rows(Plant& plant, Eigen::MatrixXd& J, std::string& reason);
  bool linearised_tracking_rows(Plant& plant, Eigen::MatrixXd& J, std::string& reason);

  MpcOptions options_;
  Linearisation lin_;
  PlantSnapshot start_;
  std::vector<PlantSnapshot> states_;  ///< x_0..x_H of the last rollout
  bool rolled_out_ = false;  ///< states_ hold a whole rollout of this plan (warm starts)
  std::vector<Eigen::VectorXd> xs_;    ///< x_1..x_H of the last rollout (tangent coordinates)
  std::vector<Eigen::MatrixXd> A_, B_, C_, D_;  ///< the rollout's step linearisations
  Eigen::MatrixXd Phi_, Phi_next_;             ///< d x_(k+1) / d u_j while chaining them
  std::vector<Vector3> tips_;          ///< p_1..p_H of the last rollout
  Eigen::MatrixXd plan_;               ///< H x m
  Eigen::VectorXd U_, U_trial_, U_old_, r_, r_trial_, r_old_, z_lower_, z_upper_;
  Eigen::MatrixXd J_;
  Eigen::VectorXd applied_, range_, dx_, du_, zero_u_, zero_x_;
  StepDerivative d_;
};

}  // namespace rodlab::solvers::control
