#include "rodlab/solvers/control/plant_ilqr.hpp"

#include "rodlab/check.hpp"

namespace rodlab::solvers::control {
namespace {

/// eps of the header, on the scaled state.
constexpr double kStateRegularisation = 1e-8;

}  // namespace

PlantIlqrModel::PlantIlqrModel(Plant& plant, int horizon, double input_weight,
                               double terminal_weight, JacobianMethod method)
    : plant_(plant), horizon_(horizon), input_weight_(input_weight),
      terminal_weight_(terminal_weight), initial_(plant.snapshot()), targets_(horizon),
      lin_(plant, LinearisationOptions{.method = method}) {
  RODLAB_THROW_UNLESS(horizon >= 1, "ilqr: horizon must be >= 1 (got {})", horizon);
  for (int k = 0; k < horizon; ++k) {
    kept_.push_back(plant.snapshot());
    kept_trial_.push_back(plant.snapshot());
  }
  range_ = (plant.upper() - plant.lower()).cwiseMax(1e-300);
}

void PlantIlqrModel::start(std::span<const Vector3> targets) {
  RODLAB_THROW_UNLESS(static_cast<int>(targets.size()) == horizon_,
                      "ilqr: expected {} targets, got {}", horizon_, targets.size());
  plant_.save(initial_);
  targets_.assign(targets.begin(), targets.end());
}

void PlantIlqrModel::state(Eigen::VectorXd& x) const {
  x.resize(plant_.state_size());
  plant_.read_state(std::span<double>(x.data(), x.size()));
}

bool PlantIlqrModel::step(int k, const Eigen::VectorXd& u, double& cost) {
  plant_.set_input(u);
  if (!plant_.advance().ok) return false;
  const double L = plant_.length();
  cost += weight(k) * (plant_.tip() - targets_[k]).squaredNorm() / (L * L) +
          input_weight_ * (u - plant_.lower()).cwiseQuotient(range_).squaredNorm();
  return true;
}

bool PlantIlqrModel::linearise(int k, const Eigen::VectorXd& u, Eigen::MatrixXd& A,
                               Eigen::MatrixXd& B, Eigen::VectorXd& l_x, Eigen::VectorXd& l_u,
                               Eigen::MatrixXd& l_xx, Eigen::MatrixXd& l_uu,
                               Eigen::MatrixXd& l_ux) {
  // the step's Jacobians at the kept state and the nominal tip error after it (the nominal
  // rollout's solve of the step, which ended in the next kept state, starts this one)
  plant_.restore(kept_[k]);
  if (k + 1 < horizon_) plant_.warm_start_from(kept_[k + 1]);
  plant_.set_input(u);
  Vector3 tip;
  if (!lin_.jacobians(plant_, A, B, C_, D_, &tip).ok) return false;
  const double L = plant_.length(), w = weight(k);
  const Eigen::Vector3d e = (tip - targets_[k]) / L;
  const Eigen::VectorXd R = input_weight_ * range_.cwiseInverse().cwiseAbs2();
  l_x = (2.0 * w / L) * C_.transpose() * e;
  l_u = (2.0 * w / L) * D_.transpose() * e + 2.0 * R.cwiseProduct(u - plant_.lower());
  l_xx = (2.0 * w / (L * L)) * C_.transpose() * C_;
  l_xx.diagonal() += 2.0 * kStateRegularisation * plant_.state_scale().cwiseInverse().cwiseAbs2();
  l_uu = (2.0 * w / (L * L)) * D_.transpose() * D_;
  l_uu.diagonal() += 2.0 * R;
  l_ux = (2.0 * w / (L * L)) * D_.transpose() * C_;
  return true;
}

}  // namespace rodlab::solvers::control
