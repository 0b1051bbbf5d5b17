#include "rodlab/solvers/dynamics/shooting/shooting_stepper.hpp"

#include "rodlab/solvers/dynamics/shooting/bdf_alpha.hpp"
#include "rodlab/solvers/dynamics/shooting/implicit_midpoint.hpp"

#include "embedded_reference.hpp"
#include "shooting_newton.hpp"
#include "staggered_shooting_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "rodlab/check.hpp"

namespace rodlab::solvers::dynamics {
namespace {

using lie::Matrix6;
namespace se3 = lie::se3;

/// How far (scaled, DynamicProblem::clamp_mismatch) an initial state may miss a clamped tip.
constexpr double kClampStartTolerance = 1e-6;

class ShootingStepper final : public Stepper {
 public:
  ShootingStepper(const DynamicProblem& problem, const ShootingOptions& options,
                  const RestState& initial, std::unique_ptr<TimeRule> rule)
      : P_(problem), opt_(options), rule_(std::move(rule)), n_(options.nodes),
        ds_(problem.length() / (n_ - 1)) {
    const std::string name(rule_->name());
    RODLAB_THROW_UNLESS(n_ >= 3, "{}: nodes must be >= 3", name);
    problem.model().require_spans_on_grid(n_, name);
    RODLAB_THROW_UNLESS(
        static_cast<int>(initial.xi.size()) == n_ && static_cast<int>(initial.g.size()) == n_,
        "{}: expected {} initial nodes, got {}", name, n_, initial.xi.size());
    xi_ = initial.xi;
    g_ = initial.g;
    if (problem.tip_clamped()) {
      // The state must meet the clamp on this grid (its poses are rebuilt from the strains).
      update_poses();
      const double miss = P_.clamp_mismatch(g_.back()).lpNorm<Eigen::Infinity>();
      RODLAB_THROW_UNLESS(miss <= kClampStartTolerance,
                          "{}: the initial strains miss tip.clamped by {:g} (scaled) on this grid "
                          "(explicit Euler RKMK); start from its own statics "
                          "(rkmk-euler-explicit at the same nodes)",
                          name, miss);
    }
    eta_.assign(n_, Vector6::Zero());
    xi_u_.assign(n_, Vector6::Zero());
    eta_u_.assign(n_, Vector6::Zero());
    xi_hist_.assign(n_, Vector6::Zero());
    eta_hist_.assign(n_, Vector6::Zero());
    xi_ref_.assign(n_, Vector6::Zero());
    // node j's strain carries the pose along segment j: the segment's rest strain (its span's)
    K_xi_star_.resize(n_);
    for (int j = 0; j < n_; ++j)
      K_xi_star_[j] = problem.model().K_diag().cwiseProduct(problem.model().node_xi_star(j, n_));
    g_u_.assign(n_, SE3::identity());
    const auto& K = problem.model().K_diag();
    const double EI = std::min(K[0], K[1]), L = problem.length();
    scale_ << EI / L, EI / L, EI / L, EI / (L * L), EI / (L * L), EI / (L * L);
    // first guess: the base wrench of the initial state
    const Vector6 x0 = P_.model().K_diag()
                           .cwiseProduct(xi_[0] - P_.model().segment_xi_star(0, n_))
                           .cwiseQuotient(scale_);
    entries_ = problem.entry_nodes(n_);
    m_ = problem.unknown_count();
    if (m_ == 0) {
      plain_.start(x0);
    } else {
      setup_unknowns(x0);
    }
    muscles_ = problem.has_muscles();
    if (muscles_) {
      inertia_ = problem.node_inertia(n_);
      K_emb_.resize(n_);
      V_emb_.resize(n_);
      Kt_full_.resize(n_);
      for (int j = 0; j < n_; ++j) {
        K_emb_[j] = problem.embedded_stiffness(j * ds_);
        V_emb_[j] = problem.embedded_viscosity(j * ds_);
      }
    }
  }

