#include "staggered_shooting_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "rodlab/check.hpp"
#include "rodlab/lie/small_angle.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"
#include "../../common/cloned.hpp"
#include "../staggered_paths.hpp"
#include "../tangent_state.hpp"
#include "embedded_reference.hpp"
#include "shooting_newton.hpp"
#include "inverse_broyden.hpp"

namespace rodlab::solvers::dynamics {
namespace {

using lie::Matrix6;
namespace se3 = lie::se3;
namespace small = lie::small_angle;

/// The solve of sigma(xi) = dexp^T_{ds xi} lambda for a segment's strain (segment_twist) stops
/// when its twist ds xi moves by less than this times ds: 1e-13 relative to a unit stretch,
/// three decades below the shooting tolerance (1e-10 on the scaled tip residual) and six below
/// the finite-difference step of its Jacobian (1e-7). The former 4e-15 (a few units of
/// rounding) made the step 8 % dearer (bench_dynamics); the tip moves by 4e-13 m between the
/// two over 0.5 s of the cantilever (N = 20, dt = 10 ms).
constexpr double kStrainTol = 1e-13;
/// The same under multiple shooting (below the step bound, not the hot path): a few units of
/// rounding of ds xi, so that the strains' stops add no noise to the joins' residuals.
constexpr double kJoinStrainTol = 4e-15;
/// Fixed-point iterations at most; Newton takes over if one move is not below kSlowContraction
/// times the previous one.
constexpr int kFixedPointIterations = 30;
constexpr double kSlowContraction = 0.3;
constexpr int kNewtonIterations = 30;

class StaggeredShootingStepper final : public Stepper {
 public:
  StaggeredShootingStepper(const DynamicProblem& problem, const ShootingOptions& options,
                           const RestState& initial, std::unique_ptr<TimeRule> rule)
      : P_(problem), opt_(options), rule_(std::move(rule)), n_(options.nodes),
        ds_(problem.length() / (n_ - 1)),
        name_(std::string(rule_->name()) + " (grid " +
              std::string(shooting_grid_name(options.grid)) + ")"),
        tangent_(n_, problem.model()) {
    RODLAB_THROW_UNLESS(n_ >= 3, "{}: nodes must be >= 3", name_);
    problem.model().require_spans_on_grid(n_, rule_->name());
    RODLAB_THROW_UNLESS(
        static_cast<int>(initial.g.size()) == n_ && static_cast<int>(initial.xi.size()) == n_,
        "{}: expected {} initial nodes, got {}", name_, n_, initial.g.size());
    const auto& model = problem.model();
    g_ = initial.g;
    xi_.assign(n_ - 1, Vector6::Zero());
    if (problem.tip_clamped()) g_.back() = problem.tip_target();  // met to the statics' tolerance
    for (int j = 0; j + 1 < n_; ++j) {
      Vector6 x = (g_[j].inverse() * g_[j + 1]).log();
      if (problem.is_kirchhoff()) {
        // start on the constraint (as `variational` and `ida`): each segment keeps its
        // rotation and gets nu = nu*
        x.tail<3>() = ds_ * model.segment_xi_star(j, n_).tail<3>();
        g_[j + 1] = g_[j] * SE3::exp(x);
      }
      xi_[j] = x / ds_;
    }
    eta_.assign(n_, Vector6::Zero());
    eta_u_ = eta_hist_ = eta_;
    march_.assign(n_, MarchNode{Vector6::Zero(), Vector6::Zero(), SE3()});
    xi_u_ = xi_hist_ = xi_ref_ = xi_;
    clamped_ = problem.tip_clamped();
    entry_at_.assign(n_, 0);
    entries_ = problem.entry_nodes(n_);
    for (const auto& e : entries_) entry_at_[e.node] = 1;
    actuators_ = problem.has_actuators();
    const auto& K = problem.model().K_diag();
    const double EI = std::min(K[0], K[1]), L = problem.length();
    scale_ << EI / L, EI / L, EI / L, EI / (L * L), EI / (L * L), EI / (L * L);
    // first guess: the elastic wrench at the base of the initial state (its node strain there:
    // exact for a statics solution; the base segment's mid-point strain is O(ds) off it)
    const Vector6 x0 =
        K.cwiseProduct(initial.xi[0] - model.segment_xi_star(0, n_)).cwiseQuotient(scale_);
    m_ = problem.unknown_count();
    if (m_ == 0)
      plain_.start(x0);
    else
      setup_unknowns(x0);
    muscles_ = full_inertia_ = problem.has_muscles();
    if (muscles_) {
      // the full node inertia and, at the segments' midpoints, the embedded stiffness and
      // viscosity (as SemiDiscreteRod)
      inertia_ = problem.node_inertia(n_);
      K_emb_.resize(n_ - 1);
      V_emb_.resize(n_ - 1);
      Kt_full_.resize(n_ - 1);
      Kt_accel_.resize(n_ - 1);
      for (int j = 0; j + 1 < n_; ++j) {
        K_emb_[j] = problem.embedded_stiffness((j + 0.5) * ds_);
        V_emb_[j] = problem.embedded_viscosity((j + 0.5) * ds_);
      }
    }
    if (options.grid == ShootingGrid::corrected) use_corrected_grid();
    if (initial.equilibrium) settle();
  }

  /// The corrected grid (corrected_grid.hpp; the problem carries its model): a free tip's half
  /// cell as a rigid body, its full inertia and its weight at the centre of mass in the tip's
  /// balance, both in the energies (as SemiDiscreteRod).
  void use_corrected_grid() {
    require_corrected_grid(P_);  // Cosserat, no actuators
    const auto cell = TipHalfCell::of(P_, n_);
    if (!cell) return;  // a clamped tip
    tip_cell_ = std::make_shared<const TipHalfCell>(*cell);
    inertia_ = P_.node_inertia(n_);
    inertia_.back() = tip_cell_->M;
    full_inertia_ = true;
  }

  StepStatus step(double t, double dt) override { return take_step(t, dt, nullptr, nullptr); }

  // The tangent-linear step: the shooting's own converged equations differentiated (below);
  // muscles, length control and a clamped tip are not covered (their extra unknowns and clamp
  // rows would need their own rows): controllers difference whole steps there.
  bool has_step_linearisation() const override {
    return m_ == 0 && !muscles_ && !clamped_ && !tip_cell_;
  }

  StepStatus step_linearised(double t, double dt, Eigen::MatrixXd& A, Eigen::MatrixXd& B) override {
    if (!has_step_linearisation())
      throw unsupported(
          "step_linearised with muscles, length control, a clamped tip or the corrected grid");
    return take_step(t, dt, &A, &B);
  }

  void tip_jacobian(Eigen::MatrixXd& T) const override { tangent_.tip_jacobian(g_, xi_, ds_, T); }

