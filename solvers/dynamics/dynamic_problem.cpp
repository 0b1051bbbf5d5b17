#include "rodlab/solvers/dynamics/dynamic_problem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

#include "rodlab/check.hpp"
#include "rodlab/loads/fluidic_chamber.hpp"
#include "rodlab/loads/point_wrench.hpp"
#include "rodlab/solvers/common/tendon_law.hpp"

namespace rodlab::solvers::dynamics {
namespace {

/// Body components of a scene wrench on a section with rotation R (world: a dead load).
Vector6 frame_wrench(const Vector3& moment, const Vector3& force, scene::Frame frame, const SO3& R) {
  const auto kind = frame == scene::Frame::body ? loads::WrenchFrame::body : loads::WrenchFrame::world;
  return loads::PointWrench{lie::se3::join(moment, force), kind}.body_wrench(R);
}

loads::TendonPath tendon_path(const scene::Offset& offset, const std::optional<scene::Span>& span,
                              double length) {
  return loads::TendonPath(offset.points, span ? span->s0 : 0.0, span ? span->s1 : length);
}

/// Ad_{T^-1} for T = [I r; 0 1] (3.13): [I 0; -hat(r) I], so Ad x = [w; v + w x r] (3.19)-(3.20).
lie::Matrix6 offset_adjoint(const Vector3& r) {
  lie::Matrix6 Ad = lie::Matrix6::Identity();
  Ad.bottomLeftCorner<3, 3>() = -lie::so3::hat(r);
  return Ad;
}

/// Ad^T diag(D) Ad: a muscle's diagonal property about its own axis, about the centroid.
lie::Matrix6 transported(const Vector6& D, const Vector3& r) {
  const lie::Matrix6 Ad = offset_adjoint(r);
  return Ad.transpose() * D.asDiagonal() * Ad;
}

TendonActuator tendon_actuator(const scene::Actuator& actuator, double L) {
  struct Convert {
    double L;
    TendonActuator operator()(const scene::Cable& c) const {
      TendonActuator a{tendon_path(c.offset, c.span, L), c.tension ? *c.tension : *c.displacement};
      a.is_cable = true;
      a.enters_from_outside = a.path.s0() > 0.0;
      if (!c.tension) a.drive = ActuatorDrive::length;  // displacement control
      return a;
    }
    TendonActuator operator()(const scene::Fluidic& f) const {
      TendonActuator a{tendon_path(f.offset, f.span, L), f.pressure ? *f.pressure : *f.volume};
      a.chamber_area = loads::chamber_area(f.chamber_radius);
      a.force_per_input = loads::fluidic_chamber_force(1.0, a.chamber_area);  // F = -P A_c
      if (!f.pressure) a.drive = ActuatorDrive::length;  // volume control
      return a;
    }
    TendonActuator operator()(const scene::Muscle& m) const {
      TendonActuator a{tendon_path(m.offset, m.span, L), m.input};
      a.drive = ActuatorDrive::muscle;
      a.law = loads::make_muscle_law(m.law.type, m.law.gain, m.law.stiffness);
      // The muscle's own rod: K, V, M of its section and material, as for the main rod.
      const rod::RodModel own(a.path.s1() - a.path.s0(), m.section, m.material);
      a.embedded = EmbeddedRod{own.K_diag(), own.V_diag(), own.M_diag(), own.mass_per_length()};
      return a;
    }
  };
  return std::visit(Convert{L}, actuator);
}

}  // namespace

DynamicProblem DynamicProblem::from_scene(const scene::Scene& scene) {
  DynamicProblem p(scene.rod.to_model(), scene.base.pose);
  p.name_ = scene.name;
  // tip: exactly one of free (a wrench schedule) and clamped (a pose): the scene loader's rule, so
  // a clamped tip has no tip load (tip_ stays zero).
  if (const auto* clamped = std::get_if<scene::ClampedTip>(&scene.tip))
    p.tip_target_ = clamped->pose;
  else
    p.tip_ = std::get<scene::FreeTip>(scene.tip).wrench;
  const auto& loads = scene.loads;
  if (loads.gravity) {
    const double fluid = loads.buoyancy ? loads.buoyancy->fluid_density : 0.0;
    p.gravity_ = loads::Gravity(p.model_, *loads.gravity, fluid);
  }
  p.drag_ = loads.drag;
  p.distributed_ = loads.distributed;
  RODLAB_THROW_UNLESS(scene.actuators.size() <= static_cast<std::size_t>(kMaxActuators),
                      "dynamics: at most {} actuators (got {})", kMaxActuators,
                      scene.actuators.size());
  for (const auto& a : scene.actuators) {
    p.actuators_.push_back(tendon_actuator(a, p.length()));
    const TendonActuator& t = p.actuators_.back();
    if (t.drive != ActuatorDrive::force)
      p.unknown_actuators_.push_back(static_cast<int>(p.actuators_.size()) - 1);
    p.muscles_ = p.muscles_ || t.drive == ActuatorDrive::muscle;
    p.length_control_ = p.length_control_ || t.drive == ActuatorDrive::length;
  }
  // The muscles are inside the rod's volume: their weight has no buoyancy of its own.
  if (loads.gravity) p.gravity_vector_ = *loads.gravity;
  return p;
}

Vector6 DynamicProblem::drag_load(const Vector6& eta) const {
  if (!drag_) return Vector6::Zero();
  const double speed = eta.tail<3>().norm();
  return -drag_->fluid_density * (drag_->laminar + speed * drag_->turbulent).cwiseProduct(eta);
}

Vector6 DynamicProblem::applied_load(const SO3& R, double t) const {
  if (!distributed_) return Vector6::Zero();
  return frame_wrench(distributed_->moment.at(t), distributed_->force.at(t), distributed_->frame, R);
}

Vector6 DynamicProblem::tip_load(const SO3& R, double t) const {
  return frame_wrench(tip_.moment.at(t), tip_.force.at(t), tip_.frame, R);
}

DynamicProblem::Forces DynamicProblem::forces(double t, const double* unknowns,
                                               const double* rest) const {
  Forces F{};
  if (!unknown_actuators_.empty() && (unknowns == nullptr || rest == nullptr))
    throw std::logic_error("dynamics: the forces of muscles and length-controlled actuators "
                           "need the scheme's unknowns");
  int e = 0;
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    const TendonActuator& a = actuators_[k];
    switch (a.drive) {
      case ActuatorDrive::force:
        F[k] = a.force(t);
        break;
      case ActuatorDrive::length:
        F[k] = unknowns[e++];
        break;
      case ActuatorDrive::muscle:
        F[k] = a.law->force(a.input_at(t), unknowns[e], rest[e]);  // (2.63) with Delta (2.66)
        ++e;
        break;
    }
  }
  return F;
}

