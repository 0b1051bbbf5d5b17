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
// `load_factor` scales every load and moves a clamped tip's target from the reference tip pose
// through the tips of constant-twist rods (twist interpolated from xi* to the one reaching the
// target); the continuation of the solvers walks it from 0 to 1.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rodlab/lie/se3.hpp"
#include "rodlab/loads/gravity.hpp"
#include "rodlab/loads/point_wrench.hpp"
#include "rodlab/rod/rod_model.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/statics/actuator_term.hpp"

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
  /// Adds an actuator (at most kMaxActuators); computes its rest length.
  void add_actuator(ActuatorTerm term);
  /// Sets actuator k's prescribed input (ActuatorTerm::input: tension, displacement, pressure,
  /// volume or muscle q, as in the scene), and the target length that a displacement or a volume
  /// prescribes, as add_actuator does. For inverse statics (control/inverse_statics.hpp).
  void set_actuator_input(int k, double value);

  // --- queries -------------------------------------------------------------------------
  const rod::RodModel& model() const { return model_; }
  const SE3& base() const { return base_; }
  const std::string& name() const { return name_; }
  double length() const { return model_.length(); }
  double load_factor() const { return load_factor_; }
  bool tip_clamped() const { return tip_target_.has_value(); }
  /// The clamped tip's target at the current load factor.
  SE3 tip_target() const;
  /// Reference (unloaded) pose of the tip, base * exp(L xi*) (over the spans: base * g*(L)).
  SE3 reference_tip() const { return base_ * model_.rest_pose(length()); }

  // --- actuators ------------------------------------------------------------------------
  static constexpr int kMaxActuators = 16;
  using Mask = std::uint32_t;  ///< bit k: actuator k is active on the current stretch of s
  const std::vector<ActuatorTerm>& actuators() const { return actuators_; }
  bool has_actuators() const { return !actuators_.empty(); }
  /// Actuators active on a stretch of s that contains s_mid and no breakpoint.
  Mask active_mask(double s_mid) const;
  /// Actuator span ends, routing knots and rest-strain span begins inside (0, L), sorted: where
  /// the integrators split steps (and evaluate xi*(s) strictly inside each piece).
  const std::vector<double>& breakpoints() const { return breakpoints_; }
  /// Axial force F of actuator k at the current load factor and unknowns.
  double axial_force(int k) const;
  /// Extra unknowns of the BVP (one per actuator with has_unknown()), scaled to O(1):
  /// forces / (E I / L^2), muscle lengths / L.
  int extra_unknowns() const { return extra_count_; }
  void set_extra_unknowns(std::span<const double> z);
  /// The unknowns' initial guess (zero force, Delta = Delta*), scaled.
  std::vector<double> extra_initial_guess() const;
  /// Residual of the extra conditions from the integrated path lengths (by actuator index),
  /// made dimensionless by L.
  void extra_residuals(std::span<const double> lengths, std::span<double> out) const;
  /// Whether shooting must integrate path lengths (some actuator has an unknown).
  bool tracks_lengths() const { return extra_count_ > 0; }
  /// Jump of Lambda when crossing a breakpoint b forward with strain xi_left: cables entering
  /// there are pulled from outside, so the strain is continuous and Lambda gains F c(xi).
  Vector6 entry_jump(double b, const Vector6& xi_left) const;

  /// Whether a cable enters the rod at the breakpoint b (entry_jump is then not zero in general).
  bool has_entry(double b) const;
  /// d entry_jump(b, xi) / d xi: sum over the cables entering at b of F_k dc_k/dxi.
  lie::Matrix6 entry_jump_jacobian(double b, const Vector6& xi_left) const;

  /// Strain from internal wrench with the actuators in `mask` active:
  /// K (xi - xi*) + sum_k [F_k c_k(xi) + K_mus,k (xi - xi*)] = Lambda, solved by Newton
  /// (Kirchhoff: omega only, nu = nu*). Without actuators it is the closed form below.
  Vector6 strain(const Vector6& Lambda, double s, Mask mask) const;
  /// d xi / d Lambda of strain(Lambda, s, mask) at its solution xi (implicit function theorem):
  /// the inverse of the law's Jacobian J = K + sum_k [F_k dc_k/dxi + K_mus,k]; for Kirchhoff rods
  /// (nu = nu* held) the inverse of J's moment block, zero on the force columns and nu rows.
  lie::Matrix6 strain_jacobian(const Vector6& xi, double s, Mask mask) const;
  /// The rod's own internal wrench (without the actuators') at s.
  Vector6 rod_wrench(const Vector6& Lambda, const Vector6& xi, double s, Mask mask) const;

  /// Strain from internal wrench without actuators at s: xi = xi*(s) + K^-1 Lambda (Kirchhoff:
  /// nu = nu*(s)). At a rest-strain span begin s belongs to the span it begins; a scheme that
  /// needs the other side passes an s inside it.
  Vector6 strain(const Vector6& Lambda, double s) const {
    const Vector6& xs = model_.xi_star(s);
    Vector6 xi = xs + model_.K_inv_diag().cwiseProduct(Lambda);
    if (model_.is_kirchhoff()) xi.tail<3>() = xs.tail<3>();
    return xi;
  }
  /// d xi / d Lambda of strain() above, a diagonal: K^-1 (Kirchhoff: zero on nu).
  Vector6 strain_slope() const {
    Vector6 slope = model_.K_inv_diag();
    if (model_.is_kirchhoff()) slope.tail<3>().setZero();
    return slope;
  }
  /// Internal wrench of the rod from strain at s: K (xi - xi*(s)).
  Vector6 rod_wrench(const Vector6& xi, double s) const {
    return model_.K_diag().cwiseProduct(xi - model_.xi_star(s));
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
  /// K plus the transported stiffness of the muscles in `mask` at s: the law's linear part.
  lie::Matrix6 law_stiffness(double s, Mask mask) const;
  /// A cable that enters the rod at b > 0 (pulled from outside there).
  static bool enters_at(const ActuatorTerm& a, double b) {
    return a.enters_from_outside() && a.path.s0() == b && b > 0.0;
  }

  rod::RodModel model_;
  SE3 base_;
  std::string name_;
  std::optional<SE3> tip_target_;
  loads::PointWrench tip_wrench_;
  std::optional<loads::Gravity> gravity_;
  std::optional<loads::DistributedWrench> distributed_;
  double load_factor_ = 1.0;
  Vector6 wrench_scale_;
  std::vector<ActuatorTerm> actuators_;
  std::vector<double> breakpoints_;
  std::vector<double> unknown_value_;  ///< per actuator: its unknown (force or Delta), unscaled
  int extra_count_ = 0;
};

}  // namespace rodlab::solvers::statics