 private:
  /// step(); with A and B also its linearisation (step_linearised), taken at the converged
  /// solution before the rule advances the state.
  StepStatus take_step(double t, double dt, Eigen::MatrixXd* A, Eigen::MatrixXd* B) {
    t_u_ = t + rule_->theta() * dt;
    c_ = rule_->coefficient(dt);
    end_ = rule_->end_coefficient();
    rule_->history(RuleField::strain, dt, xi_, xi_hist_);
    rule_->history(RuleField::velocity, dt, eta_, eta_hist_);
    t_end_ = t + dt;
    prepare_references();
    set_intervals(std::max(interval_count_for(dt), refined_intervals_));
    ShootingOutcome out = intervals() > 1 ? solve_intervals(dt) : solve_shots(steps_ >= 2);
    // A multiple-shooting step that stalls is retried with twice the intervals (for the rest of
    // the run), up to one per segment: shorter intervals amplify the rounding less.
    const int most = n_ - 1;
    while (!out.failure.empty() && intervals() > 1 && intervals() < most) {
      const int spent = out.shots;
      refined_intervals_ = std::min(2 * intervals(), most);
      set_intervals(refined_intervals_);
      out = solve_intervals(dt);
      out.shots += spent;
    }
    if (!out.failure.empty())
      return StepStatus::failed(rodlab::format(
          "{}: {} in the step from t = {:g} s (dt = {:g} s)", name_, out.failure, t, dt));
    if (inner_failed_)
      return StepStatus::failed(rodlab::format(
          "{}: a segment's strain did not converge at the solution in the step from t = {:g} s",
          name_, t));
    // the last shot was at the solution: its profiles, march and powers are current.
    if (A != nullptr) {
      linearise(dt, *A, *B);
      if (inner_failed_)
        return StepStatus::failed(rodlab::format(
            "{}: a segment's strain did not converge in the linearisation of the step from t = "
            "{:g} s", name_, t));
    }
    const double w0 = rule_->ledger_start_weight(), w1 = 1.0 - w0;
    ledger_.dissipated += dt * (w0 * dissipated_start_ + w1 * dissipated_u_);
    ledger_.work_in += dt * (w0 * work_start_ + w1 * work_u_);
    dissipated_start_ = dissipated_u_;
    work_start_ = work_u_;
    rule_->advance(RuleField::strain, dt, xi_u_, xi_hist_, xi_);
    rule_->advance(RuleField::velocity, dt, eta_u_, eta_hist_, eta_);
    // poses from the strains: exact on the staggered grid, g_(j+1) = g_j exp(ds xi_j)   (3.38)
    for (int j = 0; j + 1 < n_; ++j) g_[j + 1] = g_[j] * SE3::exp(ds_ * xi_[j]);
    ++steps_;
    StepStatus status;
    status.iterations = out.shots;
    return status;
  }

 public:

  Energy energy() const override {
    Energy e = staggered_energy(P_, g_, eta_, xi_, ds_,
                                full_inertia_ ? std::span<const lie::Matrix6>(inertia_)
                                              : std::span<const lie::Matrix6>());
    if (tip_cell_)  // the half cell's weight at its centre of mass (corrected_grid.hpp)
      e.gravity += tip_cell_->gravity_energy(P_.weight_per_length(), g_.back().rotation(), ds_);
    e.dissipated = ledger_.dissipated;
    e.work_in = ledger_.work_in;
    return e;
  }

  Vector3 tip_position() const override { return g_.back().translation(); }

  double max_det_deviation() const override { return dynamics::max_det_deviation(g_); }

  std::vector<result::CenterlineSample> centerline() const override {
    return staggered_centerline(g_, xi_, ds_);
  }
  std::vector<Vector6> velocities() const override { return eta_; }

  std::vector<ActuatorReading> actuator_readings() const override {
    std::vector<ActuatorReading> out(m_);
    for (int e = 0; e < m_; ++e) out[e] = {which_[e], paths_.length(e, xi_), F_[which_[e]]};
    return out;
  }

  std::unique_ptr<Stepper> clone() const override {
    return std::make_unique<StaggeredShootingStepper>(*this);
  }

  // Every member a step changes, scratch included (the test of bit-for-bit repetition,
  // tests/control/test_plant.cpp, catches one left out); the rest is fixed at construction.
  void assign_state(const Stepper& other) override {
    const auto& o = dynamic_cast<const StaggeredShootingStepper&>(other);
    RODLAB_THROW_UNLESS(&o.P_ == &P_ && o.n_ == n_, "{}: assign_state from another problem or grid",
                        name_);
    rule_ = o.rule_;
    Kt_ = o.Kt_, Kt_inv_ = o.Kt_inv_;
    Kt_matrix_ = o.Kt_matrix_;
    t_u_ = o.t_u_, t_end_ = o.t_end_, c_ = o.c_, end_ = o.end_;
    dissipated_start_ = o.dissipated_start_, work_start_ = o.work_start_;
    dissipated_u_ = o.dissipated_u_, work_u_ = o.work_u_;
    xi_ = o.xi_, eta_ = o.eta_, xi_u_ = o.xi_u_, eta_u_ = o.eta_u_;
    xi_hist_ = o.xi_hist_, eta_hist_ = o.eta_hist_, xi_ref_ = o.xi_ref_;
    g_ = o.g_;
    march_ = o.march_;
    inner_failed_ = o.inner_failed_;
    F_ = o.F_;
    plain_ = o.plain_;
    extended_ = o.extended_;
    multiple_ = o.multiple_;
    multiple_steps_ = o.multiple_steps_, refined_intervals_ = o.refined_intervals_;
    intervals_dt_ = o.intervals_dt_, intervals_at_dt_ = o.intervals_at_dt_;
    first_ = o.first_;
    interval_ref_ = o.interval_ref_;
    interval_end_ = o.interval_end_;
    interval_dissipated_ = o.interval_dissipated_, interval_work_ = o.interval_work_;
    eta_scale_ = o.eta_scale_, join_scale_ = o.join_scale_;
    unknown_ = o.unknown_;
    xi_end_ = o.xi_end_;
    Kt_full_ = o.Kt_full_, Kt_accel_ = o.Kt_accel_;
    steps_ = o.steps_;
    ledger_ = o.ledger_;
  }

  void warm_start_from(const Stepper& after) override {
    const auto& o = dynamic_cast<const StaggeredShootingStepper&>(after);
    plain_.warm_from(o.plain_);
    extended_.warm_from(o.extended_);
    multiple_.warm_from(o.multiple_);
  }

  int tangent_size() const override { return tangent_.size(); }
  void read_tangent(std::span<double> x) const override { tangent_.read(xi_, eta_, x); }
  // bdf-alpha: the rule's history (x_(i-1), x_dot_i) is not moved (docs/control.md).
  void add_tangent(std::span<const double> dx) override {
    tangent_.add(dx, xi_, eta_);
    for (int j = 0; j + 1 < n_; ++j) g_[j + 1] = g_[j] * SE3::exp(ds_ * xi_[j]);
  }

 private:
  /// The march's state at a node: its wrench before its entry loads, its velocity at t_u, its
  /// pose.
  struct MarchNode {
    Vector6 lambda_pre, eta;
    SE3 g;
  };