  StepStatus step(double t, double dt) override {
    t_u_ = t + rule_->theta() * dt;
    t_end_ = t + dt;
    dt_ = dt;
    c_ = rule_->coefficient(dt);
    end_ = rule_->end_coefficient();
    rule_->history(RuleField::strain, dt, xi_, xi_hist_);
    rule_->history(RuleField::velocity, dt, eta_, eta_hist_);
    const Vector6& V = P_.model().V_diag();
    Kt_ = P_.model().K_diag() + c_ * V;
    // Lambda = K (xi - xi*) + V (c xi + h) + tendons = Kt (xi - xi_ref) + tendons   (3.10)
    if (muscles_)
      muscle_references();
    else
      for (int j = 0; j < n_; ++j)
        xi_ref_[j] = (K_xi_star_[j] - V.cwiseProduct(xi_hist_[j])).cwiseQuotient(Kt_);
    const StepStatus status = m_ == 0 ? solve(plain_, t) : solve(extended_, t);
    if (!status.ok) return status;
    // the last shot was at the solution: the profiles at t_u are current.
    accumulate_ledger(dt);
    rule_->advance(RuleField::strain, dt, xi_u_, xi_hist_, xi_);
    rule_->advance(RuleField::velocity, dt, eta_u_, eta_hist_, eta_);
    update_poses();
    ++steps_;
    return status;
  }

  Energy energy() const override {
    Energy e = ledger_;
    e.kinetic = kinetic_energy(P_.model(), eta_, ds_);
    e.strain = strain_energy_nodes(P_.model(), xi_, ds_);
    e.gravity = gravity_energy(P_, g_, ds_);
    if (muscles_) {
      e.kinetic = kinetic_energy(inertia_, eta_, ds_);
      e.strain += embedded_strain_energy_nodes(P_, xi_, ds_);
      e.gravity += embedded_gravity_energy(P_, g_, ds_);
    }
    return e;
  }

  Vector3 tip_position() const override { return g_.back().translation(); }

  double max_det_deviation() const override { return dynamics::max_det_deviation(g_); }

  std::vector<result::CenterlineSample> centerline() const override {
    std::vector<result::CenterlineSample> out(n_);
    for (int j = 0; j < n_; ++j) out[j] = {j * ds_, g_[j], xi_[j]};
    return out;
  }
  std::vector<Vector6> velocities() const override { return eta_; }

  std::vector<ActuatorReading> actuator_readings() const override {
    std::vector<ActuatorReading> out(m_);
    const auto& which = P_.unknown_actuators();
    for (int e = 0; e < m_; ++e) out[e] = {which[e], path_length(e, xi_), F_[which[e]]};
    return out;
  }

 private:
  StepStatus failure(const std::string& what, double t) const {
    return StepStatus::failed(rodlab::format("{}: {} in the step from t = {:g} s (dt = {:g} s)",
                                             rule_->name(), what, t, dt_));
  }

  /// Newton on the shooting unknowns x (Lambda(0) scaled, then the actuator unknowns):
  /// shooting_newton.hpp.
  template <class Vec, class Mat>
  StepStatus solve(ShootingNewton<Vec, Mat>& newton, double t) {
    const ShootingOutcome out = newton.solve([this](const Vec& x) { return shoot<Vec>(x); }, c_,
                                             steps_ >= 2, opt_.tol, opt_.max_iterations);
    if (!out.failure.empty()) return failure(out.failure, t);
    StepStatus status;
    status.iterations = out.shots;
    return status;
  }