double DynamicProblem::span_overlap(int k, double a, double b) const {
  const auto& path = actuators_[k].path;
  return std::max(0.0, std::min(b, path.s1()) - std::max(a, path.s0()));
}

Vector6 DynamicProblem::actuator_wrench(const Vector6& xi, double s, const Forces& F) const {
  Vector6 W = Vector6::Zero();
  for (std::size_t k = 0; k < actuators_.size(); ++k)
    if (F[k] != 0.0 && actuators_[k].path.active(s)) W += F[k] * actuators_[k].path.unit_wrench(s, xi);
  return W;
}

double DynamicProblem::actuator_power(const Vector6& xi, const Vector6& xi_dot, double s,
                                      const Forces& F) const {
  double P = 0.0;
  for (std::size_t k = 0; k < actuators_.size(); ++k)
    if (F[k] != 0.0 && actuators_[k].path.active(s))
      P -= F[k] * actuators_[k].path.unit_wrench(s, xi).dot(xi_dot);
  return P;
}

double DynamicProblem::actuator_length_change(const Vector6& xi_old, const Vector6& xi_new,
                                              double s, const Forces& F) const {
  double d = 0.0;
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    const auto& path = actuators_[k].path;
    if (path.active(s)) d += F[k] * (path.length_rate(s, xi_new) - path.length_rate(s, xi_old));
  }
  return d;
}

Vector6 DynamicProblem::embedded_wrench(const Vector6& xi, const Vector6& xi_dot, double s) const {
  Vector6 W = Vector6::Zero();
  if (!muscles_) return W;
  const Vector6 d = xi - model_.xi_star(s);
  for (const auto& a : actuators_) {
    if (!a.embedded || !a.path.active(s)) continue;
    const Vector3 r = a.path.offset(s);
    // Ad x = [w; v + w x r]; Ad^T y = [y_w + r x y_v; y_v]   (3.19), (2.64)
    auto Ad = [&](const Vector6& x) {
      return lie::se3::join(x.head<3>(), Vector3(x.tail<3>() + x.head<3>().cross(r)));
    };
    const Vector6 y = a.embedded->K.cwiseProduct(Ad(d)) + a.embedded->V.cwiseProduct(Ad(xi_dot));
    W += lie::se3::join(Vector3(y.head<3>() + r.cross(y.tail<3>())), y.tail<3>());
  }
  return W;
}