  /// Segment j and node j + 1 of the march (header): node j + 1's state from node j's, the
  /// segment's twist X = ds xi_j (solved from the guess X0), its viscous dissipation and input
  /// power added to `dissipated` and `work`. Reads the step's c_, t_u_, F_, histories and
  /// references and writes nothing else, so that the linearisation can evaluate it perturbed.
  MarchNode march_segment(int j, const MarchNode& in, const Vector6& X0, Vector6& X,
                          double& dissipated, double& work) {
    const Vector6& M = P_.model().M_diag();
    const Vector6& V = P_.model().V_diag();
    const double s_mid = (j + 0.5) * ds_;
    // segment j: sigma(xi_j) = dexp^T_{ds xi_j} lambda_j, lambda_j = lambda_pre - entry(xi_j)
    Vector6 lambda;
    X = segment_twist(j, in.lambda_pre, X0, lambda);
    const Vector6 xi = X / ds_;
    // its rate and the viscous and actuator power of the segment
    const Vector6 xi_dot = c_ * xi + xi_hist_[j];
    Vector6 xk_dot = xi_dot;
    if (P_.is_kirchhoff()) xk_dot.tail<3>().setZero();
    dissipated += ds_ * xk_dot.dot(V.cwiseProduct(xk_dot));
    if (muscles_) dissipated += ds_ * P_.embedded_dissipation(xk_dot, s_mid);
    if (actuators_) work += ds_ * P_.actuator_power(xi, xk_dot, s_mid, F_);
    if (entry_at_[j]) work += entry_loads(j, xi).dot(in.eta);  // at node j, with its eta
    // node j + 1: compatibility, then its balance
    const SE3 G = small::exp(X);
    // Ad_{G^-1} eta and Ad_G^T lambda with R^T formed once (se3.hpp)
    const auto [eta_moved, lambda_moved] =
        lie::SE3Adjoints(G).inverse_Ad_and_coAd_apply(in.eta, lambda);
    MarchNode out;
    out.eta = eta_moved +
              ds_ * small::dexp_apply(-X, xi_dot, small::bcd(X.head<3>().squaredNorm()));
    out.g = in.g * G;
    const Vector6& eta = out.eta;
    const int k = j + 1;
    const bool tip = k == n_ - 1;
    const double w = tip ? 0.5 * ds_ : ds_;
    const SO3& R = out.g.rotation();
    const Vector6 applied = P_.applied_load(R, t_u_), drag = P_.drag_load(eta);
    if (full_inertia_) {
      out.lambda_pre = lambda_moved + w * (full_inertia_balance(k, R, eta) - applied - drag);
    } else {
      const Vector6 Meta = M.cwiseProduct(eta);
      out.lambda_pre = lambda_moved +
                       w * (M.cwiseProduct(c_ * eta + eta_hist_[k]) - se3::coad_apply(eta, Meta) -
                            P_.gravity_load(R) - applied - drag);                  // (3.41), (3.8)
    }
    dissipated -= w * drag.dot(eta);
    work += w * applied.dot(eta);
    if (tip && entry_at_[k]) {
      // a cable entering at the tip: its load uses the last segment's strain (inside, the
      // segment that starts at the node, solved with it above), as the semi-discrete rod does
      const Vector6 entry = entry_loads(k, xi);
      work += entry.dot(eta);
      out.lambda_pre -= entry;
    }
    return out;
  }

  /// Node k's balance per unit length with its full inertia, less the applied load and drag
  /// (march_segment's): the muscles' weight on the node's cell (3.16)-(3.20); the corrected
  /// grid's tip: the half cell's inertia, its weight at its centre of mass. Out of line, as a
  /// rarely taken branch of march_segment.
  [[gnu::noinline]] Vector6 full_inertia_balance(int k, const SO3& R, const Vector6& eta) const {
    const double s = k * ds_;
    const Vector6 weight =
        muscles_ ? P_.embedded_weight(R, s - 0.5 * ds_, std::min(P_.length(), s + 0.5 * ds_), s)
                 : Vector6::Zero();
    const Vector6 gravity = k == n_ - 1 && tip_cell_
                                ? tip_cell_->at_centre_of_mass(P_.gravity_load(R))
                                : P_.gravity_load(R);
    return inertia_[k] * (c_ * eta + eta_hist_[k]) - se3::coad_apply(eta, inertia_[k] * eta) -
           gravity - weight;
  }

  /// The march from the base with lambda_0 = x * scale (header); returns the scaled tip
  /// residual lambda_(N-1) - W_tip, leaves the profiles at t_u and their powers behind. With
  /// actuator unknowns (x_e after the six: a muscle's Delta / L, a length-controlled actuator's
  /// F / (E I / L^2)) also their rows: a muscle's x_e - L_e(xi_u) / L (its length at t_u), a
  /// length-controlled actuator's (L_e(xi_end) - L_target(t + dt)) / L on the end-of-step strains
  /// xi_end = a xi_u + (1 - a) xi (TimeRule::end_coefficient); L_e: the segment sum
  /// (staggered_paths.hpp) of SemiDiscreteRod, so that the march solves ida's equations.
  template <class Vec>
  Vec shoot(const Vec& x) {
    // node 0: lambda_0 before its entry load (none at the base), at rest, at the base pose
    MarchNode node{x.template head<6>().cwiseProduct(scale_), Vector6::Zero(), P_.base()};
    if (m_ > 0) set_actuator_unknowns(x.data() + 6);
    double dissipated = 0.0, work = 0.0;
    eta_u_[0].setZero();
    march_[0] = node;
    // warm start from the last shot's strains unless that shot failed somewhere (then from the
    // state at the start of the step)
    const std::vector<Vector6>& guess = inner_failed_ ? xi_ : xi_u_;
    inner_failed_ = false;
    for (int j = 0; j + 1 < n_; ++j) {
      Vector6 X;
      node = march_segment(j, node, ds_ * guess[j], X, dissipated, work);
      const Vector6 xi = X / ds_;
      xi_u_[j] = xi;
      eta_u_[j + 1] = node.eta;
      march_[j + 1] = node;
    }
    dissipated_u_ = dissipated;
    Vec r;
    r.resize(6 + m_);
    r.template head<6>() = tip_residual(node, work, scale_);
    if (m_ > 0) actuator_rows(x.data() + 6, r.data() + 6);
    return r;
  }

  /// The actuator unknowns u (header: scaled) into the forces of the march.
  void set_actuator_unknowns(const double* u) {
    for (int e = 0; e < m_; ++e) unknown_[e] = u[e] * (is_muscle_[e] ? P_.length() : scale_[3]);
    F_ = P_.forces(t_u_, unknown_.data(), paths_.rest().data());
  }

  /// Their rows r (header) from the last march's strains.
  void actuator_rows(const double* u, double* r) {
    const double a = end_;
    for (int j = 0; j + 1 < n_; ++j) xi_end_[j] = a * xi_u_[j] + (1.0 - a) * xi_[j];
    const double L = P_.length();
    for (int e = 0; e < m_; ++e)
      r[e] = is_muscle_[e] ? u[e] - paths_.length(e, xi_u_) / L
                           : (paths_.length(e, xi_end_) -
                              P_.actuators()[which_[e]].target_length(t_end_, paths_.rest()[e])) /
                                 L;
  }

  /// The tip's rows of the residual from the march's last node and the work of the rest of the
  /// rod; sets work_u_. A free tip: the wrench mismatch over `scale` (single shooting's scale_,
  /// multiple shooting's join_scale_); a clamped one (no work): the
  /// end-of-step tip pose, exp(ds (a xi_u + (1 - a) xi)) chained from the base, on the clamp
  /// (lambda_pre is its reaction).
  Vector6 tip_residual(const MarchNode& tip, double work, const Vector6& scale) {
    if (clamped_) {
      work_u_ = work;
      const double a = end_;
      SE3 g_end = P_.base();
      for (int j = 0; j + 1 < n_; ++j)
        g_end = g_end * SE3::exp(ds_ * (a * xi_u_[j] + (1.0 - a) * xi_[j]));
      return P_.clamp_mismatch(g_end);
    }
    const Vector6 W = P_.tip_load(tip.g.rotation(), t_u_);
    work_u_ = work + W.dot(tip.eta);
    return (tip.lambda_pre - W).cwiseQuotient(scale);
  }