  /// Integrates the BVP at t_u from the base with Lambda(0) = x * scale (explicit Euler RKMK,
  /// (3.51)-(3.52)) and returns the scaled tip residual; with actuator unknowns, also their rows:
  /// a muscle's x_e - L_e(xi_u) / L (its length at t_u, x_e = Delta / L), a length-controlled
  /// actuator's (L_e(x_end) - L_target(t + dt)) / L with the end-of-step strains
  /// x_end = a xi_u + (1 - a) xi (x_e = F / (E I / L^2)). L_e: the trapezoid over the nodes.
  template <class Vec>
  Vec shoot(const Vec& x) {
    const Vector6& M = P_.model().M_diag();
    Vector6 Lambda = x.template head<6>().cwiseProduct(scale_);
    Vector6 eta = Vector6::Zero();
    SE3 g = P_.base();
    SE3 g_end = g;  // a clamped tip: the end-of-step poses (below)
    const bool clamp_at_end = P_.tip_clamped() && end_ != 1.0;
    const bool unknowns = m_ > 0;
    if (unknowns) {
      for (int e = 0; e < m_; ++e)
        unknown_[e] = x[6 + e] * (is_muscle_[e] ? P_.length() : scale_[3]);
      F_ = P_.forces(t_u_, unknown_.data(), rest_.data());
    }
    for (int j = 0;; ++j) {
      const double s = j * ds_;
      Vector6 xi;
      if (muscles_)
        xi = P_.solve_strain(Kt_full_[j], xi_ref_[j], Lambda, s, F_);
      else if (unknowns)
        xi = P_.solve_strain(lie::Matrix6(Kt_.asDiagonal()), xi_ref_[j], Lambda, s, F_);
      else
        xi = P_.solve_strain(Kt_, xi_ref_[j], Lambda, s, t_u_);
      xi_u_[j] = xi;
      eta_u_[j] = eta;
      g_u_[j] = g;
      if (j == n_ - 1) break;
      const SO3& R = g.rotation();
      const Vector6 load = P_.gravity_load(R) + P_.applied_load(R, t_u_) + P_.drag_load(eta);
      Vector6 dLambda;
      if (muscles_) {
        // the full node inertia and the muscles' weight (3.16)-(3.20)
        const Vector6 Meta = inertia_[j] * eta;
        dLambda = inertia_[j] * (c_ * eta + eta_hist_[j]) - se3::coad_apply(eta, Meta) +
                  se3::coad_apply(xi, Lambda) - load -
                  P_.embedded_weight(R, std::max(0.0, s - 0.5 * ds_), s + 0.5 * ds_, s);
      } else {
        const Vector6 Meta = M.cwiseProduct(eta);
        dLambda = M.cwiseProduct(c_ * eta + eta_hist_[j]) - se3::coad_apply(eta, Meta) +
                  se3::coad_apply(xi, Lambda) - load;                                   // (3.51)
      }
      const Vector6 deta = (c_ * xi + xi_hist_[j]) - se3::ad_apply(xi, eta);             // (3.52)
      g = g * SE3::exp(ds_ * xi);
      if (clamp_at_end) g_end = g_end * SE3::exp(ds_ * (end_ * xi + (1.0 - end_) * xi_[j]));
      Lambda += ds_ * dLambda;
      eta += ds_ * deta;
      for (const auto& e : entries_)
        if (e.node == j + 1)
          Lambda -= unknowns ? P_.entry_load(e.s, xi, F_) : P_.entry_load(e.s, xi, t_u_);
    }
    Vec r;
    r.resize(6 + m_);
    r.template head<6>() = tip_residual(clamp_at_end ? g_end : g, Lambda);
    if (unknowns) {
      for (int j = 0; j < n_; ++j) xi_end_[j] = end_ * xi_u_[j] + (1.0 - end_) * xi_[j];
      const double L = P_.length();
      for (int e = 0; e < m_; ++e)
        r[6 + e] = is_muscle_[e]
                       ? x[6 + e] - path_length(e, xi_u_) / L
                       : (path_length(e, xi_end_) - P_.actuators()[which_[e]].target_length(
                                                        t_end_, rest_[e])) / L;
    }
    return r;
  }

  /// The six tip rows of the shooting residual from the marched tip wrench Lambda(L) at the
  /// unknowns' time t_u and the tip pose g: a free tip's wrench balance (Lambda(L) - W_tip) /
  /// scale (g at t_u), or a clamped tip's pose mismatch [log(g^-1 g_clamp) rotation;
  /// translation / L] (DynamicProblem::clamp_mismatch; O(1) for a bend of about a radian, as the
  /// scaled wrench; the thesis' static clamp, section 2.7.2, uses log(R_des^T R(L)) and
  /// p(L) - p_des, the same zero set). For the clamp g is the END-of-step tip pose, marched from
  /// the end-of-step strains a xi_u + (1 - a) xi (TimeRule::end_coefficient; BDF-alpha: xi_u
  /// itself): with the midpoint rule, clamping at t_u left the poses rebuilt from
  /// 2 xi_u - xi off the clamp by O(|xi_u - xi|^2), a mismatch that flips sign every step
  /// (docs/dynamics.md "Clamped tips"). The clamp's reaction is Lambda(L).
  Vector6 tip_residual(const SE3& g, const Vector6& Lambda) const {
    if (P_.tip_clamped()) return P_.clamp_mismatch(g);
    return (Lambda - P_.tip_load(g.rotation(), t_u_)).cwiseQuotient(scale_);
  }

