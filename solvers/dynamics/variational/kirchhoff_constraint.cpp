#include "kirchhoff_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "rodlab/check.hpp"
#include "rodlab/lie/small_angle.hpp"


namespace rodlab::solvers::dynamics {

using lie::Matrix6;
using lie::SE3;
using lie::Vector3;
using lie::Vector6;
namespace se3 = lie::se3;

/// |nu - nu*| that the constraint solve reaches (relative to max(1, |nu*|)).
constexpr double kConstraintTol = 1e-12;

KirchhoffConstraint::KirchhoffConstraint(int nodes, double ds, std::vector<Vector3> nu_star,
                                         DiscreteLegendre legendre, int max_iterations)
    : n_(nodes),
      ds_(ds),
      nu_star_(std::move(nu_star)),
      nu_scale_(1.0),
      legendre_(legendre),
      max_iterations_(max_iterations),
      mu_free_(nodes, Vector6::Zero()),
      f_(nodes - 1, Vector3::Zero()),
      c_(nodes - 1, Vector3::Zero()),
      B_(nodes - 1, Matrix63::Zero()),
      C_(nodes - 1, Matrix63::Zero()) {
  A_.resize(nodes - 1);
  RODLAB_THROW_UNLESS(static_cast<int>(nu_star_.size()) == nodes - 1,
                      "KirchhoffConstraint: {} segments' nu*, expected {}", nu_star_.size(),
                      nodes - 1);
  for (const Vector3& nu : nu_star_) nu_scale_ = std::max(nu_scale_, nu.norm());
}

bool KirchhoffConstraint::enforce(double dt, std::span<const SE3> G, std::span<const Vector6> xi,
                                  std::span<Vector6> mu, std::span<Vector6> eta) {
  const int m = n_ - 1;  // segments
  // Chord matrix at the configuration of this step.
  for (int k = 0; k < m; ++k) {
    B_[k] = se3::dexp_inv(ds_ * xi[k]).transpose().rightCols<3>();
    C_[k] = G[k].Ad().transpose() * B_[k];
  }
  const Vector6& M_inv = legendre_.M_inv;
  for (int k = 0; k < m; ++k) {
    const Eigen::Matrix<double, 3, 6> D =
        (dt / ds_) * se3::dexp_inv(-ds_ * xi[k]).bottomRows<3>();
    const Matrix6 H = G[k].inverse().Ad();
    const Vector6 Q_next = (dt / weight(k + 1)) * M_inv;
    A_.Di[k] = -D * (Q_next.asDiagonal() * C_[k]);
    A_.Up[k].setZero();
    A_.Lo[k].setZero();
    if (k + 1 < m) A_.Up[k] = D * (Q_next.asDiagonal() * B_[k + 1]);
    if (k >= 1) {
      const Vector6 Q = (dt / weight(k)) * M_inv;
      A_.Di[k] -= D * H * (Q.asDiagonal() * B_[k]);
      A_.Lo[k] = D * H * (Q.asDiagonal() * C_[k - 1]);
    }
  }
  if (!A_.factor()) {
    failure_ = "has a singular matrix";
    return false;
  }
  for (auto& f : f_) f.setZero();
  std::copy(mu.begin(), mu.end(), mu_free_.begin());
  double worst = 0.0;
  for (int it = 0; it <= max_iterations_; ++it) {
    // residuals of the velocities at the current forces
    worst = 0.0;
    SE3 E = SE3::identity();
    for (int k = 0; k < m; ++k) {
      const SE3 E_next = lie::small_angle::exp(dt * eta[k + 1]);
      const Vector6 x = (E.inverse() * G[k] * E_next).log();
      c_[k] = x.tail<3>() / ds_ - nu_star_[k];
      worst = std::max(worst, c_[k].lpNorm<Eigen::Infinity>());
      E = E_next;
    }
    if (worst <= kConstraintTol * nu_scale_) return true;
    if (it == max_iterations_ || !std::isfinite(worst)) break;
    for (auto& c : c_) c = -c;
    A_.solve(c_);
    for (int k = 0; k < m; ++k) f_[k] += c_[k];
    // the momenta with the constraint impulses, and their velocities (3.42)
    for (int j = 1; j < n_; ++j) {
      Vector6 impulse = -C_[j - 1] * f_[j - 1];
      if (j < m) impulse += B_[j] * f_[j];
      mu[j] = mu_free_[j] + (dt / weight(j)) * impulse;
      // eta[j] solves (3.42) for the momentum it had: legendre_.momentum(dt, eta[j])
      if (!legendre_.solve(dt, mu[j], legendre_.momentum(dt, eta[j]), eta[j])) {
        failure_ = rodlab::format("diverged in the velocity of node {}", j);
        return false;
      }
    }
  }
  failure_ = rodlab::format("did not converge (max |nu - nu*| = {:g})", worst);
  return false;
}

}  // namespace rodlab::solvers::dynamics
