#include "rodlab/solvers/statics/static_problem.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <variant>

#include <Eigen/LU>

#include "rodlab/check.hpp"
#include "rodlab/loads/fluidic_chamber.hpp"
#include "rodlab/solvers/common/tendon_law.hpp"

namespace rodlab::solvers::statics {
namespace {

using Matrix6 = lie::Matrix6;

/// Ad_{T^-1} for T a translation by r: [I 0; -hat(r) I].
/// K_mus = Ad^T diag(K_a) Ad maps a body strain change to the muscle's wrench about the centroid.
Matrix6 transported_stiffness(const Vector6& Ka, const Vector3& r) {
  Matrix6 Ad = Matrix6::Identity();
  Ad.bottomLeftCorner<3, 3>() = -lie::so3::hat(r);
  return Ad.transpose() * Ka.asDiagonal() * Ad;
}

loads::TendonPath tendon_path(const scene::Offset& offset, const std::optional<scene::Span>& span,
                              double length) {
  return loads::TendonPath(offset.points, span ? span->s0 : 0.0, span ? span->s1 : length);
}

ActuatorTerm actuator_term(const scene::Actuator& actuator, double t, double L) {
  struct Convert {
    double t, L;
    ActuatorTerm operator()(const scene::Cable& c) const {
      ActuatorTerm a{ActuatorKind::cable, tendon_path(c.offset, c.span, L)};
      if (c.tension) a.input = c.tension->at(t);
      if (c.displacement) a.input = c.displacement->at(t), a.target_length = 0.0;  // set below
      return a;
    }
    ActuatorTerm operator()(const scene::Fluidic& f) const {
      ActuatorTerm a{ActuatorKind::fluidic, tendon_path(f.offset, f.span, L)};
      a.chamber_area = loads::chamber_area(f.chamber_radius);
      if (f.pressure) a.input = f.pressure->at(t);
      if (f.volume) a.input = f.volume->at(t), a.target_length = 0.0;  // set below
      return a;
    }
    ActuatorTerm operator()(const scene::Muscle& m) const {
      ActuatorTerm a{ActuatorKind::muscle, tendon_path(m.offset, m.span, L)};
      a.input = m.input.at(t);
      a.law = loads::make_muscle_law(m.law.type, m.law.gain, m.law.stiffness);
      const auto p = rod::properties(m.section);
      const auto& e = m.material;
      a.embedded_stiffness << e.E * p.Ix, e.E * p.Iy, e.G * p.Jt, e.G * p.A, e.G * p.A, e.E * p.A;
      return a;
    }
  };
  return std::visit(Convert{t, L}, actuator);
}

}  // namespace

StaticProblem::StaticProblem(rod::RodModel model, SE3 base)
    : model_(std::move(model)), base_(base) {
  const auto& K = model_.K_diag();
  const double EI = std::min(K[0], K[1]);
  const double L = model_.length();
  wrench_scale_ << EI / L, EI / L, EI / L, EI / (L * L), EI / (L * L), EI / (L * L);
  breakpoints_ = model_.rest_breaks();  // where xi* jumps: the schemes split their steps there
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
  for (const auto& actuator : scene.actuators) problem.add_actuator(actuator_term(actuator, t, problem.length()));
  return problem;
}

SE3 StaticProblem::tip_target() const {
  if (load_factor_ == 1.0) return *tip_target_;
  // Continuation path: the tip of a rod of constant twist interpolated between xi* and the
  // constant twist xi_eff that reaches the target, base exp(L xi_eff) = target. Every
  // intermediate target is then reachable without stretch (an arc end for an arc target), unlike
  // the SE(3) geodesic between the reference tip and the target.
  const double L = length();
  const SE3 local = base_.inverse() * *tip_target_;
  const Vector6 xi_eff = local.log() / L;
  if (model_.has_rest_spans()) {  // the same blend span by span: sum (1 - f) l_k xi*_k + f L xi_eff
    SE3 g = base_;
    const auto& spans = model_.rest_spans();
    for (std::size_t k = 0; k < spans.size(); ++k) {
      const double l = (k + 1 < spans.size() ? spans[k + 1].begin : L) - spans[k].begin;
      g = g * SE3::exp(l * ((1.0 - load_factor_) * spans[k].xi_star + load_factor_ * xi_eff));
    }
    return g;
  }
  Vector6 xi_arc = model_.xi_star();
  xi_arc.head<3>() = xi_eff.head<3>();  // the rotation part of the screw: log(R) / L
  if (!model_.is_kirchhoff() || xi_arc == model_.xi_star())  // (no turn: a pure translation)
    return base_ * SE3::exp(L * ((1.0 - load_factor_) * model_.xi_star() + load_factor_ * xi_eff));
  // A straight Kirchhoff rod held at its full length has an indeterminate axial force, and the
  // screw path above asks for stretch the rod cannot give (kinsol stalled at its start for
  // buckled-column tips beyond 150 degrees; docs/statics.md). Its path leaves the start along
  // exact equilibria instead: first the arcs of nu = nu* (zero force) that turn the tip to the
  // target's rotation, then the tip moved straight to the target's position.
  const Vector6& xs = model_.xi_star();
  if (load_factor_ <= 0.5) return base_ * SE3::exp(L * (xs + 2.0 * load_factor_ * (xi_arc - xs)));
  const Vector3 arc_tip = SE3::exp(L * xi_arc).translation();
  const double t = 2.0 * load_factor_ - 1.0;
  return base_ * SE3(local.rotation(), arc_tip + t * (local.translation() - arc_tip));
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

namespace rodlab::solvers::statics {

void StaticProblem::add_actuator(ActuatorTerm term) {
  RODLAB_THROW_UNLESS(static_cast<int>(actuators_.size()) < kMaxActuators, "at most {} actuators",
                      kMaxActuators);
  if (term.path.s0() < 0.0 || term.path.s1() > length())
    throw std::invalid_argument("actuator span outside [0, L]");
  // Rest length: composite Simpson of |u(xi*)| over the span (u is piecewise smooth between
  // routing knots, so integrate knot to knot).
  std::vector<double> cuts{term.path.s0()};
  for (double k : term.path.knots()) cuts.push_back(k);
  for (double b : model_.rest_breaks())  // xi* jumps there
    if (b > term.path.s0() && b < term.path.s1()) cuts.push_back(b);
  std::sort(cuts.begin() + 1, cuts.end());
  cuts.push_back(term.path.s1());
  double rest = 0.0;
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
    const int n = 200;  // even
    const double a = cuts[c], h = (cuts[c + 1] - a) / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      // evaluate just inside the segment at its ends, where r' is the segment's slope
      const double si = std::clamp(a + i * h, a + 1e-12 * h, cuts[c + 1] - 1e-12 * h);
      sum += w * term.path.length_rate(si, model_.xi_star(si));
    }
    rest += sum * h / 3.0;
  }
  term.rest_length = rest;
  actuators_.push_back(std::move(term));
  set_actuator_input(static_cast<int>(actuators_.size()) - 1, actuators_.back().input);
  const ActuatorTerm& a = actuators_.back();
  unknown_value_.push_back(a.kind == ActuatorKind::muscle ? a.rest_length : 0.0);
  if (a.has_unknown()) ++extra_count_;
  for (double b : {a.path.s0(), a.path.s1()})
    if (b > 0.0 && b < length()) breakpoints_.push_back(b);
  for (double k : a.path.knots()) breakpoints_.push_back(k);
  std::sort(breakpoints_.begin(), breakpoints_.end());
  breakpoints_.erase(std::unique(breakpoints_.begin(), breakpoints_.end()), breakpoints_.end());
}

void StaticProblem::set_actuator_input(int k, double value) {
  RODLAB_THROW_UNLESS(k >= 0 && k < static_cast<int>(actuators_.size()),
                      "actuator index {} out of range (the problem has {} actuators)", k, actuators_.size());
  ActuatorTerm& term = actuators_[k];
  term.input = value;
  // Length control: the input is a displacement (cable pulled in) or a volume (chamber).
  if (term.target_length) {
    term.target_length = term.kind == ActuatorKind::cable ? term.rest_length - value
                                                          : loads::chamber_length(value, term.chamber_area);
  }
}

StaticProblem::Mask StaticProblem::active_mask(double s_mid) const {
  Mask mask = 0;
  for (std::size_t k = 0; k < actuators_.size(); ++k)
    if (actuators_[k].path.active(s_mid)) mask |= Mask{1} << k;
  return mask;
}

double StaticProblem::axial_force(int k) const {
  const ActuatorTerm& a = actuators_[k];
  switch (a.kind) {
    case ActuatorKind::cable:
      return a.target_length ? unknown_value_[k] : load_factor_ * a.input;
    case ActuatorKind::fluidic:
      return a.target_length ? unknown_value_[k]
                             : loads::fluidic_chamber_force(load_factor_ * a.input, a.chamber_area);
    case ActuatorKind::muscle:
      return a.law->force(load_factor_ * a.input, unknown_value_[k], a.rest_length);
  }
  return 0.0;
}

void StaticProblem::set_extra_unknowns(std::span<const double> z) {
  std::size_t j = 0;
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    if (!actuators_[k].has_unknown()) continue;
    const bool is_length = actuators_[k].kind == ActuatorKind::muscle;
    unknown_value_[k] = z[j++] * (is_length ? length() : wrench_scale_[3]);
  }
}

