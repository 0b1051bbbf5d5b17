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
// wrench that may follow a schedule, or clamped (g(L) = the clamp's pose, eta(L) = 0; the clamp's
// reaction replaces Lambda(L) = W_tip and does no work; docs/dynamics.md "Clamped tips"). The
// problem is immutable: schedules are evaluated at the time asked for.
//
// Artificial muscles are embedded rods (thesis 3.2.3): their stiffness and viscosity join
// Lambda, their inertia makes M full where they sit off the centreline (M + Ad^T M_a Ad, (3.20)),
// their weight acts at the offset, and their force follows a law of their current length Delta
// (2.54)-(2.67). Muscles and length-controlled actuators (cable displacement, chamber volume)
// have forces that the schemes determine: their unknowns (docs/dynamics.md "Muscles and length
// control").
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rodlab/lie/se3.hpp"
#include "rodlab/loads/fluidic_chamber.hpp"
#include "rodlab/loads/gravity.hpp"
#include "rodlab/loads/muscle_law.hpp"
#include "rodlab/loads/tendon.hpp"
#include "rodlab/rod/rod_model.hpp"
#include "rodlab/scene/scene.hpp"

namespace rodlab::solvers::dynamics {

using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;

/// How an actuator's axial force F is set (docs/dynamics.md "Muscles and length control").
enum class ActuatorDrive {
  force,   ///< given: F(t) = force_per_input * input(t) (cable tension: 1; chamber pressure: -A_c)
  length,  ///< its path length is prescribed (cable displacement, chamber volume); F is unknown
  muscle,  ///< F = law(q(t), Delta, Delta*), Delta the muscle's current path length (2.66)
};

/// The embedded rod of an artificial muscle (thesis 3.2.3): its own stiffness, viscosity and
/// inertia diagonals about its own axis (from its section and material, as a rod's (2.28),
/// (3.5), (3.10)), transported to the centreline through T = [I r; 0 1] (3.13), (3.19)-(3.20).
struct EmbeddedRod {
  Vector6 K, V, M;               ///< diagonals about the muscle's axis
  double mass_per_length = 0.0;  ///< rho_a A_a
};

/// A tendon-like actuator along a path (cable, fluidic chamber, the active force of a muscle).
struct TendonActuator {
  TendonActuator(loads::TendonPath path_, scene::ScalarSchedule input_)
      : path(std::move(path_)), input(std::move(input_)) {}

  loads::TendonPath path;
  scene::ScalarSchedule input;  ///< tension, pressure, displacement, volume or muscle input q
  double force_per_input = 1.0;  ///< drive force: cable 1, chamber -A_c
  bool enters_from_outside = false;  ///< a cable pulled from outside where its span begins
  ActuatorDrive drive = ActuatorDrive::force;
  double chamber_area = 0.0;  ///< fluidic: A_c (volume control: the length is V / A_c)
  bool is_cable = false;      ///< a cable (length control: a displacement; else a volume)
  std::shared_ptr<const loads::MuscleLaw> law;  ///< muscle
  std::optional<EmbeddedRod> embedded;          ///< muscle
  /// A controller's input held over the current control step (solvers/control/plant.hpp),
  /// which replaces the schedule; NaN: the schedule drives.
  double held = std::numeric_limits<double>::quiet_NaN();
  /// The input at t: the held one, else the schedule's.
  double input_at(double t) const { return std::isnan(held) ? input.at(t) : held; }
  /// The drive force at t (ActuatorDrive::force only).
  double force(double t) const { return force_per_input * input_at(t); }
  /// Length control: the prescribed path length at t for a path of length `rest` in the
  /// reference configuration: rest - displacement(t) for a cable (2.47), volume(t) / A_c for a
  /// chamber (the chamber's section is rigid, so V = A_c x its length; docs/statics.md).
  double target_length(double t, double rest) const {
    return is_cable ? rest - input_at(t) : loads::chamber_length(input_at(t), chamber_area);
  }
};

class DynamicProblem {
 public:
  /// Throws std::invalid_argument for scene features the dynamics do not support yet.
  static DynamicProblem from_scene(const scene::Scene& scene);

  const rod::RodModel& model() const { return model_; }
  /// This problem with another model of the same rod (the corrected grid's, corrected_grid.hpp).
  DynamicProblem with_model(rod::RodModel model) const {
    DynamicProblem p = *this;
    p.model_ = std::move(model);
    return p;
  }
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
  /// The free tip's wrench at time t on a tip with rotation R (world: a dead load); zero for a
  /// clamped tip (the clamp's reaction is not a load).
  Vector6 tip_load(const SO3& R, double t) const;

  // --- clamped tip ------------------------------------------------------------------------
  /// The tip is held by a clamp at tip_target() (world pose): g(L) = tip_target(), eta(L) = 0.
  bool tip_clamped() const { return tip_target_.has_value(); }
  /// The clamp's pose (identity for a free tip).
  SE3 tip_target() const { return tip_target_ ? *tip_target_ : SE3::identity(); }
  /// The rest shape's tip pose, base exp(L xi*).
  SE3 reference_tip() const { return base_ * model_.rest_pose(length()); }
  /// Scaled mismatch of a tip pose g against the clamp, [log(g^-1 g_clamp) rotation;
  /// translation / L]: dimensionless, O(1) for a bend of about a radian.
  Vector6 clamp_mismatch(const SE3& g) const {
    Vector6 r = (g.inverse() * tip_target()).log();
    r.tail<3>() /= length();
    return r;
  }