  /// Unknown e's path length on the grid: trapezoid over the nodes, each node's weight the
  /// overlap of its cell with the span.
  double path_length(int e, const std::vector<Vector6>& xi) const {
    const auto& path = P_.actuators()[which_[e]].path;
    double sum = 0.0;
    for (int j = 0; j < n_; ++j) {
      const double w = node_weight_[static_cast<std::size_t>(e) * n_ + j];
      if (w != 0.0) sum += w * path.length_rate(j * ds_, xi[j]);
    }
    return sum;
  }

  /// Actuator unknowns: which actuators, their node weights and grid rest lengths, the first
  /// guess (muscles: the length of the initial state; forces: 0).
  void setup_unknowns(const Vector6& lambda0) {
    which_ = P_.unknown_actuators();
    is_muscle_.assign(m_, 0);
    rest_.assign(m_, 0.0);
    unknown_.assign(m_, 0.0);
    node_weight_.assign(static_cast<std::size_t>(m_) * n_, 0.0);
    xi_end_.assign(n_, Vector6::Zero());
    std::vector<Vector6> reference(n_);
    for (int j = 0; j < n_; ++j) reference[j] = P_.model().node_xi_star(j, n_);
    for (int e = 0; e < m_; ++e) {
      is_muscle_[e] = P_.actuators()[which_[e]].drive == ActuatorDrive::muscle;
      for (int j = 0; j < n_; ++j) {
        const double s = j * ds_;
        const double a = std::max(0.0, s - 0.5 * ds_), b = std::min(P_.length(), s + 0.5 * ds_);
        node_weight_[static_cast<std::size_t>(e) * n_ + j] = P_.span_overlap(which_[e], a, b);
      }
      rest_[e] = path_length(e, reference);
    }
    ShootingVectorU x0(6 + m_);
    x0.head<6>() = lambda0;
    for (int e = 0; e < m_; ++e) x0[6 + e] = is_muscle_[e] ? path_length(e, xi_) / P_.length() : 0.0;
    extended_.start(x0);
  }

  /// Muscles: the full constitutive reference of every node (embedded_reference.hpp).
  void muscle_references() {
    for (int j = 0; j < n_; ++j)
      embedded_reference(P_, P_.model().node_xi_star(j, n_), K_emb_[j],
                         V_emb_[j], c_, xi_hist_[j], Kt_full_[j], xi_ref_[j]);
  }

  /// Dissipation and input work of the step: the power at t_u (trapezoid in s) weighted with
  /// the power at the start of the step as the rule says (midpoint rule or trapezoid in time).
  void accumulate_ledger(double dt) {
    const auto& V = P_.model().V_diag();
    double dissipated = 0.0, work = 0.0;
    for (int j = 0; j < n_; ++j) {
      const double w = (j == 0 || j == n_ - 1) ? 0.5 * ds_ : ds_;
      const Vector6 xi_dot = c_ * xi_u_[j] + xi_hist_[j];
      const SO3& R = g_u_[j].rotation();
      dissipated += w * (xi_dot.dot(V.cwiseProduct(xi_dot)) - P_.drag_load(eta_u_[j]).dot(eta_u_[j]));
      if (muscles_) dissipated += w * P_.embedded_dissipation(xi_dot, j * ds_);
      work += w * P_.applied_load(R, t_u_).dot(eta_u_[j]);
      if (m_ > 0)
        work += w * P_.actuator_power(xi_u_[j], xi_dot, j * ds_, F_);
      else if (P_.has_actuators())
        work += w * P_.actuator_power(xi_u_[j], xi_dot, j * ds_, t_u_);
    }
    work += P_.tip_load(g_u_.back().rotation(), t_u_).dot(eta_u_.back());
    const double w0 = rule_->ledger_start_weight(), w1 = 1.0 - w0;
    ledger_.dissipated += dt * (w0 * dissipated_start_ + w1 * dissipated);
    ledger_.work_in += dt * (w0 * work_start_ + w1 * work);
    dissipated_start_ = dissipated;  // the start of the next step (the state at rest: 0)
    work_start_ = work;
  }