  /// Actuator unknowns: which actuators, their segment weights and grid rest lengths (at xi*),
  /// the first guess (muscles: the length of the initial state; forces: 0).
  void setup_unknowns(const Vector6& lambda0) {
    which_ = P_.unknown_actuators();
    is_muscle_.assign(m_, 0);
    unknown_.assign(m_, 0.0);
    paths_ = StaggeredPaths(P_, which_, n_);
    xi_end_.assign(n_ - 1, Vector6::Zero());
    for (int e = 0; e < m_; ++e)
      is_muscle_[e] = P_.actuators()[which_[e]].drive == ActuatorDrive::muscle;
    ShootingVectorU x0(6 + m_);
    x0.head<6>() = lambda0;
    for (int e = 0; e < m_; ++e) x0[6 + e] = is_muscle_[e] ? paths_.length(e, xi_) / P_.length() : 0.0;
    extended_.start(x0);
  }

  /// The constitutive references of a solve at (t_u, c) with the histories h set:
  /// sigma = K (xi - xi*) + V (c xi + h) + tendons = Kt (xi - xi_ref) + tendons   (3.10)
  void prepare_references() {
    const Vector6& V = P_.model().V_diag();
    Kt_ = P_.model().K_diag() + c_ * V;
    Kt_inv_ = Kt_.cwiseInverse();
    Kt_matrix_ = Kt_.asDiagonal();
    if (actuators_ && m_ == 0) F_ = P_.forces(t_u_);  // else set by each shot from its unknowns
    if (muscles_) {
      muscle_references();
    } else {
      for (int j = 0; j + 1 < n_; ++j) strain_reference(j);
    }
  }

  /// Segment j's xi_ref = (K xi*_j - V h_j) / Kt (no muscles; xi*_j its span's).
  void strain_reference(int j) {
    const auto& model = P_.model();
    xi_ref_[j] = (model.K_diag().cwiseProduct(model.segment_xi_star(j, n_)) -
                  model.V_diag().cwiseProduct(xi_hist_[j])).cwiseQuotient(Kt_);
  }

  // --- the tangent-linear step (step_linearised; docs/control.md "Linearisation") -----------
  // The step solves r(lambda_0; x, u) = 0 (the tip residual of the march) and returns
  // x+ = a xi_u + (1 - a) x (TimeRule::end_coefficient) from the march's profiles. By the
  // implicit function theorem dlambda_0 = -r_lambda^-1 (r_x dx + r_u du), and the profiles'
  // derivative is the march's partials plus their lambda_0 column times dlambda_0. The march's
  // partials are a tangent-linear march: node j's state z_j = (lambda_pre, eta, rho) (rho the
  // rotation, R exp(rho)) maps to z_(j+1) and xi_u,j through march_segment, whose local Jacobians
  // in z_j and in its parameters (h_j of the strain, h_(j+1) of the velocity, the forces F) are
  // central differences of that one segment at the converged solution; chained along the rod
  // they give every partial at once: 2 (27 + m) segment evaluations per segment, warm-started
  // from the solution, instead of a shooting solve per column. x enters through the histories
  // only, h = slope x (TimeRule::history_slope). Accurate to about 1e-9 relative (the local
  // steps below; tests/control/test_linearisation.cpp compares with whole-step differences).
  // Under multiple shooting the chain restarts at each interior interval start i from its own
  // unknowns z_i (its start's lambda_pre, eta and rho, scaled as the joins), the residual gains
  // the 15 jumps per join (the end's chained state minus z_i; positions enter no balance), and
  // the implicit function theorem solves for lambda_0 and every z_i at once: each chain stays
  // within an interval, whose amplification the bound keeps small.

  static constexpr int kNodeDim = 15;  ///< lambda_pre, eta, rho
  using NodeVector = Eigen::Matrix<double, kNodeDim, 1>;
  using LocalOut = Eigen::Matrix<double, kNodeDim + 6, 1>;  ///< z_(j+1), xi_u,j

  /// Segment j's map from node j's converged state moved by z: node j + 1's (lambda_pre, eta,
  /// rho) with rho relative to its converged rotation, and xi_u,j.
  LocalOut local_map(int j, const NodeVector& z) {
    MarchNode in = march_[j];
    in.lambda_pre += z.head<6>();
    in.eta += z.segment<6>(6);
    in.g = SE3(in.g.rotation() * SO3::exp(z.tail<3>()), in.g.translation());
    double dissipated = 0.0, work = 0.0;
    Vector6 X;
    const MarchNode out = march_segment(j, in, ds_ * xi_u_[j], X, dissipated, work);
    LocalOut y;
    y << out.lambda_pre, out.eta, (march_[j + 1].g.rotation().inverse() * out.g.rotation()).log(),
        X / ds_;
    return y;
  }

  /// The central difference of local_map in the parameter `value` (a member the march reads),
  /// moved by +-h; `changed` refreshes what depends on it.
  template <class Changed>
  LocalOut parameter_difference(int j, double& value, double h, Changed changed) {
    const double saved = value;
    value = saved + h;
    changed();
    const LocalOut plus = local_map(j, NodeVector::Zero());
    value = saved - h;
    changed();
    const LocalOut minus = local_map(j, NodeVector::Zero());
    value = saved;
    changed();
    return (plus - minus) / (2.0 * h);
  }

