#pragma once
// The dynamics of one scene (thesis chapter 3, docs/dynamics.md) in the form every dynamics
// scheme uses. Balance and compatibility, body frame, per unit reference length:
//
//   d/dt (M eta) - ad_eta^T M eta = Lambda' - ad_xi^T Lambda + W_bar      (3.8), (3.46)
//   xi_dot = eta' + ad_xi eta                                              (3.47)
//   Lambda = K (xi - xi*) + V xi_dot + sum_k F_k(t) c_k(xi)                (3.10), docs/dynamics.md
//
// Lambda is the total internal wrench of rod and actuators (as in the statics): Kelvin-Voigt
// viscosity is part of the internal wrench, not a distributed load as (3.10) is written, and the
// tendon-like actuators (cables, fluidic chambers) are internal forces F_k c_k(xi). W_bar holds the
// external distributed loads: gravity with buoyancy (2.36), drag (3.11)-(3.12), and a uniform
// distributed wrench. The base is fixed (g(0) = base, eta(0) = 0); the tip is free with a point
// wrench that may follow a schedule. The problem is immutable: schedules are evaluated at the
// time asked for.
#include <optional>
#include <string>
#include <vector>

#include "rodlab/lie/se3.hpp"
#include "rodlab/loads/gravity.hpp"
#include "rodlab/loads/tendon.hpp"
#include "rodlab/rod/rod_model.hpp"
#include "rodlab/scene/scene.hpp"

namespace rodlab::solvers::dynamics {

using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;

/// A tendon-like actuator driven by a scheduled input: F(t) = force_per_input * input(t)
/// (cable: tension, 1; fluidic chamber: pressure, -A_c; docs/statics.md).
struct TendonActuator {
  loads::TendonPath path;
  scene::ScalarSchedule input;
  double force_per_input = 1.0;
  bool enters_from_outside = false;  ///< a cable pulled from outside where its span begins
  double force(double t) const { return force_per_input * input.at(t); }
};

class DynamicProblem {
 public:
  /// Throws std::invalid_argument for scene features the dynamics do not support yet.
  static DynamicProblem from_scene(const scene::Scene& scene);

  const rod::RodModel& model() const { return model_; }
  const SE3& base() const { return base_; }
  const std::string& name() const { return name_; }
  double length() const { return model_.length(); }
  bool is_kirchhoff() const { return model_.is_kirchhoff(); }

  // --- external loads, body frame ------------------------------------------------------
  /// Gravity with buoyancy (2.36) per unit length on a section with rotation R.
  Vector6 gravity_load(const SO3& R) const {
    return gravity_ ? gravity_->body_wrench(R) : Vector6::Zero();
  }
  /// Weight per unit length in the world frame (zero without gravity), for the potential.
  Vector3 weight_per_length() const {
    return gravity_ ? gravity_->weight_per_length() : Vector3::Zero();
  }
  /// Drag (3.11)-(3.12): -rho_f (D_lam + |v| D_turb) eta, v the section's linear velocity.
  Vector6 drag_load(const Vector6& eta) const;
  bool has_drag() const { return drag_.has_value(); }
  /// The uniform distributed wrench of the scene at time t (loads.distributed).
  Vector6 applied_load(const SO3& R, double t) const;
  /// The free tip's wrench at time t on a tip with rotation R (world: a dead load).
  Vector6 tip_load(const SO3& R, double t) const;

  // --- internal wrench ---------------------------------------------------------------------
  const std::vector<TendonActuator>& actuators() const { return actuators_; }
  bool has_actuators() const { return !actuators_.empty(); }
  /// Sum of the actuators' internal wrenches F_k(t) c_k(xi) active at s (span ends: half-open).
  Vector6 actuator_wrench(const Vector6& xi, double s, double t) const;
  /// Their power into the rod per unit length, -sum_k F_k c_k(xi)^T xi_dot (a pulled cable
  /// shortens its path and does positive work on the rod).
  double actuator_power(const Vector6& xi, const Vector6& xi_dot, double s, double t) const;
  /// Lambda = K (xi - xi*) + V xi_dot + sum_k F_k c_k(xi)  (3.10).
  Vector6 internal_wrench(const Vector6& xi, const Vector6& xi_dot, double s, double t) const {
    Vector6 W = model_.K_diag().cwiseProduct(xi - model_.xi_star()) +
                model_.V_diag().cwiseProduct(xi_dot);
    if (!actuators_.empty()) W += actuator_wrench(xi, s, t);
    return W;
  }
  /// Solves Kt (xi - xi_ref) + sum_k F_k(t) c_k(xi) = Lambda for the strain, Kt diagonal
  /// (an implicit step's K + c V); Kirchhoff rods solve for omega and keep nu = nu_ref.
  Vector6 solve_strain(const Vector6& Kt, const Vector6& xi_ref, const Vector6& Lambda, double s,
                       double t) const {
    if (actuators_.empty()) {
      Vector6 xi = xi_ref + Lambda.cwiseQuotient(Kt);
      if (is_kirchhoff()) xi.tail<3>() = xi_ref.tail<3>();
      return xi;
    }
    return solve_strain_with_actuators(Kt, xi_ref, Lambda, s, t);
  }
  /// Point wrench on the rod where cables enter from outside at s0 > 0: the rod's internal
  /// wrench is continuous there, so the node that carries the jump of the total internal wrench
  /// gets it back as an external load, -F c(xi) (compare StaticProblem::entry_jump).
  struct EntryNode {
    double s;  ///< where the cable enters
    int node;  ///< the node nearest to it on a grid of N nodes (inside (0, N - 1])
  };
  std::vector<EntryNode> entry_nodes(int nodes) const;
  Vector6 entry_load(double s_entry, const Vector6& xi, double t) const;

 private:
  Vector6 solve_strain_with_actuators(const Vector6& Kt, const Vector6& xi_ref,
                                      const Vector6& Lambda, double s, double t) const;
  DynamicProblem(rod::RodModel model, SE3 base) : model_(std::move(model)), base_(base) {}

  rod::RodModel model_;
  SE3 base_;
  std::string name_;
  std::optional<loads::Gravity> gravity_;
  std::optional<scene::Drag> drag_;
  std::optional<scene::DistributedWrench> distributed_;
  scene::Wrench tip_;
  std::vector<TendonActuator> actuators_;
};

}  // namespace rodlab::solvers::dynamics