std::vector<double> StaticProblem::extra_initial_guess() const {
  std::vector<double> z;
  for (const auto& a : actuators_)
    if (a.has_unknown()) z.push_back(a.kind == ActuatorKind::muscle ? a.rest_length / length() : 0.0);
  return z;
}

void StaticProblem::extra_residuals(std::span<const double> lengths, std::span<double> out) const {
  std::size_t j = 0;
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    const ActuatorTerm& a = actuators_[k];
    if (!a.has_unknown()) continue;
    const double target = a.kind == ActuatorKind::muscle
                              ? unknown_value_[k]  // (2.67): Delta_guess = integrated length
                              : a.rest_length + load_factor_ * (*a.target_length - a.rest_length);
    out[j++] = (lengths[k] - target) / length();
  }
}

Vector6 StaticProblem::entry_jump(double b, const Vector6& xi_left) const {
  Vector6 jump = Vector6::Zero();
  for (std::size_t k = 0; k < actuators_.size(); ++k)
    if (enters_at(actuators_[k], b))
      jump += axial_force(static_cast<int>(k)) * actuators_[k].path.unit_wrench(b, xi_left);
  return jump;
}

bool StaticProblem::has_entry(double b) const {
  return std::any_of(actuators_.begin(), actuators_.end(),
                     [b](const ActuatorTerm& a) { return enters_at(a, b); });
}