  void linearise(double dt, Eigen::MatrixXd& A, Eigen::MatrixXd& B) {
    const int ns = n_ - 1, nf = static_cast<int>(P_.actuators().size());
    // columns of the partials: the unknowns, lambda_0 (scaled) and under multiple shooting each
    // interior start's z_i (scaled), then x's strains and velocities (six per segment and per
    // node 1..N-1), the forces
    const int M = intervals(), n_x = 6 + kNodeDim * (M - 1);
    const int col_xi = n_x, col_eta = n_x + 6 * ns, col_F = n_x + 12 * ns, n_in = col_F + nf;
    const double slope = rule_->history_slope(dt), L = P_.length();
    // local steps: lambda relative to its scale (E I / L: a radian of bend), rho 1e-5 rad,
    // velocities 1e-4 rad/s and 1e-4 L/s, strains 1e-5 / L and 1e-7, forces 1e-5 E I / L^2
    NodeVector h_node;
    h_node << 1e-5 * scale_, Vector3::Constant(1e-4), Vector3::Constant(1e-4 * L),
        Vector3::Constant(1e-5);
    Vector6 h_strain, h_velocity;
    h_strain << Vector3::Constant(1e-5 / L), Vector3::Constant(1e-7);
    h_velocity = h_node.segment<6>(6);
    const double h_force = 1e-5 * scale_[3];
    lin_S_.setZero(kNodeDim, n_in);
    lin_S_.topLeftCorner<6, 6>() = scale_.asDiagonal();
    lin_D_.setZero(12 * ns, n_in);
    if (M > 1) lin_J_.setZero(n_x, n_in);  // the joins' rows, then the tip's
    NodeVector z_scale;             // z_i's units: the joins' scales
    z_scale << join_scale_, eta_scale_, Vector3::Ones();
    Eigen::Matrix<double, kNodeDim + 6, kNodeDim> Lz;
    lin_P_.resize(kNodeDim + 6, 12 + nf);
    for (int j = 0, next = 1; j < ns; ++j) {
      if (next < M && j == first_[next]) {  // interval `next` starts: its jump, its own chain
        const int row = kNodeDim * (next - 1), z = 6 + row;
        lin_J_.middleRows(row, kNodeDim) = lin_S_.array().colwise() / z_scale.array();
        lin_J_.block(row, z, kNodeDim, kNodeDim).diagonal().array() -= 1.0;
        lin_S_.setZero();
        lin_S_.block(0, z, kNodeDim, kNodeDim) = z_scale.asDiagonal();
        ++next;
      }
      for (int i = 0; i < kNodeDim; ++i) {
        NodeVector z = NodeVector::Zero();
        z[i] = h_node[i];
        Lz.col(i) = (local_map(j, z) - local_map(j, -z)) / (2.0 * h_node[i]);
      }
      for (int i = 0; i < 6; ++i) {
        lin_P_.col(i) = slope * parameter_difference(j, xi_hist_[j][i], std::abs(slope) * h_strain[i],
                                                     [&] { strain_reference(j); });
        lin_P_.col(6 + i) = slope * parameter_difference(j, eta_hist_[j + 1][i],
                                                         std::abs(slope) * h_velocity[i], [] {});
      }
      for (int e = 0; e < nf; ++e)
        lin_P_.col(12 + e) = P_.actuators()[e].force_per_input *
                             parameter_difference(j, F_[e], h_force, [] {});
      lin_Y_.noalias() = Lz * lin_S_;
      lin_Y_.middleCols(col_xi + 6 * j, 6) += lin_P_.leftCols(6);
      lin_Y_.middleCols(col_eta + 6 * j, 6) += lin_P_.middleCols(6, 6);
      lin_Y_.rightCols(nf) += lin_P_.rightCols(nf);
      lin_S_ = lin_Y_.topRows(kNodeDim);
      lin_D_.middleRows(6 * j, 6) = lin_Y_.bottomRows(6);                 // xi_u,j
      lin_D_.middleRows(6 * ns + 6 * j, 6) = lin_Y_.middleRows(6, 6);     // eta_u,(j+1)
    }
    // the tip residual (lambda_pre - W(R exp(rho))) / scale and the implicit function theorem
    Eigen::Matrix<double, 6, 3> W_rho;
    const SO3& R_tip = march_[ns].g.rotation();
    for (int i = 0; i < 3; ++i) {
      const Vector3 d = Vector3::Unit(i) * 1e-5;
      W_rho.col(i) =
          (P_.tip_load(R_tip * SO3::exp(d), t_u_) - P_.tip_load(R_tip * SO3::exp(-d), t_u_)) / 2e-5;
    }
    // (multiple shooting: the tip's rows scaled as its residual's, E A for the axial force)
    const Vector6& tip_scale = M > 1 ? join_scale_ : scale_;
    lin_R_ = (lin_S_.topRows(6) - W_rho * lin_S_.bottomRows(3)).array().colwise() /
             tip_scale.array();
    if (M == 1) {
      const Eigen::PartialPivLU<Matrix6> r_lambda(Matrix6(lin_R_.leftCols(6)));
      lin_L_ = -r_lambda.solve(lin_R_.rightCols(n_in - 6));
    } else {
      lin_J_.bottomRows(6) = lin_R_;
      lin_L_ = -lin_J_.leftCols(n_x).partialPivLu().solve(lin_J_.rightCols(n_in - n_x));
    }
    lin_Y_ = lin_D_.rightCols(n_in - n_x);
    lin_Y_.noalias() += lin_D_.leftCols(n_x) * lin_L_;
    // x+ = a u + (1 - a) x in the tangent coordinates
    const double a = end_;
    const int n = tangent_.size();
    A.resize(n, n);
    B.resize(n, nf);
    for (int r = 0; r < n; ++r) {
      const int fr = tangent_.full_index(r);
      for (int c = 0; c < n; ++c) {
        const int fc = tangent_.full_index(c);
        A(r, c) = a * lin_Y_(fr, fc) + (fr == fc ? 1.0 - a : 0.0);
      }
      for (int e = 0; e < nf; ++e) B(r, e) = a * lin_Y_(fr, 12 * ns + e);
    }
  }

  /// Newton on the shooting unknowns (shooting_newton.hpp): lambda_0, and the actuator unknowns.
  ShootingOutcome solve_shots(bool extrapolate) {
    return m_ == 0 ? plain_.solve([this](const Vector6& x) { return shoot<Vector6>(x); }, c_,
                                  extrapolate, opt_.tol, opt_.max_iterations)
                   : extended_.solve(
                         [this](const ShootingVectorU& x) { return shoot<ShootingVectorU>(x); },
                         c_, extrapolate, opt_.tol, opt_.max_iterations);
  }

  // --- multiple shooting (docs/dynamics.md "Multiple shooting below the bound") ------------
  // Beyond single shooting's lower step bound the march amplifies an error at the base by
  // e^kappa > tol / eps (step_bound.hpp). The rod is then cut at nodes first_[1..M-1] into M
  // intervals of exponent about kappa / M; each interval is marched from its own start state
  // (the unknowns: lambda_0 as in single shooting, per interior start node its lambda_pre, eta
  // and pose, then the actuator unknowns), and the residual is the 18 jumps where an interval's
  // march ends on the next one's start, the tip's rows, then the actuators' rows (a staircase).
  // Same equations, same solution as single shooting (to tol); the Jacobian by intervals,
  // sparse (a column re-marches its interval only), Broyden between as for single shooting but
  // on the Jacobian's inverse (inverse_broyden.hpp: dense for few unknowns, KLU's factors and
  // the updates in product form for many), and a stall on the
  // residual's rounding floor accepted (ShootingNewton::accept_rounding_floor). The joins' (and
  // the free tip's) axial force is scaled by E A, not E I / L^2: at small dt the axial rows
  // cannot be resolved to 1e-10 E I / L^2 (5e-15 N on the Table 2.1 rod, an axial strain of
  // 6e-17) and Newton stalled there. Not the hot path: dynamic-size vectors.

  static constexpr int kJoin = 18;  ///< unknowns (and residual rows) per interior interval start

  int intervals() const { return first_.empty() ? 1 : static_cast<int>(first_.size()) - 1; }

  /// The intervals a step of dt takes (step_bound.hpp; kept for the last dt: the step's hot path
  /// pays no pow).
  int interval_count_for(double dt) {
    if (opt_.grid == ShootingGrid::euler) return 1;
    if (opt_.intervals > 0) return std::min(opt_.intervals, n_ - 1);
    if (dt != intervals_dt_) {
      intervals_dt_ = dt;
      intervals_at_dt_ =
          shooting_intervals(single_shooting_exponent(P_, dt), opt_.grid, opt_.tol, n_ - 1);
    }
    return intervals_at_dt_;
  }

  /// M intervals of (nearly) equal numbers of segments; a change restarts multiple_ (its
  /// unknowns change).
  void set_intervals(int M) {
    if (M == intervals()) return;
    multiple_steps_ = 0;
    if (M == 1) {
      first_.clear();
      return;
    }
    first_.resize(M + 1);
    for (int i = 0; i <= M; ++i)
      first_[i] = static_cast<int>(std::lround(static_cast<double>(i) * (n_ - 1) / M));
    interval_ref_.assign(M, SE3());
    interval_end_.assign(M, MarchNode{Vector6::Zero(), Vector6::Zero(), SE3()});
    interval_dissipated_.assign(M, 0.0);
    interval_work_.assign(M, 0.0);
  }

  /// Interval i's start node from the unknowns: i = 0 the base with lambda_0 = x_0..5 scale; else
  /// lambda_pre = u_0..5 scale, eta = u_6..11 eta_scale, the pose at its rotation and position at
  /// the step's start moved by exp(u_12..14) and L u_15..17.
  MarchNode interval_start(int i, const Eigen::VectorXd& x) const {
    if (i == 0) return {x.head<6>().cwiseProduct(scale_), Vector6::Zero(), P_.base()};
    const auto u = x.segment<kJoin>(start_at(i));
    const SE3& ref = interval_ref_[i];
    return {u.head<6>().cwiseProduct(join_scale_), u.segment<6>(6).cwiseProduct(eta_scale_),
            SE3(ref.rotation() * SO3::exp(u.segment<3>(12)),
                ref.translation() + P_.length() * u.tail<3>())};
  }

