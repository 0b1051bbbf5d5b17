#include "rodlab/solvers/control/linearisation.hpp"

#include <algorithm>
#include <cmath>

#include "rodlab/check.hpp"

namespace rodlab::solvers::control {
namespace {

/// Whether u + h du lies inside the plant's limits.
bool feasible(const Plant& plant, const Eigen::VectorXd& u, double h,
              const Eigen::Ref<const Eigen::VectorXd>& du) {
  for (int k = 0; k < plant.input_count(); ++k) {
    const double v = u[k] + h * du[k];
    if (v < plant.lower()[k] || v > plant.upper()[k]) return false;
  }
  return true;
}

}  // namespace

Linearisation::Linearisation(const Plant& plant, LinearisationOptions options)
    : options_(options), start_(plant.snapshot()) {
  RODLAB_THROW_UNLESS(options.relative_step > 0.0 && options.relative_step < 1.0,
                      "linearisation: relative_step must lie in (0, 1) (got {:g})",
                      options.relative_step);
  const int n = plant.state_size(), m = plant.input_count();
  x_plus_.resize(n);
  x_minus_.resize(n);
  step_.resize(n);
  u_.resize(m);
  e_x_.resize(n);
  e_u_.resize(m);
  column_.dx.resize(n);
}

dynamics::StepStatus Linearisation::perturbed(Plant& plant, double h,
                                              const Eigen::Ref<const Eigen::VectorXd>& dx,
                                              const Eigen::Ref<const Eigen::VectorXd>& du,
                                              Eigen::VectorXd& x, Vector3& tip) {
  plant.restore(start_);
  if (after_ != nullptr) plant.warm_start_from(*after_);
  if (h != 0.0) {
    step_ = h * dx;
    plant.add_state(std::span<const double>(step_.data(), step_.size()));
    u_ = start_.u + h * du;
    plant.set_input(u_);
  }
  const dynamics::StepStatus status = plant.advance();
  plant.read_state(std::span<double>(x.data(), x.size()));
  tip = plant.tip();
  return status;
}

dynamics::StepStatus Linearisation::directional(Plant& plant,
                                                const Eigen::Ref<const Eigen::VectorXd>& dx,
                                                const Eigen::Ref<const Eigen::VectorXd>& du,
                                                StepDerivative& out) {
  return difference(plant, dx, du, out, nullptr, nullptr);
}

dynamics::StepStatus Linearisation::directional(Plant& plant,
                                                const Eigen::Ref<const Eigen::VectorXd>& dx,
                                                const Eigen::Ref<const Eigen::VectorXd>& du,
                                                StepDerivative& out, const Eigen::VectorXd& x_next,
                                                const Vector3& tip_next, const PlantSnapshot& after) {
  after_ = &after;
  const dynamics::StepStatus status = difference(plant, dx, du, out, &x_next, &tip_next);
  after_ = nullptr;
  return status;
}

dynamics::StepStatus Linearisation::difference(Plant& plant,
                                               const Eigen::Ref<const Eigen::VectorXd>& dx,
                                               const Eigen::Ref<const Eigen::VectorXd>& du,
                                               StepDerivative& out, const Eigen::VectorXd* x_next,
                                               const Vector3* tip_next) {
  RODLAB_THROW_UNLESS(dx.size() == plant.state_size() && du.size() == plant.input_count(),
                      "linearisation: expected directions of sizes {} and {}, got {} and {}",
                      plant.state_size(), plant.input_count(), dx.size(), du.size());
  plant.save(start_);
  // h makes the scaled direction's largest component relative_step
  double size = 0.0;
  for (int i = 0; i < dx.size(); ++i)
    size = std::max(size, std::abs(dx[i]) / plant.state_scale()[i]);
  for (int k = 0; k < du.size(); ++k)
    size = std::max(size, std::abs(du[k]) / std::max(plant.upper()[k] - plant.lower()[k], 1e-300));
  out.dx.setZero(plant.state_size());
  out.dtip.setZero();
  if (size == 0.0) return {};
  const double h = options_.relative_step / size;
  const bool up = feasible(plant, start_.u, h, du), down = feasible(plant, start_.u, -h, du);
  Vector3 tip_plus, tip_minus;
  dynamics::StepStatus status;
  double span = h;
  if (options_.central && up && down) {
    status = perturbed(plant, h, dx, du, x_plus_, tip_plus);
    if (status.ok) status = perturbed(plant, -h, dx, du, x_minus_, tip_minus);
    span = 2.0 * h;
  } else {  // one-sided: the feasible side (forward as (4.33)-(4.34) where both are)
    RODLAB_THROW_UNLESS(up || down, "linearisation: neither side of the input direction is feasible");
    const double side = up ? h : -h;
    Eigen::VectorXd& moved = up ? x_plus_ : x_minus_;
    Eigen::VectorXd& nominal = up ? x_minus_ : x_plus_;
    Vector3& tip_moved = up ? tip_plus : tip_minus;
    Vector3& tip_nominal = up ? tip_minus : tip_plus;
    status = perturbed(plant, side, dx, du, moved, tip_moved);
    if (status.ok && x_next != nullptr) {
      nominal = *x_next;
      tip_nominal = *tip_next;
    } else if (status.ok) {
      status = perturbed(plant, 0.0, dx, du, nominal, tip_nominal);
    }
  }
  if (status.ok) {
    out.dx = (x_plus_ - x_minus_) / span;
    out.dtip = (tip_plus - tip_minus) / span;
  }
  plant.restore(start_);
  return status;
}

dynamics::StepStatus Linearisation::jacobians(Plant& plant, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                              Eigen::MatrixXd& C, Eigen::MatrixXd& D,
                                              Vector3* tip_next) {
  if (options_.method == JacobianMethod::implicit_function && plant.has_step_linearisation()) {
    plant.save(start_);
    const dynamics::StepStatus status = plant.advance_linearised(A, B, C, D);
    if (tip_next != nullptr) *tip_next = plant.tip();
    plant.restore(start_);
    return status;
  }
  if (tip_next != nullptr) {
    plant.save(start_);
    const dynamics::StepStatus status = plant.advance();
    *tip_next = plant.tip();
    plant.restore(start_);
    if (!status.ok) return status;
  }
  const int n = plant.state_size(), m = plant.input_count();
  A.resize(n, n);
  B.resize(n, m);
  C.resize(3, n);
  D.resize(3, m);
  e_u_.setZero();
  for (int i = 0; i < n; ++i) {  // (4.33), column i along the scaled unit direction
    e_x_.setZero();
    e_x_[i] = plant.state_scale()[i];
    const auto status = directional(plant, e_x_, e_u_, column_);
    if (!status.ok) return status;
    A.col(i) = column_.dx / e_x_[i];
    C.col(i) = column_.dtip / e_x_[i];
  }
  e_x_.setZero();
  for (int k = 0; k < m; ++k) {  // (4.34)
    e_u_.setZero();
    e_u_[k] = plant.upper()[k] - plant.lower()[k];
    if (!(e_u_[k] > 0.0)) {  // a fixed input: no column
      B.col(k).setZero();
      D.col(k).setZero();
      continue;
    }
    const auto status = directional(plant, e_x_, e_u_, column_);
    if (!status.ok) return status;
    B.col(k) = column_.dx / e_u_[k];
    D.col(k) = column_.dtip / e_u_[k];
  }
  return {};
}

}  // namespace rodlab::solvers::control
