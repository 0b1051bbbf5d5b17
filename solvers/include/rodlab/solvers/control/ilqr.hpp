#pragma once
// Iterative LQR with input limits (box-DDP: Tassa, Mansard & Todorov, ICRA 2014; docs/control.md
// "iLQR"). The thesis' Algorithm 4 is not iLQR: it applies u = -K x to the absolute state and has
// no feed-forward term, no line search and no target. Here, on deviations from a nominal
// trajectory (x_k, u_k), k = 0..H-1:
//
//   backward:  Q_x = l_x + A^T V_x,  Q_u = l_u + B^T V_x,
//              Q_xx = l_xx + A^T V_xx A,  Q_uu = l_uu + B^T V_xx B + mu I,  Q_ux = l_ux + B^T V_xx A,
//              k = argmin_{lower <= u + k <= upper} 1/2 k^T Q_uu k + Q_u^T k   (box QP, box_qp.hpp)
//              K = -Q_uu,ff^-1 Q_ux on the free inputs, 0 on the clamped ones,
//              V_x = Q_x + K^T Q_uu k + K^T Q_u + Q_ux^T k,  V_xx = Q_xx + K^T Q_uu K + K^T Q_ux + Q_ux^T K
//   forward:   u_k = clamp(u_k + alpha k_k + K_k (x_k' - x_k)), alpha = 1, 1/2, ... until the true
//              cost falls (Armijo on the expected decrease)
//
// with Levenberg regularisation mu (raised when Q_uu is not positive definite or no step is
// accepted, lowered after a success). The stage costs and the linearisations come from the
// model (IlqrModel), so the algorithm is tested on small systems with known optima and runs the
// rod through the plant.
#include <string>
#include <vector>

#include <Eigen/Core>

namespace rodlab::solvers::control {

/// What iLQR needs of a system with H stages (stage k: x_k, u_k -> x_(k+1) and cost l_k).
class IlqrModel {
 public:
  virtual ~IlqrModel() = default;
  virtual int state_size() const = 0;
  virtual int input_size() const = 0;
  virtual const Eigen::VectorXd& lower() const = 0;
  virtual const Eigen::VectorXd& upper() const = 0;
  /// Back to the initial state x_0.
  virtual void reset() = 0;
  /// The current state's coordinates.
  virtual void state(Eigen::VectorXd& x) const = 0;
  /// Applies u at stage k from the current state; adds l_k(x_k, u_k) to cost. False: the step
  /// failed (the trial is rejected).
  virtual bool step(int k, const Eigen::VectorXd& u, double& cost) = 0;
  /// Keeps the current state as the nominal state of stage k (before its step).
  virtual void keep(int k) = 0;
  /// Keeps the current state as stage k's of the line search's trial rollout.
  virtual void keep_trial(int /*k*/) {}
  /// Makes the kept trial states the nominal ones (the trial was accepted, so its rollout is the
  /// new nominal one); false when the model keeps no trial states (solve_ilqr then runs the
  /// nominal rollout again).
  virtual bool accept_trial() { return false; }
  /// At the kept state of stage k with input u: the step's Jacobians A, B and the stage cost's
  /// gradient and (Gauss-Newton) Hessian. False: a step failed.
  virtual bool linearise(int k, const Eigen::VectorXd& u, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                         Eigen::VectorXd& l_x, Eigen::VectorXd& l_u, Eigen::MatrixXd& l_xx,
                         Eigen::MatrixXd& l_uu, Eigen::MatrixXd& l_ux) = 0;
};

struct IlqrOptions {
  int max_iterations = 50;
  double tolerance = 1e-8;      ///< relative cost decrease that ends the iterations
  double initial_mu = 1e-6;     ///< Levenberg regularisation of V_xx's contribution to Q_uu
  double mu_factor = 10.0;
  double max_mu = 1e10;
  double armijo = 1e-4;         ///< accepted when the decrease is this share of the expected
};

struct IlqrResult {
  bool ok = false;
  std::string reason;
  int iterations = 0;
  std::vector<double> costs;          ///< the true cost after each accepted iteration (first: the start)
  std::vector<Eigen::VectorXd> u;     ///< the inputs u_0..u_(H-1)
  std::vector<Eigen::MatrixXd> K;     ///< the feedback gains of the last backward pass
};

/// Optimises H stages from the model's initial state, starting from the inputs u (clamped).
IlqrResult solve_ilqr(IlqrModel& model, std::vector<Eigen::VectorXd> u, const IlqrOptions& options = {});

}  // namespace rodlab::solvers::control
