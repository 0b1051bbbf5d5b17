#include "rodlab/solvers/statics/static_problem.hpp"

#include <algorithm>
#include <stdexcept>
#include <variant>

namespace rodlab::solvers::statics {

StaticProblem::StaticProblem(rod::RodModel model, SE3 base)
    : model_(std::move(model)), base_(base) {
  const auto& K = model_.K_diag();
  const double EI = std::min(K[0], K[1]);
  const double L = model_.length();
  wrench_scale_ << EI / L, EI / L, EI / L, EI / (L * L), EI / (L * L), EI / (L * L);
}

StaticProblem StaticProblem::from_scene(const scene::Scene& scene, double t) {
  StaticProblem problem(scene.rod.to_model(), scene.base.pose);
  problem.set_name(scene.name);
  if (const auto* clamped = std::get_if<scene::ClampedTip>(&scene.tip)) {
    problem.set_tip_clamped(clamped->pose);
  } else {
    const auto& w = std::get<scene::FreeTip>(scene.tip).wrench;
    loads::PointWrench tip;
    tip.wrench = lie::se3::join(w.moment.at(t), w.force.at(t));
    tip.frame = w.frame == scene::Frame::world ? loads::WrenchFrame::world : loads::WrenchFrame::body;
    problem.set_tip_wrench(tip);
  }
  const auto& loads = scene.loads;
  if (loads.gravity) {
    const double fluid = loads.buoyancy ? loads.buoyancy->fluid_density : 0.0;
    problem.set_gravity(loads::Gravity(problem.model(), *loads.gravity, fluid));
  }
  if (loads.distributed) {
    loads::DistributedWrench w;
    w.wrench = lie::se3::join(loads.distributed->moment.at(t), loads.distributed->force.at(t));
    w.frame = loads.distributed->frame == scene::Frame::world ? loads::WrenchFrame::world
                                                             : loads::WrenchFrame::body;
    problem.set_distributed(w);
  }
  if (!scene.actuators.empty())
    throw std::invalid_argument(
        "actuators (cable, fluidic, muscle) are not supported by the statics solvers yet");
  return problem;
}

SE3 StaticProblem::tip_target() const {
  const SE3 ref = reference_tip();
  if (load_factor_ == 1.0) return *tip_target_;
  return ref * SE3::exp(load_factor_ * (ref.inverse() * *tip_target_).log());
}

Vector6 StaticProblem::tip_residual(const SE3& g_tip, const Vector6& Lambda_tip) const {
  if (tip_target_) {
    const SE3 target = tip_target();
    const Vector3 rotation_error = (target.rotation().inverse() * g_tip.rotation()).log();
    const Vector3 position_error = (g_tip.translation() - target.translation()) / length();
    return lie::se3::join(rotation_error, position_error);
  }
  const Vector6 W = tip_wrench_.body_wrench(g_tip.rotation(), load_factor_);
  return (Lambda_tip - W).cwiseQuotient(wrench_scale_);
}

}  // namespace rodlab::solvers::statics
