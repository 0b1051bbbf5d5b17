#include "rodlab/solvers/control/nlsq_mpc.hpp"

#include <algorithm>
#include <cmath>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/box_qp.hpp"

namespace rodlab::solvers::control {
namespace {

/// Levenberg-Marquardt: the damping's start (relative to diag(J^T J)), its growth on a
/// rejected step, the gain ratio that accepts a step, and the trials per iteration.
constexpr double kInitialDamping = 1e-3;
constexpr double kDampingGrowth = 4.0;
constexpr double kAcceptRatio = 1e-4;
constexpr int kTrialsPerIteration = 12;
/// A step accepted with a gain ratio above this updates the Jacobian by Broyden's rank-one
/// formula; a worse one recomputes it (the problem is nearly linear over a plan's steps).
constexpr double kBroydenRatio = 0.75;

}  // namespace

NlsqMpc::NlsqMpc(const Plant& plant, const MpcOptions& options)
    : options_(options), lin_(plant, LinearisationOptions{1e-5, false}), start_(plant.snapshot()) {
  RODLAB_THROW_UNLESS(options.horizon >= 1, "nlsq-mpc: horizon must be >= 1 (got {})",
                      options.horizon);
  RODLAB_THROW_UNLESS(options.input_rate_weight >= 0.0 && options.input_weight >= 0.0 &&
                          options.terminal_weight >= 0.0,
                      "nlsq-mpc: weights must be >= 0");
  RODLAB_THROW_UNLESS(options.max_iterations >= 1, "nlsq-mpc: max_iterations must be >= 1");
  const int H = options.horizon, m = plant.input_count(), n = plant.state_size();
  for (int k = 0; k <= H; ++k) states_.push_back(plant.snapshot());
  xs_.assign(H, Eigen::VectorXd(n));
  tips_.resize(H);
  plan_.resize(H, m);
  reset(plant);
  range_ = (plant.upper() - plant.lower()).cwiseMax(1e-300);
  dx_.resize(n);
  du_.resize(m);
  zero_u_ = Eigen::VectorXd::Zero(m);
  zero_x_ = Eigen::VectorXd::Zero(n);
  d_.dx.resize(n);
}

void NlsqMpc::reset(const Plant& plant) {
  for (int k = 0; k < options_.horizon; ++k) plan_.row(k) = plant.input().transpose();
  applied_ = plant.input();
  J_.resize(0, 0);
  rolled_out_ = false;
}

bool NlsqMpc::residuals(Plant& plant, std::span<const Vector3> targets, const Eigen::VectorXd& U,
                        Eigen::VectorXd& r, std::string& reason) {
  const int H = options_.horizon, m = plant.input_count();
  const bool effort = options_.input_weight > 0.0;
  r.resize(3 * H + H * m + (effort ? H * m : 0));
  plant.restore(start_);
  const double L = plant.length();
  const bool warm = rolled_out_;
  rolled_out_ = false;
  for (int k = 0; k < H; ++k) {
    plant.set_input(U.segment(k * m, m));
    plant.save(states_[k]);
    // the last rollout solved this step for nearby inputs: its solve's end starts this one
    if (warm) plant.warm_start_from(states_[k + 1]);
    const dynamics::StepStatus status = plant.advance();
    if (!status.ok) {
      reason = status.reason;
      return false;
    }
    plant.read_state(std::span<double>(xs_[k].data(), xs_[k].size()));
    tips_[k] = plant.tip();
    if (k + 1 == H) plant.save(states_[H]);  // (the others are the next steps' starts)
    r.segment<3>(3 * k) = weight(k) * (tips_[k] - targets[k]) / L;
  }
  const double rate = std::sqrt(options_.input_rate_weight);
  const double w = std::sqrt(options_.input_weight);
  for (int k = 0; k < H; ++k)
    for (int i = 0; i < m; ++i) {
      const double previous = k == 0 ? applied_[i] : U[(k - 1) * m + i];
      r[3 * H + k * m + i] = rate * (U[k * m + i] - previous) / range_[i];
      if (effort) r[3 * H + H * m + k * m + i] = w * (U[k * m + i] - plant.lower()[i]) / range_[i];
    }
  rolled_out_ = true;
  return true;
}

bool NlsqMpc::jacobian(Plant& plant, Eigen::MatrixXd& J, std::string& reason) {
  const int H = options_.horizon, m = plant.input_count(), n_u = H * m;
  const bool effort = options_.input_weight > 0.0;
  J.setZero(3 * H + n_u + (effort ? n_u : 0), n_u);
  const bool linearised =
      options_.jacobian == JacobianMethod::implicit_function && plant.has_step_linearisation();
  if (!(linearised ? linearised_tracking_rows(plant, J, reason)
                   : differenced_tracking_rows(plant, J, reason)))
    return false;
  const double rate = std::sqrt(options_.input_rate_weight);
  const double w = std::sqrt(options_.input_weight);
  for (int k = 0; k < H; ++k)
    for (int i = 0; i < m; ++i) {
      const int row = k * m + i;
      J(3 * H + row, row) = rate / range_[i];
      if (k > 0) J(3 * H + row, row - m) = -rate / range_[i];
      if (effort) J(3 * H + n_u + row, row) = w / range_[i];
    }
  return true;
}

// d p_(k+1) / d u_j = D_k (k = j), C_k A_(k-1) ... A_(j+1) B_j (k > j): each step linearised once
// along the rollout (H steps), then chained.
bool NlsqMpc::linearised_tracking_rows(Plant& plant, Eigen::MatrixXd& J, std::string& reason) {
  const int H = options_.horizon, m = plant.input_count();
  const double L = plant.length();
  if (static_cast<int>(A_.size()) != H) A_.resize(H), B_.resize(H), C_.resize(H), D_.resize(H);
  for (int k = 0; k < H; ++k) {
    plant.restore(states_[k]);  // x_k under u_k (the rollout); its step's solve ends in x_(k+1)
    plant.warm_start_from(states_[k + 1]);
    const auto status = plant.advance_linearised(A_[k], B_[k], C_[k], D_[k]);
    if (!status.ok) {
      reason = status.reason;
      return false;
    }
  }
  for (int j = 0; j < H; ++j) {
    J.block(3 * j, j * m, 3, m) = (weight(j) / L) * D_[j];
    Phi_ = B_[j];
    for (int k = j + 1; k < H; ++k) {
      J.block(3 * k, j * m, 3, m).noalias() = (weight(k) / L) * C_[k] * Phi_;
      if (k + 1 < H) {
        Phi_next_.noalias() = A_[k] * Phi_;
        Phi_.swap(Phi_next_);
      }
    }
  }
  return true;
}

bool NlsqMpc::differenced_tracking_rows(Plant& plant, Eigen::MatrixXd& J, std::string& reason) {
  const int H = options_.horizon, m = plant.input_count();
  const double L = plant.length();  // the tracking residuals are (p_k - p_des,k) / L
  for (int j = 0; j < H; ++j)
    for (int i = 0; i < m; ++i) {
      const int col = j * m + i;
      du_.setZero();
      du_[i] = range_[i];
      for (int k = j; k < H; ++k) {  // u_j,i acts on p_(j+1) and propagates to p_H
        plant.restore(states_[k]);   // x_k under u_k (the rollout)
        const PlantSnapshot& after = states_[k + 1];
        const auto status =
            k == j ? lin_.directional(plant, zero_x_, du_, d_, xs_[k], tips_[k], after)
                   : lin_.directional(plant, dx_, zero_u_, d_, xs_[k], tips_[k], after);
        if (!status.ok) {
          reason = status.reason;
          return false;
        }
        J.block<3, 1>(3 * k, col) = weight(k) * d_.dtip / (range_[i] * L);
        dx_ = d_.dx;
      }
    }
  return true;
}

bool NlsqMpc::evaluate(Plant& plant, std::span<const Vector3> targets, const Eigen::VectorXd& U,
                       Eigen::VectorXd& r, Eigen::MatrixXd* J, std::string& reason) {
  rolled_out_ = false;
  RODLAB_THROW_UNLESS(static_cast<int>(targets.size()) == options_.horizon &&
                          U.size() == options_.horizon * plant.input_count(),
                      "nlsq-mpc: expected {} targets and {} inputs", options_.horizon,
                      options_.horizon * plant.input_count());
  plant.save(start_);
  applied_ = plant.input();
  bool ok = residuals(plant, targets, U, r, reason);
  if (ok && J != nullptr) ok = jacobian(plant, *J, reason);
  plant.restore(start_);
  return ok;
}

MpcPlan NlsqMpc::plan(Plant& plant, std::span<const Vector3> targets) {
  const int H = options_.horizon, m = plant.input_count(), n_u = H * m;
  RODLAB_THROW_UNLESS(static_cast<int>(targets.size()) == H,
                      "nlsq-mpc: expected {} targets (one per step of the horizon), got {}", H,
                      targets.size());
  plant.save(start_);
  applied_ = plant.input();
  rolled_out_ = false;  // the last rollout started elsewhere
  // warm start: the last plan shifted by a step, its last input repeated, inside the limits
  for (int k = 0; k + 1 < H; ++k) plan_.row(k) = plan_.row(k + 1);
  U_.resize(n_u);
  for (int k = 0; k < H; ++k)
    for (int i = 0; i < m; ++i)
      U_[k * m + i] = std::clamp(plan_(k, i), plant.lower()[i], plant.upper()[i]);
  const Eigen::VectorXd range = range_.replicate(H, 1);
  const Eigen::VectorXd lower = plant.lower().replicate(H, 1), upper = plant.upper().replicate(H, 1);

  MpcPlan out;
  std::string why;
  ++out.rollouts;
  if (!residuals(plant, targets, U_, r_, why)) {
    // the shifted plan's input jumps can exceed what single shooting converges from at a small
    // dt (docs/dynamics.md "The lower step bound"); the input now applied, held, has no jump
    for (int k = 0; k < H; ++k) U_.segment(k * m, m) = applied_;
    ++out.rollouts;
    std::string held;
    if (!residuals(plant, targets, U_, r_, held)) {
      out.ok = false;
      out.reason = "nlsq-mpc: the rollout of the warm start failed: " + why +
                   "; so did the rollout of the input held: " + held;
    }
  }
  bool at_U = true;  // the last rollout was U_'s (the Jacobian is built along it)
  // Along U_; false (reason set) when a step fails.
  auto exact_jacobian = [&] {
    if (!at_U) {
      ++out.rollouts;
      if (!residuals(plant, targets, U_, r_, why)) return false;
      at_U = true;
    }
    ++out.jacobians;
    return jacobian(plant, J_, why);
  };
  // the last plan's Jacobian: its blocks depend on k - j alone for a plant that changes little
  // over a step (MpcOptions::reuse_jacobian); a poor prediction replaces it below
  bool fresh = false;
  const bool reuse = options_.reuse_jacobian && J_.rows() == r_.size() && J_.cols() == n_u;
  if (out.ok && !reuse) {
    if (!exact_jacobian()) {
      out.ok = false;
      out.reason = "nlsq-mpc: a step of the linearisation failed: " + why;
    }
    fresh = true;
  }
  double mu = -1.0;  // damping, set from the first J^T J
  for (; out.ok && out.iterations < options_.max_iterations; ++out.iterations) {
    // Levenberg-Marquardt in the scaled inputs z = U / range: min 1/2 |r + J_z d|^2 + mu/2 d^T D d
    const Eigen::MatrixXd Jz = J_ * range.asDiagonal();
    const Eigen::MatrixXd A = Jz.transpose() * Jz;
    const Eigen::VectorXd g = Jz.transpose() * r_;
    const Eigen::VectorXd D = A.diagonal().cwiseMax(1e-12 * A.diagonal().maxCoeff() + 1e-300);
    if (mu < 0.0) mu = kInitialDamping;
    z_lower_ = (lower - U_).cwiseQuotient(range);
    z_upper_ = (upper - U_).cwiseQuotient(range);
    const double cost = 0.5 * r_.squaredNorm();
    bool accepted = false;
    double decrease = 0.0, rho_accepted = 0.0;
    r_old_ = r_;
    U_old_ = U_;
    for (int trial = 0; trial < kTrialsPerIteration && !accepted; ++trial) {
      Eigen::MatrixXd Am = A;
      Am.diagonal() += mu * D;
      const BoxQpResult qp =
          solve_box_qp(Am, g, z_lower_, z_upper_, Eigen::VectorXd::Zero(n_u));
      const double predicted = -(g.dot(qp.x) + 0.5 * qp.x.dot(A * qp.x));
      if (!qp.ok || !(predicted > 0.0)) break;  // stationary in the box
      U_trial_ = (U_ + qp.x.cwiseProduct(range)).cwiseMax(lower).cwiseMin(upper);
      ++out.rollouts;
      const bool ran = residuals(plant, targets, U_trial_, r_trial_, why);
      at_U = false;
      const double rho = ran ? (cost - 0.5 * r_trial_.squaredNorm()) / predicted : -1.0;
      if (rho > kAcceptRatio) {
        accepted = true;
        decrease = cost - 0.5 * r_trial_.squaredNorm();
        rho_accepted = rho;
        U_ = U_trial_;
        r_ = r_trial_;
        at_U = true;
        mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));  // Nielsen
      } else {
        mu *= kDampingGrowth;
      }
    }
    if (!accepted && fresh) break;  // no trial decreased the cost: a (local) minimum in the box
    if (accepted && decrease <= options_.function_tolerance * cost) {
      ++out.iterations;
      break;
    }
    if (accepted && rho_accepted > kBroydenRatio) {
      // the model predicted well: Broyden's rank-one update instead of a new Jacobian
      const Eigen::VectorXd dU = U_ - U_old_;
      J_ += ((r_ - r_old_) - J_ * dU) * dU.transpose() / dU.squaredNorm();
      fresh = false;
    } else if (!exact_jacobian()) {  // a poor or no step with an updated or reused Jacobian
      out.ok = false;
      out.reason = "nlsq-mpc: a step of the linearisation failed: " + why;
      break;
    } else {
      fresh = true;
      mu = kInitialDamping;
    }
  }
  out.cost = r_.squaredNorm();
  for (int k = 0; k < H; ++k) plan_.row(k) = U_.segment(k * m, m).transpose();
  out.u = plan_.row(0).transpose();
  plant.restore(start_);
  return out;
}

}  // namespace rodlab::solvers::control