  /// Marches interval i from its start (the strains from `guess`): profiles, march_ and eta_u_
  /// on its nodes but its last (the next interval's start; the tip for the last interval), its
  /// end node and powers.
  void march_interval(int i, const Eigen::VectorXd& x, const std::vector<Vector6>& guess) {
    MarchNode node = interval_start(i, x);
    const int first = first_[i], end = first_[i + 1];
    march_[first] = node;
    eta_u_[first] = node.eta;
    double dissipated = 0.0, work = 0.0;
    for (int j = first; j < end; ++j) {
      Vector6 X;
      node = march_segment(j, node, ds_ * guess[j], X, dissipated, work);
      xi_u_[j] = X / ds_;
      if (j + 1 < end || j + 2 == n_) {
        eta_u_[j + 1] = node.eta;
        march_[j + 1] = node;
      }
    }
    interval_end_[i] = node;
    interval_dissipated_[i] = dissipated;
    interval_work_[i] = work;
  }

  /// The residual from the intervals' last marches, its rows in staircase order (interval
  /// i's unknowns reach rows of blocks i - 1 and i alone, so that the LU of the Jacobian in its
  /// natural order fills only inside that staircase): per interior start i the jump of the
  /// march's end on it (join_row), scaled as its unknowns (the rotation as log(R_start^T R_end)),
  /// then the tip's rows (tip_residual), then the actuators'. Sets the step's powers.
  Eigen::VectorXd interval_residual(const Eigen::VectorXd& x) {
    const int M = intervals();
    Eigen::VectorXd r(x.size());
    for (int i = 1; i < M; ++i) r.segment<kJoin>(join_row(i)) = jump(i, x);
    r.segment<6>(tip_row()) = interval_tip(x, r.data() + actuator_at());
    return r;
  }

  /// The 18 rows of the jump at interior start i: the end of interval i - 1's last march on
  /// the start the unknowns x give.
  Eigen::Matrix<double, kJoin, 1> jump(int i, const Eigen::VectorXd& x) const {
    const MarchNode& end = interval_end_[i - 1];
    const MarchNode start = interval_start(i, x);
    Eigen::Matrix<double, kJoin, 1> rows;
    rows << (end.lambda_pre - start.lambda_pre).cwiseQuotient(join_scale_),
        (end.eta - start.eta).cwiseQuotient(eta_scale_),
        (start.g.rotation().inverse() * end.g.rotation()).log(),
        (end.g.translation() - start.g.translation()) / P_.length();
    return rows;
  }

  /// The tip's rows from the last marches, the actuators' rows into `actuator_rows_out`, and
  /// the step's powers.
  Vector6 interval_tip(const Eigen::VectorXd& x, double* actuator_rows_out) {
    double dissipated = 0.0, work = 0.0;
    for (int i = 0; i < intervals(); ++i) {
      dissipated += interval_dissipated_[i];
      work += interval_work_[i];
    }
    dissipated_u_ = dissipated;
    if (m_ > 0) actuator_rows(x.data() + actuator_at(), actuator_rows_out);
    return tip_residual(interval_end_.back(), work, join_scale_);
  }

  Eigen::VectorXd shoot_intervals(const Eigen::VectorXd& x) {
    // warm start as shoot()
    const std::vector<Vector6>& guess = inner_failed_ ? xi_ : xi_u_;
    inner_failed_ = false;
    if (m_ > 0) set_actuator_unknowns(x.data() + actuator_at());
    for (int i = 0; i < intervals(); ++i) march_interval(i, x, guess);
    return interval_residual(x);
  }

  /// Interval i's first unknown: lambda_0 (i = 0) or its start's 18.
  static int start_at(int i) { return i == 0 ? 0 : 6 + kJoin * (i - 1); }
  static int start_count(int i) { return i == 0 ? 6 : kJoin; }
  /// The residual's rows: the jump at interior start i, the tip's, the actuators' (which are
  /// also where the actuator unknowns start).
  static int join_row(int i) { return kJoin * (i - 1); }
  int tip_row() const { return kJoin * (intervals() - 1); }
  /// The row blocks interval i's unknowns move (the Jacobian's pattern and its columns both
  /// read them): the jump at its start (i >= 1), the jump at its end (all but the last), the
  /// tip's rows (the last interval's, and a clamped tip's: its pose chains every interval's
  /// strains); the actuators' rows are moved by every unknown.
  struct Reach {
    bool start_jump, end_jump, tip;
  };
  Reach reach(int i) const {
    return {i >= 1, i + 1 < intervals(), i + 1 == intervals() || clamped_};
  }
  int actuator_at() const { return 6 + kJoin * (intervals() - 1); }

  /// Forward differences by intervals: an unknown of interval i moves its march and the jump at
  /// its start only (and the next jump or the tip, a clamped tip's pose and the actuators'
  /// rows), so its column re-marches interval i alone and evaluates those rows alone (an
  /// actuator unknown's column re-marches every interval), the others staying at x (Newton may
  /// ask at an iterate after a shot elsewhere: x is shot first); the profiles of x are
  /// restored. The shots counted: segments marched / segments of the rod.
  void interval_jacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& r,
                         InverseBroyden::Jacobian& J, int& shots) {
    if (J.rows() != x.size()) J = interval_pattern();
    shoot_intervals(x);
    const bool failed = inner_failed_;
    const int M = intervals();
    long segments = n_ - 1;
    Eigen::VectorXd xp = x;
    column_.resize(x.size());  // the moved rows of a column (its pattern's rows)
    auto set_column = [&](int k, double h) {
      for (InverseBroyden::Jacobian::InnerIterator it(J, k); it; ++it)
        it.valueRef() = (column_[it.row()] - r[it.row()]) / h;
    };
    for (int i = 0; i < M; ++i) {
      const Reach reached = reach(i);
      for (int k = start_at(i); k < start_at(i) + start_count(i); ++k) {
        const double h = kShootingFdStep * std::max(1.0, std::abs(x[k]));
        xp[k] = x[k] + h;
        march_interval(i, xp, xi_u_);
        if (reached.start_jump) column_.segment<kJoin>(join_row(i)) = jump(i, xp);
        if (reached.end_jump) column_.segment<kJoin>(join_row(i + 1)) = jump(i + 1, xp);
        if (reached.tip || m_ > 0)  // interval_tip sets the actuators' rows too
          column_.segment<6>(tip_row()) = interval_tip(xp, column_.data() + actuator_at());
        set_column(k, h);
        xp[k] = x[k];
      }
      march_interval(i, x, xi_u_);
      segments += static_cast<long>(start_count(i) + 1) * (first_[i + 1] - first_[i]);
    }
    // an actuator unknown moves every interval's march
    for (int k = actuator_at(); k < actuator_at() + m_; ++k) {
      const double h = kShootingFdStep * std::max(1.0, std::abs(x[k]));
      xp[k] = x[k] + h;
      column_ = shoot_intervals(xp);
      set_column(k, h);
      xp[k] = x[k];
      segments += n_ - 1;
    }
    if (m_ > 0) {  // every interval moved: shoot x again
      shoot_intervals(x);
      segments += n_ - 1;
    } else {
      interval_residual(x);  // the step's powers at x
    }
    inner_failed_ = failed;
    shots += static_cast<int>((segments + n_ - 2) / (n_ - 1));
  }

