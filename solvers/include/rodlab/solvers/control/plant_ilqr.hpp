#pragma once
// The rod as an iLQR model (ilqr.hpp): the plant's control steps with the task-space stage cost
// of NLSQ-MPC (nlsq_mpc.hpp),
//
//   l_k = w_k |p_(k+1) - p*_(k+1)|^2 / L^2 + w_input |(u_k - lower) / range|^2
//         + eps |(x_k - x_k,nominal) / scale|^2 (zero along the nominal: it only keeps the
//           Gauss-Newton Hessian positive definite),
//
// w_k = 1 and w_H = w_terminal, in the plant's tangent coordinates; the Jacobians A, B of each
// stage and the tip's C, D come from the linearisation: the scheme's linearised step where it
// has one (implicit-midpoint, bdf-alpha: one step per stage), else central differences of every
// column (2 (n + m) steps per stage; docs/control.md "iLQR").
#include <span>
#include <vector>

#include "rodlab/solvers/control/ilqr.hpp"
#include "rodlab/solvers/control/linearisation.hpp"
#include "rodlab/solvers/control/plant.hpp"

namespace rodlab::solvers::control {

class PlantIlqrModel final : public IlqrModel {
 public:
  /// H stages on `plant` (kept by reference); weights as in MpcOptions.
  PlantIlqrModel(Plant& plant, int horizon, double input_weight, double terminal_weight,
                 JacobianMethod method = JacobianMethod::implicit_function);

  /// The next solve starts from the plant's current state towards targets p*_1..p*_H.
  void start(std::span<const Vector3> targets);

  int state_size() const override { return plant_.state_size(); }
  int input_size() const override { return plant_.input_count(); }
  const Eigen::VectorXd& lower() const override { return plant_.lower(); }
  const Eigen::VectorXd& upper() const override { return plant_.upper(); }
  void reset() override { plant_.restore(initial_); }
  void state(Eigen::VectorXd& x) const override;
  bool step(int k, const Eigen::VectorXd& u, double& cost) override;
  void keep(int k) override { plant_.save(kept_[k]); }
  void keep_trial(int k) override { plant_.save(kept_trial_[k]); }
  bool accept_trial() override {
    kept_.swap(kept_trial_);  // the snapshots change hands: no copy, no allocation
    return true;
  }
  bool linearise(int k, const Eigen::VectorXd& u, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                 Eigen::VectorXd& l_x, Eigen::VectorXd& l_u, Eigen::MatrixXd& l_xx,
                 Eigen::MatrixXd& l_uu, Eigen::MatrixXd& l_ux) override;

 private:
  double weight(int k) const { return k + 1 == horizon_ ? terminal_weight_ : 1.0; }

  Plant& plant_;
  int horizon_;
  double input_weight_, terminal_weight_;
  PlantSnapshot initial_;
  std::vector<PlantSnapshot> kept_, kept_trial_;
  std::vector<Vector3> targets_;
  Linearisation lin_;
  Eigen::VectorXd range_;
  Eigen::MatrixXd C_, D_;
};

}  // namespace rodlab::solvers::control
