#pragma once
// The statics boundary-value problem (2.33)-(2.34) of one scene at one time, in the form every
// statics scheme solves (docs/statics.md):
//
//   g'      = g hat(xi)                                   (2.33)
//   Lambda' = ad_xi^T Lambda - W_bar(g)                   (2.34) with Lambda = K (xi - xi*)
//   g(0) = base;  free tip: Lambda(L) = W_tip;  clamped tip: g(L) = g_target.
//
// Lambda is the internal wrench (body frame) that the rod beyond s exerts across the section at
// s. Kirchhoff rods hold nu = nu* (3.45): only the moment part of Lambda sets the strain and its
// force part is the constraint force, still balanced by (2.34), so the tip keeps all six
// conditions (the thesis's xi-state form drops the internal force, which would leave a Kirchhoff
// cantilever unbent by gravity).
//
// `load_factor` scales every load and moves a clamped tip's target along the geodesic from the
// reference tip pose; the continuation of the solvers walks it from 0 to 1.
#include <optional>
#include <string>

#include "rodlab/lie/se3.hpp"
#include "rodlab/loads/gravity.hpp"
#include "rodlab/loads/point_wrench.hpp"
#include "rodlab/rod/rod_model.hpp"
#include "rodlab/scene/scene.hpp"

namespace rodlab::solvers::statics {

using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;

class StaticProblem {
 public:
  StaticProblem(rod::RodModel model, SE3 base);

  /// Builds the problem of a scene, evaluating schedules at time t. Throws
  /// std::invalid_argument for scene features the statics do not support yet.
  static StaticProblem from_scene(const scene::Scene& scene, double t = 0.0);

  // --- set-up --------------------------------------------------------------------------
  void set_tip_wrench(const loads::PointWrench& w) { tip_wrench_ = w; }
  void set_tip_clamped(const SE3& target) { tip_target_ = target; }
  void set_gravity(const loads::Gravity& g) { gravity_ = g; }
  void set_distributed(const loads::DistributedWrench& w) { distributed_ = w; }
  void set_load_factor(double f) { load_factor_ = f; }
  void set_name(std::string name) { name_ = std::move(name); }

  // --- queries -------------------------------------------------------------------------
  const rod::RodModel& model() const { return model_; }
  const SE3& base() const { return base_; }
  const std::string& name() const { return name_; }
  double length() const { return model_.length(); }
  double load_factor() const { return load_factor_; }
  bool tip_clamped() const { return tip_target_.has_value(); }
  /// The clamped tip's target at the current load factor.
  SE3 tip_target() const;
  /// Reference (unloaded) pose of the tip, base * exp(L xi*).
  SE3 reference_tip() const { return base_ * SE3::exp(length() * model_.xi_star()); }

  /// Strain from internal wrench: xi = xi* + K^-1 Lambda (Kirchhoff: nu = nu*).
  Vector6 strain(const Vector6& Lambda) const {
    Vector6 xi = model_.xi_star() + model_.K_inv_diag().cwiseProduct(Lambda);
    if (model_.is_kirchhoff()) xi.tail<3>() = model_.xi_star().tail<3>();
    return xi;
  }
  /// Internal wrench of the rod from strain: K (xi - xi*).
  Vector6 rod_wrench(const Vector6& xi) const {
    return model_.K_diag().cwiseProduct(xi - model_.xi_star());
  }

  /// External distributed wrench in the body frame at a section with rotation R.
  Vector6 distributed_load(const SO3& R) const {
    Vector6 w = Vector6::Zero();
    if (gravity_) w += gravity_->body_wrench(R, load_factor_);
    if (distributed_) w += distributed_->body_wrench(R, load_factor_);
    return w;
  }

  /// The free tip's applied wrench in the body frame of a tip with rotation R.
  Vector6 tip_load(const SO3& R) const { return tip_wrench_.body_wrench(R, load_factor_); }

  /// (2.34): Lambda' = ad_xi^T Lambda - W_bar.
  Vector6 wrench_derivative(const SO3& R, const Vector6& xi, const Vector6& Lambda) const {
    return lie::se3::coad_apply(xi, Lambda) - distributed_load(R);
  }

  /// Tip conditions, made dimensionless: free tip (Lambda(L) - W_tip) / wrench scale;
  /// clamped tip [log(R_target^T R(L)); (p(L) - p_target) / L].
  Vector6 tip_residual(const SE3& g_tip, const Vector6& Lambda_tip) const;

  /// Scales that make wrenches dimensionless: E I / L for moments, E I / L^2 for forces.
  const Vector6& wrench_scale() const { return wrench_scale_; }

 private:
  rod::RodModel model_;
  SE3 base_;
  std::string name_;
  std::optional<SE3> tip_target_;
  loads::PointWrench tip_wrench_;
  std::optional<loads::Gravity> gravity_;
  std::optional<loads::DistributedWrench> distributed_;
  double load_factor_ = 1.0;
  Vector6 wrench_scale_;
};

}  // namespace rodlab::solvers::statics