  /// The Jacobian's structure: interval i's unknowns reach the jump at its start (i >= 1) and
  /// the rows its march's end reaches, the next jump or (the last interval) the tip's; a clamped
  /// tip's rows (its pose chained through every strain) and the actuators' rows are in every
  /// column, and an actuator unknown's column is dense.
  InverseBroyden::Jacobian interval_pattern() const {
    const int M = intervals(), n = actuator_at() + m_;
    std::vector<Eigen::Triplet<double>> entries;
    auto rows = [&entries](int first, int count, int column) {
      for (int row = first; row < first + count; ++row) entries.emplace_back(row, column, 1.0);
    };
    for (int i = 0; i < M; ++i) {
      const Reach reached = reach(i);
      for (int k = start_at(i); k < start_at(i) + start_count(i); ++k) {
        if (reached.start_jump) rows(join_row(i), kJoin, k);
        if (reached.end_jump) rows(join_row(i + 1), kJoin, k);
        if (reached.tip) rows(tip_row(), 6, k);
        rows(actuator_at(), m_, k);
      }
    }
    for (int k = actuator_at(); k < n; ++k) rows(0, n, k);
    InverseBroyden::Jacobian J(n, n);
    J.setFromTriplets(entries.begin(), entries.end());
    J.makeCompressed();
    return J;
  }

  /// The first unknowns of multiple shooting, from the state at the step's start: each start
  /// node's lambda_pre the elastic stress of its segment (as the constructor's lambda_0), its
  /// velocity, its pose; later steps predict from the last two solutions (these coordinates are
  /// relative to the step's start, so a steady motion extrapolates exactly).
  Eigen::VectorXd interval_guess() const {
    const int M = intervals();
    const auto& K = P_.model().K_diag();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(6 + kJoin * (M - 1) + m_);
    for (int i = 0; i < M; ++i) {
      const int b = first_[i];
      const Vector6 lambda = K.cwiseProduct(xi_[b] - P_.model().segment_xi_star(b, n_));
      if (i == 0) {
        x.head<6>() = lambda.cwiseQuotient(scale_);
      } else {
        x.segment<6>(start_at(i)) = lambda.cwiseQuotient(join_scale_);
        x.segment<6>(start_at(i) + 6) = eta_[b].cwiseQuotient(eta_scale_);
      }
    }
    // a muscle: its length now; a length-controlled force: the last one
    for (int e = 0; e < m_; ++e)
      x[actuator_at() + e] = is_muscle_[e] ? paths_.length(e, xi_) / P_.length()
                                           : unknown_[e] / scale_[3];
    return x;
  }

  ShootingOutcome solve_intervals(double dt) {
    const double L = P_.length();
    eta_scale_ << Vector3::Constant(1.0 / dt), Vector3::Constant(L / dt);
    join_scale_ = scale_;
    join_scale_[5] = P_.model().K_diag()[5];
    for (int i = 1; i < intervals(); ++i) interval_ref_[i] = g_[first_[i]];
    if (multiple_steps_ == 0) {
      multiple_.start(interval_guess());
      multiple_.accept_rounding_floor(true);
    }
    multiple_.name(rodlab::format("multiple shooting ({} intervals)", intervals()));
    ShootingOutcome out = multiple_.solve(
        [this](const Eigen::VectorXd& x) { return shoot_intervals(x); },
        [this](const Eigen::VectorXd& x, const Eigen::VectorXd& r, InverseBroyden::Jacobian& J,
               int& shots) { interval_jacobian(x, r, J, shots); },
        c_, multiple_steps_ >= 2, opt_.tol, opt_.max_iterations);
    ++multiple_steps_;
    return out;
  }

  /// `initial: static`: the given state is a statics solution sampled from another grid
  /// (rkmk-rk4, 4x finer), O(ds^2) off this grid's equilibrium; re-solve the equilibrium here
  /// with the march at c = 0 (no inertia, no viscous stress: the staggered grid's statics) under
  /// the loads at t = 0. The rod then starts at rest in equilibrium (no spurious transient), and
  /// the first step's Newton starts from its base wrench: single shooting from the sampled
  /// state failed the first step of scenes/fixed-ends.yaml at N < 20 (residual 0.04-0.3).
  /// Without convergence the given state stays.
  void settle() {
    t_u_ = t_end_ = 0.0;
    c_ = 0.0;
    end_ = 1.0;
    std::fill(xi_hist_.begin(), xi_hist_.end(), Vector6::Zero());
    std::fill(eta_hist_.begin(), eta_hist_.end(), Vector6::Zero());
    prepare_references();
    const ShootingOutcome out = solve_shots(false);
    if (!out.failure.empty() || inner_failed_) return;
    xi_ = xi_u_;
    for (int j = 0; j + 1 < n_; ++j) g_[j + 1] = g_[j] * SE3::exp(ds_ * xi_[j]);
    if (clamped_) g_.back() = P_.tip_target();  // on it to the shooting tolerance
  }

  /// Muscles: every segment's full Kt and xi_ref (embedded_reference.hpp) and the operator of
  /// segment_twist's acceleration, Kt^-1 (Kirchhoff: the moment rows' block, nu = nu* fixed),
  /// factorised once per step.
  void muscle_references() {
    for (int j = 0; j + 1 < n_; ++j) {
      embedded_reference(P_, P_.model().segment_xi_star(j, n_), K_emb_[j], V_emb_[j], c_,
                         xi_hist_[j], Kt_full_[j], xi_ref_[j]);
      if (P_.is_kirchhoff()) {
        Kt_accel_[j].setZero();
        Kt_accel_[j].topLeftCorner<3, 3>() = Kt_full_[j].topLeftCorner<3, 3>().inverse();
      } else {
        Kt_accel_[j] = Kt_full_[j].inverse();
      }
    }
  }

