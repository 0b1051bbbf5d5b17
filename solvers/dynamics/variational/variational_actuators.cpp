#include "variational_actuators.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <Eigen/LU>

#include "rodlab/check.hpp"
#include "rodlab/lie/small_angle.hpp"


namespace rodlab::solvers::dynamics {

using lie::Matrix6;
using lie::SE3;
using lie::SO3;
using lie::Vector6;
namespace se3 = lie::se3;

namespace {
/// |length - target| / L that the length-control solve reaches.
constexpr double kLengthTol = 1e-12;
/// Relative finite-difference step of its Jacobian (on the scale E I / L^2 of the forces).
constexpr double kFdStep = 1e-6;
}  // namespace

VariationalActuators::VariationalActuators(const DynamicProblem& problem, int nodes,
                                           const DiscreteLegendre& legendre)
    : P_(problem), n_(nodes), ds_(problem.length() / (nodes - 1)), legendre_(legendre) {
  if (problem.is_kirchhoff())
    throw std::invalid_argument(
        "variational: artificial muscles and length control are not supported for Kirchhoff "
        "rods yet; use implicit-midpoint-collocation, implicit-midpoint or bdf-alpha");
  muscles_ = problem.has_muscles();
  if (muscles_) {
    M_ = problem.node_inertia(n_);
    M_inv_.resize(n_);
    for (int j = 0; j < n_; ++j) M_inv_[j] = M_[j].inverse();
  }
  which_ = problem.unknown_actuators();
  const int m = static_cast<int>(which_.size());
  is_muscle_.assign(m, 0);
  unknowns_.assign(m, 0.0);
  paths_ = StaggeredPaths(problem, which_, n_);
  for (int e = 0; e < m; ++e) {
    is_muscle_[e] = problem.actuators()[which_[e]].drive == ActuatorDrive::muscle;
    if (!is_muscle_[e]) lengths_.push_back(e);
  }
  const auto ml = static_cast<Eigen::Index>(lengths_.size());
  Fl_ = Fl_prev_ = power_ = residual_ = lengths_next_ = trial_ = Eigen::VectorXd::Zero(ml);
  J_ = Eigen::MatrixXd::Zero(ml, ml);
  b_.assign(static_cast<std::size_t>(ml) * n_, Vector6::Zero());
  mu_free_.assign(n_, Vector6::Zero());
  eta_free_.assign(n_, Vector6::Zero());
  xi_next_.assign(n_ - 1, Vector6::Zero());
}

bool VariationalActuators::solve_velocity(int j, double dt, const Vector6& mu, const Vector6& mu_old,
                                          Vector6& eta) const {
  if (!muscles_) return legendre_.solve(dt, mu, mu_old, eta);
  return legendre_.solve(dt, mu, mu_old, eta, M_[j], M_inv_[j]);
}

Vector6 VariationalActuators::weight(int j, const SO3& R) const {
  if (!muscles_) return Vector6::Zero();
  const double s = j * ds_;
  return P_.embedded_weight(R, std::max(0.0, s - 0.5 * ds_), std::min(P_.length(), s + 0.5 * ds_), s);
}

const DynamicProblem::Forces& VariationalActuators::forces(double t1, std::span<const Vector6> xi) {
  if (started_) F_prev_ = F_;
  for (std::size_t e = 0; e < which_.size(); ++e)
    unknowns_[e] = is_muscle_[e] ? paths_.length(static_cast<int>(e), xi) : 0.0;
  F_ = P_.forces(t1, unknowns_.data(), paths_.rest().data());
  if (!started_) F_prev_ = F_;  // the first step: no earlier forces
  started_ = true;
  power_.setZero();
  Fl_prev_ = Fl_;
  return F_;
}

DynamicProblem::Forces VariationalActuators::work_forces() const {
  DynamicProblem::Forces W{};
  for (std::size_t k = 0; k < W.size(); ++k) W[k] = 0.5 * (F_prev_[k] + F_[k]);
  for (const int e : lengths_) W[which_[e]] = 0.0;
  return W;
}

void VariationalActuators::add_segment_power(int j, const Vector6& xi_old, const Vector6& xi,
                                             double dt) {
  const double s_mid = (j + 0.5) * ds_;
  for (std::size_t l = 0; l < lengths_.size(); ++l) {
    const auto& path = P_.actuators()[which_[lengths_[l]]].path;
    if (path.active(s_mid))
      power_[static_cast<Eigen::Index>(l)] -=
          ds_ * (path.length_rate(s_mid, xi) - path.length_rate(s_mid, xi_old)) / dt;
  }
}

void VariationalActuators::add_entry_power(double s_entry, const Vector6& xi, const Vector6& eta) {
  for (std::size_t l = 0; l < lengths_.size(); ++l) {
    const auto& a = P_.actuators()[which_[lengths_[l]]];
    if (a.enters_from_outside && a.path.s0() == s_entry)
      power_[static_cast<Eigen::Index>(l)] -= a.path.unit_wrench(s_entry, xi).dot(eta);
  }
}

void VariationalActuators::next_lengths(double dt, std::span<const SE3> G,
                                        std::span<const Vector6> eta) {
  SE3 E = SE3::identity();  // the base does not move
  for (int j = 0; j + 1 < n_; ++j) {
    const SE3 E_next = lie::small_angle::exp(dt * eta[j + 1]);
    xi_next_[j] = (E.inverse() * G[j] * E_next).log() / ds_;  // (3.38) of the next step
    E = E_next;
  }
  for (std::size_t l = 0; l < lengths_.size(); ++l)
    lengths_next_[static_cast<Eigen::Index>(l)] = paths_.length(lengths_[l], xi_next_);
}

bool VariationalActuators::apply_forces(double dt, std::span<Vector6> mu, std::span<Vector6> eta) {
  for (int j = 1; j < n_; ++j) {
    Vector6 impulse = Vector6::Zero();
    for (std::size_t l = 0; l < lengths_.size(); ++l)
      impulse += trial_[static_cast<Eigen::Index>(l)] * b_[l * n_ + j];
    mu[j] = mu_free_[j] + (dt / weight_of(j)) * impulse;
    eta[j] = eta_free_[j];
    const Vector6 mu_old =
        muscles_ ? legendre_.momentum(dt, eta[j], M_[j]) : legendre_.momentum(dt, eta[j]);
    if (!solve_velocity(j, dt, mu[j], mu_old, eta[j])) return false;
  }
  return true;
}

bool VariationalActuators::enforce_lengths(double t1, double dt, std::span<const SE3> G,
                                           std::span<const Vector6> xi, std::span<Vector6> mu,
                                           std::span<Vector6> eta, double& power) {
  if (lengths_.empty()) return true;
  const auto ml = static_cast<Eigen::Index>(lengths_.size());
  // Impulse directions per unit force (3.40)-(3.41).
  for (Eigen::Index l = 0; l < ml; ++l) {
    const auto& a = P_.actuators()[which_[lengths_[l]]];
    Vector6* b = &b_[l * n_];
    std::fill(b, b + n_, Vector6::Zero());
    for (int j = 0; j + 1 < n_; ++j) {
      const double s_mid = (j + 0.5) * ds_;
      if (!a.path.active(s_mid)) continue;
      const Vector6 d = se3::dexp_inv_transpose_apply(ds_ * xi[j], a.path.unit_wrench(s_mid, xi[j]));
      b[j] += d;
      b[j + 1] -= G[j].coAd_apply(d);
    }
    if (a.enters_from_outside) {
      const int node = static_cast<int>(std::lround(a.path.s0() / ds_));
      if (node > 0 && node < n_)
        b[node] -= a.path.unit_wrench(a.path.s0(), xi[node == n_ - 1 ? node - 1 : node]);
    }
    if (P_.tip_clamped()) b[n_ - 1].setZero();  // the clamp takes the tip's share
  }
  std::copy(mu.begin(), mu.end(), mu_free_.begin());
  std::copy(eta.begin(), eta.end(), eta_free_.begin());
  const double L = P_.length();
  const double t_next = t1 + dt;
  const double force_scale = std::min(P_.model().K_diag()[0], P_.model().K_diag()[1]) / (L * L);
  auto evaluate = [&](Eigen::VectorXd& r) {
    if (!apply_forces(dt, mu, eta)) return false;
    next_lengths(dt, G, eta);
    for (Eigen::Index l = 0; l < ml; ++l) {
      const int e = lengths_[l];
      r[l] = (lengths_next_[l] - P_.actuators()[which_[e]].target_length(t_next, paths_.rest()[e])) / L;
    }
    return r.allFinite();
  };
  trial_ = Fl_;  // the last step's forces
  bool jacobian = false;
  for (int it = 0; it <= legendre_.max_iterations; ++it) {
    if (!evaluate(residual_)) break;
    if (residual_.lpNorm<Eigen::Infinity>() <= kLengthTol) {
      Fl_ = trial_;
      for (Eigen::Index l = 0; l < ml; ++l) {
        F_[which_[lengths_[l]]] = Fl_[l];
        unknowns_[lengths_[l]] = Fl_[l];
      }
      power = (0.5 * (Fl_prev_ + Fl_)).dot(power_);
      return true;
    }
    if (!jacobian) {  // finite differences, one column per actuator; the state is restored
      const Eigen::VectorXd F0 = trial_, r0 = residual_;
      Eigen::VectorXd r1(ml);
      for (Eigen::Index l = 0; l < ml; ++l) {
        const double h = kFdStep * std::max(std::abs(F0[l]), force_scale);
        trial_ = F0;
        trial_[l] += h;
        if (!evaluate(r1)) {
          failure_ = "has a non-finite Jacobian";
          return false;
        }
        J_.col(l) = (r1 - r0) / h;
      }
      trial_ = F0;
      residual_ = r0;
      jacobian = true;
    }
    trial_ -= J_.partialPivLu().solve(residual_);
  }
  failure_ = rodlab::format(
      "did not reach the prescribed path lengths (max |length - target| / L = {:g})",
      residual_.lpNorm<Eigen::Infinity>());
  return false;
}

std::vector<ActuatorReading> VariationalActuators::readings(std::span<const Vector6> xi) const {
  std::vector<ActuatorReading> out(which_.size());
  for (std::size_t e = 0; e < which_.size(); ++e)
    out[e] = {which_[e], paths_.length(static_cast<int>(e), xi), F_[which_[e]]};
  return out;
}

}  // namespace rodlab::solvers::dynamics