lie::Matrix6 DynamicProblem::embedded_stiffness(double s) const {
  lie::Matrix6 K = lie::Matrix6::Zero();
  for (const auto& a : actuators_)
    if (a.embedded && a.path.active(s)) K += transported(a.embedded->K, a.path.offset(s));
  return K;
}

lie::Matrix6 DynamicProblem::embedded_viscosity(double s) const {
  lie::Matrix6 V = lie::Matrix6::Zero();
  for (const auto& a : actuators_)
    if (a.embedded && a.path.active(s)) V += transported(a.embedded->V, a.path.offset(s));
  return V;
}

Vector6 DynamicProblem::solve_strain(const lie::Matrix6& Kt, const Vector6& xi_ref,
                                     const Vector6& Lambda, double s, const Forces& F,
                                     const Vector6* guess) const {
  return solve_tendon_law(Kt, xi_ref, Lambda, is_kirchhoff(),
                          [&](const Vector6& xi, Vector6& r, lie::Matrix6& J) {
                            for (std::size_t k = 0; k < actuators_.size(); ++k) {
                              const auto& path = actuators_[k].path;
                              // a slack cable adds exactly nothing (a controller's are often 0)
                              if (F[k] == 0.0 || !path.active(s)) continue;
                              path.add_wrench(s, xi, F[k], r, J);
                            }
                          },
                          guess);
}

lie::Matrix6 DynamicProblem::cell_inertia(double a, double b, double s) const {
  lie::Matrix6 M = model_.M_diag().asDiagonal();
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    const auto& act = actuators_[k];
    if (!act.embedded) continue;
    const double f = span_overlap(static_cast<int>(k), a, b) / (b - a);
    if (f > 0.0) M += f * transported(act.embedded->M, act.path.offset(s));  // (3.20)
  }
  return M;
}

std::vector<lie::Matrix6> DynamicProblem::node_inertia(int nodes) const {
  const double ds = length() / (nodes - 1);
  std::vector<lie::Matrix6> M(nodes);
  for (int j = 0; j < nodes; ++j) {
    const double s = j * ds;
    M[j] = cell_inertia(std::max(0.0, s - 0.5 * ds), std::min(length(), s + 0.5 * ds), s);
  }
  return M;
}

Vector6 DynamicProblem::embedded_weight(const SO3& R, double a, double b, double s) const {
  Vector6 W = Vector6::Zero();
  if (!muscles_ || gravity_vector_.isZero()) return W;
  const Vector3 g_body = R.inverse() * gravity_vector_;
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    const auto& act = actuators_[k];
    if (!act.embedded) continue;
    const double f = span_overlap(static_cast<int>(k), a, b) / (b - a);
    if (f == 0.0) continue;
    const Vector3 force = f * act.embedded->mass_per_length * g_body;
    W += lie::se3::join(act.path.offset(s).cross(force), force);  // Ad^T [0; f], at the offset
  }
  return W;
}

double DynamicProblem::embedded_gravity_density(const SE3& g, const SE3& g_ref, double a,
                                                double b, double s) const {
  double P = 0.0;
  if (!muscles_ || gravity_vector_.isZero()) return P;
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    const auto& act = actuators_[k];
    if (!act.embedded) continue;
    const double f = span_overlap(static_cast<int>(k), a, b) / (b - a);
    const Vector3 r = act.path.offset(s);
    P -= f * act.embedded->mass_per_length * gravity_vector_.dot((g * r) - (g_ref * r));
  }
  return P;
}

std::vector<DynamicProblem::EntryNode> DynamicProblem::entry_nodes(int nodes) const {
  std::vector<EntryNode> entries;
  const double ds = length() / (nodes - 1);
  for (const auto& a : actuators_) {
    if (!a.enters_from_outside) continue;
    const int j = static_cast<int>(std::lround(a.path.s0() / ds));
    if (j > 0 && j < nodes) entries.push_back({a.path.s0(), j});
  }
  return entries;
}

Vector6 DynamicProblem::entry_load(double s_entry, const Vector6& xi, const Forces& F) const {
  Vector6 W = Vector6::Zero();
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    const auto& a = actuators_[k];
    if (a.enters_from_outside && a.path.s0() == s_entry) W -= F[k] * a.path.unit_wrench(s_entry, xi);
  }
  return W;
}

}  // namespace rodlab::solvers::dynamics