  // --- actuators -----------------------------------------------------------------------
  static constexpr int kMaxActuators = 16;
  /// The axial forces of one evaluation, by actuator index [N].
  using Forces = std::array<double, kMaxActuators>;
  const std::vector<TendonActuator>& actuators() const { return actuators_; }
  /// Holds actuator k's input at `value` in place of its schedule (control: the input of the
  /// coming control step); NaN gives it back to the schedule.
  void hold_input(int k, double value) { actuators_.at(static_cast<std::size_t>(k)).held = value; }
  bool has_actuators() const { return !actuators_.empty(); }
  bool has_muscles() const { return muscles_; }
  bool has_length_control() const { return length_control_; }
  /// Actuators whose force is not given, in actuator order: a muscle (its unknown is its length
  /// Delta [m]) or a length-controlled actuator (its unknown is the force F [N]). The schemes
  /// carry one extra unknown for each (docs/dynamics.md "Muscles and length control").
  const std::vector<int>& unknown_actuators() const { return unknown_actuators_; }
  int unknown_count() const { return static_cast<int>(unknown_actuators_.size()); }
  /// The forces at t: drive forces from their schedules; for unknown e (actuator
  /// unknown_actuators()[e]) a muscle's law at the length unknowns[e] and the rest length
  /// rest[e], a length-controlled actuator's unknowns[e] itself. The pointers may be null only
  /// when unknown_count() == 0 (else std::logic_error: a scheme must supply its unknowns).
  Forces forces(double t, const double* unknowns = nullptr, const double* rest = nullptr) const;
  /// The overlap of [a, b] with actuator k's span: the weight of a cell or segment in the
  /// quadrature of its path length, and the fraction (over b - a) of a cell that carries a
  /// muscle's mass.
  double span_overlap(int k, double a, double b) const;

  // --- internal wrench ---------------------------------------------------------------------
  /// Sum of the actuators' internal wrenches F_k c_k(xi) active at s (span ends: half-open).
  Vector6 actuator_wrench(const Vector6& xi, double s, const Forces& F) const;
  Vector6 actuator_wrench(const Vector6& xi, double s, double t) const {
    return actuator_wrench(xi, s, forces(t));
  }
  /// Their power into the rod per unit length, -sum_k F_k c_k(xi)^T xi_dot (a pulled cable
  /// shortens its path and does positive work on the rod); c_k^T xi_dot is the rate of the
  /// path's length |u_k|.
  double actuator_power(const Vector6& xi, const Vector6& xi_dot, double s, const Forces& F) const;
  double actuator_power(const Vector6& xi, const Vector6& xi_dot, double s, double t) const {
    return actuator_power(xi, xi_dot, s, forces(t));
  }
  /// sum_k F_k (|u_k(xi_new)| - |u_k(xi_old)|) over the actuators active at s: the change of
  /// their path lengths per unit length over a step, weighted by their forces (the work they
  /// did on the rod is its negative; `variational`'s ledger).
  double actuator_length_change(const Vector6& xi_old, const Vector6& xi_new, double s,
                                const Forces& F) const;
  double actuator_length_change(const Vector6& xi_old, const Vector6& xi_new, double s,
                                double t) const {
    return actuator_length_change(xi_old, xi_new, s, forces(t));
  }
  /// The embedded muscles' elastic and viscous wrench about the centroid at s (zero without
  /// muscles): sum_a Ad^T (K_a Ad (xi - xi*) + V_a Ad xi_dot), Ad = Ad_{T_a^-1} (3.19).
  Vector6 embedded_wrench(const Vector6& xi, const Vector6& xi_dot, double s) const;
  /// Lambda = K (xi - xi*) + V xi_dot + [embedded muscles] + sum_k F_k c_k(xi)  (3.10).
  Vector6 internal_wrench(const Vector6& xi, const Vector6& xi_dot, double s,
                          const Forces& F) const {
    Vector6 W = rod_wrench(xi, xi_dot, s);
    if (muscles_) W += embedded_wrench(xi, xi_dot, s);
    if (!actuators_.empty()) W += actuator_wrench(xi, s, F);
    return W;
  }
  /// The same with the drive forces at t (scenes without muscles or length control).
  Vector6 internal_wrench(const Vector6& xi, const Vector6& xi_dot, double s, double t) const {
    Vector6 W = rod_wrench(xi, xi_dot, s);
    if (!actuators_.empty()) W += actuator_wrench(xi, s, t);
    return W;
  }
  /// The rod's own wrench K (xi - xi*(s)) + V xi_dot (s: where the rest strain is read; a
  /// segment's midpoint).
  Vector6 rod_wrench(const Vector6& xi, const Vector6& xi_dot, double s) const {
    return model_.K_diag().cwiseProduct(xi - model_.xi_star(s)) +
           model_.V_diag().cwiseProduct(xi_dot);
  }