  /// Segment j's twist X = ds xi_j from the wrench lambda_pre of its first node before the entry
  /// loads there: the fixed point X = Phi(X) = ds solve_strain(dexp^T_X (lambda_pre -
  /// entry(X / ds))) (Kt, xi_ref, tendons and Kirchhoff's nu = nu* inside solve_strain), from
  /// the guess X0, accelerated by Phi's first-order derivative (below): the iteration then
  /// contracts with ratio ~ (ds |lambda| / (2 E I))^2 + |X| ds |lambda| / (2 E I); where it does not
  /// (far from the solution, in early Newton iterates of the shooting), Newton with a
  /// finite-difference Jacobian of Phi takes over. A failure leaves inner_failed_ set. Out of
  /// line: inlined into march_segment, GCC put SE3's product out of line and the step lost 5 %.
  /// Flattened (everything it calls inlined): when multiple shooting's sparse Newton joined this
  /// file, GCC stopped inlining Eigen's ds_ * Vector6 into it, and the step lost 25 %.
  [[gnu::noinline, gnu::flatten]] Vector6 segment_twist(int j, const Vector6& lambda_pre,
                                                        const Vector6& X0, Vector6& lambda) {
    const double s_mid = (j + 0.5) * ds_;
    auto phi = [&](const Vector6& X, Vector6& lam) {
      lam = entry_at_[j] ? Vector6(lambda_pre - entry_loads(j, X / ds_)) : lambda_pre;
      const Vector6 sigma = small::dexp_transpose_apply(X, lam, small::bcd(X.head<3>().squaredNorm()));
      if (!actuators_) return Vector6(ds_ * P_.solve_elastic_strain(Kt_inv_, xi_ref_[j], sigma));
      const Vector6 guess = X / ds_;  // the last iterate: Newton's steps drop from 3-5 to 1-2
      return Vector6(ds_ * P_.solve_strain(muscles_ ? Kt_full_[j] : Kt_matrix_, xi_ref_[j], sigma,
                                           s_mid, F_, &guess));
    };
    const double tol = intervals() > 1
                           ? kJoinStrainTol * std::max(ds_, X0.lpNorm<Eigen::Infinity>())
                           : kStrainTol * ds_;
    Vector6 X = X0;
    double previous = std::numeric_limits<double>::infinity();
    const bool kirchhoff = P_.is_kirchhoff();
    for (int it = 0; it < kFixedPointIterations; ++it) {
      const Vector6 next = phi(X, lambda);
      const Vector6 d = next - X;
      const double move = d.lpNorm<Eigen::Infinity>();
      if (move <= tol) return next;
      if (!(move <= kSlowContraction * previous) && it >= 2) {
        X = next;
        break;
      }
      const double ratio = move / previous;  // the observed contraction (0 on the first pass)
      previous = move;
      // Accelerated: X = Phi(X) + E d with E = ds Kt^-1 dsigma/dX the first-order part of Phi's
      // derivative (dexp^T_X lambda = lambda + (1/2) [m x w + f x v; f x w] + O(X^2), lambda =
      // [m; f]): the contraction ratio drops from ~ |E| to ~ |E|^2 + |X| |E|. Fixed points are
      // Phi's (the correction vanishes with d).
      const Vector3 m = lambda.head<3>(), f = lambda.tail<3>();
      const Vector3 dw = d.head<3>(), dv = d.tail<3>();
      Vector6 Ed;
      Ed << m.cross(dw) + f.cross(dv), f.cross(dw);
      if (muscles_) {
        Ed = (0.5 * ds_) * (Kt_accel_[j] * Ed);  // the full Kt (embedded_reference.hpp)
      } else {
        Ed = (0.5 * ds_) * Ed.cwiseProduct(Kt_inv_);
        if (kirchhoff) Ed.tail<3>().setZero();  // nu = nu* inside Phi
      }
      X = next + Ed;
      // the next move would be about ratio * move: below tol, X is converged without another
      // evaluation of Phi (saves one of the ~4 passes per segment and shot)
      if (it >= 1 && ratio * move <= tol) return X;
    }
    Vector6 lam_unused;
    for (int it = 0; it < kNewtonIterations; ++it) {
      const Vector6 r = X - phi(X, lambda);
      Matrix6 J;
      const double h = 1e-7 * std::max(ds_, X.lpNorm<Eigen::Infinity>());
      for (int k = 0; k < 6; ++k) {
        Vector6 Xp = X;
        Xp[k] += h;
        J.col(k) = ((Xp - phi(Xp, lam_unused)) - r) / h;
      }
      const Vector6 dX = -J.partialPivLu().solve(r);
      X += dX;
      if (!X.allFinite()) break;
      if (dX.lpNorm<Eigen::Infinity>() <= tol) {
        X = phi(X, lambda);
        return X;
      }
    }
    inner_failed_ = true;
    return X.allFinite() ? X : Vector6::Constant(std::nan(""));
  }

  /// The loads of the cables that enter at node k, with the strain xi of its segment.
  Vector6 entry_loads(int k, const Vector6& xi) const {
    Vector6 sum = Vector6::Zero();
    for (const auto& e : entries_)
      if (e.node == k) sum += actuators_ ? P_.entry_load(e.s, xi, F_) : P_.entry_load(e.s, xi, t_u_);
    return sum;
  }

  const DynamicProblem& P_;
  ShootingOptions opt_;
  Cloned<TimeRule> rule_;
  int n_;
  double ds_;
  std::string name_;
  StaggeredTangent tangent_;
  Vector6 scale_, Kt_, Kt_inv_;
  Matrix6 Kt_matrix_;
  double t_u_ = 0.0, t_end_ = 0.0, c_ = 0.0;
  double end_ = 1.0;  ///< a of the end-of-step strains a xi_u + (1 - a) xi (1 while settling)
  double dissipated_start_ = 0.0, work_start_ = 0.0, dissipated_u_ = 0.0, work_u_ = 0.0;
  std::vector<Vector6> xi_, eta_, xi_u_, eta_u_, xi_hist_, eta_hist_, xi_ref_;
  std::vector<MarchNode> march_;  ///< the last shot's march at the nodes
  Eigen::MatrixXd lin_S_, lin_D_, lin_Y_, lin_P_, lin_R_, lin_L_, lin_J_;  ///< linearise()'s
  std::vector<SE3> g_;
  std::vector<DynamicProblem::EntryNode> entries_;
  std::vector<char> entry_at_;
  bool actuators_ = false;
  bool inner_failed_ = false;  ///< a segment's strain did not converge in the last shot
  bool clamped_ = false;       ///< tip.clamped: the residual is the end-of-step pose mismatch
  DynamicProblem::Forces F_{};
  ShootingNewton<Vector6, Matrix6> plain_;  ///< lambda_0 only
  ShootingNewton<ShootingVectorU, ShootingMatrixU> extended_;  ///< and the actuator unknowns
  // Multiple shooting (below single shooting's step bound): the intervals' first nodes (and
  // n_ - 1), the poses at their starts at the step's start, their last marches' end nodes and
  // powers, the velocity unknowns' scale, Newton's state and its steps taken.
  std::vector<int> first_;
  std::vector<SE3> interval_ref_;
  std::vector<MarchNode> interval_end_;
  std::vector<double> interval_dissipated_, interval_work_;
  Vector6 eta_scale_ = Vector6::Ones(), join_scale_ = Vector6::Ones();
  Eigen::VectorXd column_;  ///< interval_jacobian's scratch
  ShootingNewton<Eigen::VectorXd, InverseBroyden::Jacobian, InverseBroyden> multiple_;
  long multiple_steps_ = 0;
  int refined_intervals_ = 1;  ///< at least this many intervals after a stalled step
  double intervals_dt_ = 0.0;  ///< interval_count_for's last dt and its intervals
  int intervals_at_dt_ = 1;
  // Actuator unknowns (muscle lengths, length-controlled forces) and embedded muscles.
  int m_ = 0;
  bool muscles_ = false;
  std::vector<int> which_;
  std::vector<char> is_muscle_;
  std::vector<double> unknown_;
  StaggeredPaths paths_;  ///< the unknowns' path lengths and rest lengths
  std::vector<Vector6> xi_end_;
  std::vector<Matrix6> inertia_, K_emb_, V_emb_, Kt_full_, Kt_accel_;
  // Node inertia densities other than the rod's diagonal M (full_inertia_): muscles, or the
  // corrected grid's free tip (tip_cell_).
  bool full_inertia_ = false;
  std::shared_ptr<const TipHalfCell> tip_cell_;  // shared by the stepper's copies (snapshots)
  long steps_ = 0;
  Energy ledger_;
};

}  // namespace

std::unique_ptr<Stepper> make_staggered_shooting_stepper(const DynamicProblem& problem,
                                                         const ShootingOptions& options,
                                                         const RestState& initial,
                                                         std::unique_ptr<TimeRule> rule) {
  return std::make_unique<StaggeredShootingStepper>(problem, options, initial, std::move(rule));
}

}  // namespace rodlab::solvers::dynamics