  /// Poses from the strains by the same explicit Euler RKMK as the shooting.
  void update_poses() {
    g_[0] = P_.base();
    for (int j = 0; j + 1 < n_; ++j) g_[j + 1] = g_[j] * SE3::exp(ds_ * xi_[j]);
  }

  const DynamicProblem& P_;
  ShootingOptions opt_;
  std::unique_ptr<TimeRule> rule_;
  int n_;
  double ds_;
  Vector6 scale_, Kt_;
  double t_u_ = 0.0, t_end_ = 0.0, dt_ = 0.0, c_ = 0.0, end_ = 1.0;
  double dissipated_start_ = 0.0, work_start_ = 0.0;
  std::vector<Vector6> xi_, eta_, xi_u_, eta_u_, xi_hist_, eta_hist_, xi_ref_;
  std::vector<Vector6> K_xi_star_;  ///< K xi* of every node (its segment's span)
  std::vector<SE3> g_, g_u_;
  std::vector<DynamicProblem::EntryNode> entries_;
  ShootingNewton<Vector6, Matrix6> plain_;  ///< Lambda(0) only
  ShootingNewton<ShootingVectorU, ShootingMatrixU> extended_;  ///< Lambda(0) and the actuator unknowns
  long steps_ = 0;
  Energy ledger_;
  // Actuator unknowns (muscle lengths, length-controlled forces) and embedded muscles.
  int m_ = 0;
  bool muscles_ = false;
  std::vector<int> which_;
  std::vector<char> is_muscle_;
  std::vector<double> rest_, unknown_, node_weight_;  ///< node_weight_: m x N
  std::vector<Vector6> xi_end_;
  DynamicProblem::Forces F_{};
  std::vector<lie::Matrix6> inertia_, K_emb_, V_emb_, Kt_full_;
};

}  // namespace

std::unique_ptr<Stepper> make_shooting_stepper(const DynamicProblem& problem,
                                               const ShootingOptions& options,
                                               const RestState& initial,
                                               std::unique_ptr<TimeRule> rule) {
  if (!rule) throw std::invalid_argument("shooting stepper: no time rule");
  if (options.grid != ShootingGrid::euler)  // staggered, or corrected (the same march)
    return make_staggered_shooting_stepper(problem, options, initial, std::move(rule));
  return std::make_unique<ShootingStepper>(problem, options, initial, std::move(rule));
}

std::string_view shooting_grid_name(ShootingGrid grid) {
  switch (grid) {
    case ShootingGrid::euler: return "euler";
    case ShootingGrid::staggered: return "staggered";
    case ShootingGrid::corrected: return "corrected";
  }
  return "?";
}

std::optional<ShootingGrid> shooting_grid_from_name(std::string_view name) {
  for (const auto grid : {ShootingGrid::euler, ShootingGrid::staggered, ShootingGrid::corrected})
    if (name == shooting_grid_name(grid)) return grid;
  return std::nullopt;
}

std::unique_ptr<Stepper> make_implicit_midpoint(const DynamicProblem& problem,
                                                const ImplicitMidpointOptions& options,
                                                const RestState& initial) {
  return make_shooting_stepper(problem, options, initial, make_midpoint_rule());
}

std::unique_ptr<Stepper> make_bdf_alpha(const DynamicProblem& problem,
                                        const BdfAlphaOptions& options, const RestState& initial) {
  return make_shooting_stepper(problem, options, initial,
                               make_bdf_alpha_rule(options.alpha, options.nodes));
}

}  // namespace rodlab::solvers::dynamics