  /// The muscles' strain energy per unit length at s, 1/2 (xi - xi*)^T K_mus (xi - xi*), and
  /// their viscous power xi_dot^T V_mus xi_dot.
  double embedded_strain_density(const Vector6& xi, double s) const {
    return 0.5 * (xi - model_.xi_star(s)).dot(embedded_wrench(xi, Vector6::Zero(), s));
  }
  double embedded_dissipation(const Vector6& xi_dot, double s) const {
    return xi_dot.dot(embedded_wrench(model_.xi_star(s), xi_dot, s));
  }
  /// The embedded muscles' stiffness and viscosity about the centroid at s, sum_a Ad^T K_a Ad
  /// and sum_a Ad^T V_a Ad (K_mus of the statics, (2.64)); zero without muscles.
  lie::Matrix6 embedded_stiffness(double s) const;
  lie::Matrix6 embedded_viscosity(double s) const;
  /// Solves Kt (xi - xi_ref) + sum_k F_k(t) c_k(xi) = Lambda for the strain, Kt diagonal
  /// (an implicit step's K + c V); Kirchhoff rods solve for omega and keep nu = nu_ref.
  Vector6 solve_strain(const Vector6& Kt, const Vector6& xi_ref, const Vector6& Lambda, double s,
                       double t) const {
    if (actuators_.empty()) return solve_elastic_strain(Kt.cwiseInverse(), xi_ref, Lambda);
    return solve_strain(lie::Matrix6(Kt.asDiagonal()), xi_ref, Lambda, s, forces(t));
  }
  /// The same without actuators, from Kt^-1: a step's many solves share one Kt, and a
  /// division per component was a fifth of the staggered march's strain solve (perf).
  Vector6 solve_elastic_strain(const Vector6& Kt_inv, const Vector6& xi_ref,
                               const Vector6& Lambda) const {
    Vector6 xi = xi_ref + Lambda.cwiseProduct(Kt_inv);
    if (is_kirchhoff()) xi.tail<3>() = xi_ref.tail<3>();
    return xi;
  }
  /// The same with a full Kt (embedded muscles) and the forces F; Newton starts from `guess`
  /// when given (tendon_law.hpp).
  Vector6 solve_strain(const lie::Matrix6& Kt, const Vector6& xi_ref, const Vector6& Lambda,
                       double s, const Forces& F, const Vector6* guess = nullptr) const;
  /// Point wrench on the rod where cables enter from outside at s0 > 0: the rod's internal
  /// wrench is continuous there, so the node that carries the jump of the total internal wrench
  /// gets it back as an external load, -F c(xi) (compare StaticProblem::entry_jump).
  struct EntryNode {
    double s;  ///< where the cable enters
    int node;  ///< the node nearest to it on a grid of N nodes (inside (0, N - 1])
  };
  std::vector<EntryNode> entry_nodes(int nodes) const;
  Vector6 entry_load(double s_entry, const Vector6& xi, const Forces& F) const;
  Vector6 entry_load(double s_entry, const Vector6& xi, double t) const {
    return entry_load(s_entry, xi, forces(t));
  }

  // --- embedded inertia and weight (muscles, (3.16)-(3.20)) -----------------------------
  /// The mass matrix per unit length of the cell [a, b] of a node at s: M plus every muscle's
  /// Ad^T M_a Ad (offset at s), weighted by the fraction of the cell it covers. Full (not
  /// diagonal) where a muscle sits off the centreline: its linear and angular velocities
  /// couple, eta_a = Ad eta (3.20).
  lie::Matrix6 cell_inertia(double a, double b, double s) const;
  /// The node inertia densities of a uniform grid of N nodes (trapezoid cells).
  std::vector<lie::Matrix6> node_inertia(int nodes) const;
  /// The muscles' weight per unit length on the cell [a, b] of a node at s with rotation R
  /// (body frame, acting at the offset): sum_a f_a m_a Ad^T [0; R^T g], f_a the covered fraction.
  Vector6 embedded_weight(const SO3& R, double a, double b, double s) const;
  /// The muscles' gravity potential per unit length on that cell,
  /// -sum_a f_a m_a <g, (p + R r) - (p* + R* r)>.
  double embedded_gravity_density(const SE3& g, const SE3& g_ref, double a, double b,
                                  double s) const;

 private:
  DynamicProblem(rod::RodModel model, SE3 base) : model_(std::move(model)), base_(base) {}

  rod::RodModel model_;
  SE3 base_;
  std::string name_;
  std::optional<loads::Gravity> gravity_;
  std::optional<scene::Drag> drag_;
  std::optional<scene::DistributedWrench> distributed_;
  scene::Wrench tip_;
  std::optional<SE3> tip_target_;  ///< clamped tip
  std::vector<TendonActuator> actuators_;
  std::vector<int> unknown_actuators_;
  bool muscles_ = false, length_control_ = false;
  Vector3 gravity_vector_ = Vector3::Zero();  ///< g [m/s^2] (the muscles' weight)
};

}  // namespace rodlab::solvers::dynamics
