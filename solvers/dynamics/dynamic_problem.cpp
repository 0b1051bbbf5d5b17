#include "rodlab/solvers/dynamics/dynamic_problem.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

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

TendonActuator tendon_actuator(const scene::Actuator& actuator, double L) {
  struct Convert {
    double L;
    TendonActuator operator()(const scene::Cable& c) const {
      if (!c.tension)
        throw std::invalid_argument(
            "dynamics: cable displacement control is not supported yet (give a tension)");
      TendonActuator a{tendon_path(c.offset, c.span, L), *c.tension, 1.0, true};
      a.enters_from_outside = a.path.s0() > 0.0;
      return a;
    }
    TendonActuator operator()(const scene::Fluidic& f) const {
      if (!f.pressure)
        throw std::invalid_argument(
            "dynamics: fluidic volume control is not supported yet (give a pressure)");
      const double area = std::numbers::pi * f.chamber_radius * f.chamber_radius;
      return TendonActuator{tendon_path(f.offset, f.span, L), *f.pressure, -area, false};
    }
    TendonActuator operator()(const scene::Muscle&) const {
      throw std::invalid_argument("dynamics: artificial muscles are not supported yet");
    }
  };
  return std::visit(Convert{L}, actuator);
}

}  // namespace

DynamicProblem DynamicProblem::from_scene(const scene::Scene& scene) {
  if (scene.tip_clamped())
    throw std::invalid_argument("dynamics: a clamped tip is not supported yet (tip.free only)");
  DynamicProblem p(scene.rod.to_model(), scene.base.pose);
  p.name_ = scene.name;
  p.tip_ = std::get<scene::FreeTip>(scene.tip).wrench;
  const auto& loads = scene.loads;
  if (loads.gravity) {
    const double fluid = loads.buoyancy ? loads.buoyancy->fluid_density : 0.0;
    p.gravity_ = loads::Gravity(p.model_, *loads.gravity, fluid);
  }
  p.drag_ = loads.drag;
  p.distributed_ = loads.distributed;
  for (const auto& a : scene.actuators) p.actuators_.push_back(tendon_actuator(a, p.length()));
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

Vector6 DynamicProblem::actuator_wrench(const Vector6& xi, double s, double t) const {
  Vector6 W = Vector6::Zero();
  for (const auto& a : actuators_)
    if (a.path.active(s)) W += a.force(t) * a.path.unit_wrench(s, xi);
  return W;
}

double DynamicProblem::actuator_power(const Vector6& xi, const Vector6& xi_dot, double s,
                                      double t) const {
  double P = 0.0;
  for (const auto& a : actuators_)
    if (a.path.active(s)) P -= a.force(t) * a.path.unit_wrench(s, xi).dot(xi_dot);
  return P;
}

Vector6 DynamicProblem::solve_strain_with_actuators(const Vector6& Kt, const Vector6& xi_ref,
                                                    const Vector6& Lambda, double s,
                                                    double t) const {
  return solve_tendon_law(Kt.asDiagonal().toDenseMatrix(), xi_ref, Lambda, is_kirchhoff(),
                          [&](const Vector6& xi, Vector6& r, lie::Matrix6& J) {
                            for (const auto& a : actuators_) {
                              if (!a.path.active(s)) continue;
                              const double F = a.force(t);
                              r += F * a.path.unit_wrench(s, xi);
                              J += F * a.path.unit_wrench_jacobian(s, xi);
                            }
                          });
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

Vector6 DynamicProblem::entry_load(double s_entry, const Vector6& xi, double t) const {
  Vector6 W = Vector6::Zero();
  for (const auto& a : actuators_)
    if (a.enters_from_outside && a.path.s0() == s_entry)
      W -= a.force(t) * a.path.unit_wrench(s_entry, xi);
  return W;
}

}  // namespace rodlab::solvers::dynamics