Matrix6 StaticProblem::entry_jump_jacobian(double b, const Vector6& xi_left) const {
  Matrix6 J = Matrix6::Zero();
  for (std::size_t k = 0; k < actuators_.size(); ++k)
    if (enters_at(actuators_[k], b))
      J += axial_force(static_cast<int>(k)) * actuators_[k].path.unit_wrench_jacobian(b, xi_left);
  return J;
}

Matrix6 StaticProblem::law_stiffness(double s, Mask mask) const {
  Matrix6 Kt = model_.K_diag().asDiagonal();
  for (std::size_t k = 0; k < actuators_.size(); ++k)
    if ((mask >> k) & 1U && actuators_[k].kind == ActuatorKind::muscle)
      Kt += transported_stiffness(actuators_[k].embedded_stiffness, actuators_[k].path.offset(s));
  return Kt;
}

Matrix6 StaticProblem::strain_jacobian(const Vector6& xi, double s, Mask mask) const {
  if (mask == 0) return strain_slope().asDiagonal();
  Matrix6 J = law_stiffness(s, mask);
  for (std::size_t k = 0; k < actuators_.size(); ++k)
    if ((mask >> k) & 1U)
      J += axial_force(static_cast<int>(k)) * actuators_[k].path.unit_wrench_jacobian(s, xi);
  Matrix6 slope = Matrix6::Zero();
  if (model_.is_kirchhoff()) slope.topLeftCorner<3, 3>() = J.topLeftCorner<3, 3>().inverse();
  else slope = J.partialPivLu().inverse();
  return slope;
}

Vector6 StaticProblem::strain(const Vector6& Lambda, double s, Mask mask) const {
  if (mask == 0) return strain(Lambda, s);
  const Vector6& xs = model_.xi_star(s);
  return solve_tendon_law(law_stiffness(s, mask), xs, Lambda, model_.is_kirchhoff(),
                          [&](const Vector6& xi, Vector6& r, Matrix6& J) {
                            for (std::size_t k = 0; k < actuators_.size(); ++k) {
                              if (!((mask >> k) & 1U)) continue;
                              const double F = axial_force(static_cast<int>(k));
                              r += F * actuators_[k].path.unit_wrench(s, xi);
                              J += F * actuators_[k].path.unit_wrench_jacobian(s, xi);
                            }
                          });
}

Vector6 StaticProblem::rod_wrench(const Vector6& Lambda, const Vector6& xi, double s, Mask mask) const {
  Vector6 W = Lambda;
  for (std::size_t k = 0; k < actuators_.size(); ++k) {
    if (!((mask >> k) & 1U)) continue;
    const ActuatorTerm& a = actuators_[k];
    W -= axial_force(static_cast<int>(k)) * a.path.unit_wrench(s, xi);
    if (a.kind == ActuatorKind::muscle)
      W -= transported_stiffness(a.embedded_stiffness, a.path.offset(s)) * (xi - model_.xi_star(s));
  }
  return W;
}

}  // namespace rodlab::solvers::statics
