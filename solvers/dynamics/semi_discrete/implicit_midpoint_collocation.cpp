#include "rodlab/solvers/dynamics/semi_discrete/implicit_midpoint_collocation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/kinsol_solver.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "../tangent_state.hpp"

namespace rodlab::solvers::dynamics {
namespace {

/// Levels of step halving after a failed solve (down to dt / 2^kMaxSplits).
constexpr int kMaxSplits = 6;

using Vector = Eigen::VectorXd;
using ConstRef = Eigen::Ref<const Vector>;

/// Rounding floor of the scaled residual: f is evaluated to about eps |p| omega_max^2 (elastic
/// forces from differences of positions over ds, divided by the node mass), i.e. eps
/// (omega_max / omega_1)^2 in the scaled norm; a safety factor on top.
constexpr double kRoundingFloor = 2.0;
/// A solve needing more iterations than this, and kSlowMargin more than the last solve that
/// started from a fresh Jacobian, refreshes the Jacobian for the next step: at large steps
/// (dt auto, 10-13 iterations even from a fresh Jacobian) the absolute count alone refreshed
/// it at every step, one finite-difference Jacobian (39 residuals) per step for no fewer
/// iterations (bench_dynamics, docs/dynamics.md).
constexpr int kSlowSolve = 8;
constexpr int kSlowMargin = 3;
/// Iterations of full modified-Newton steps before a step retries with KINSOL's line search
/// (the slowest converging steps of the benchmarks take about 11).
constexpr int kChordIterations = 20;

class ImplicitMidpointCollocation final : public ImplicitMidpointCollocationStepper {
 public:
  ImplicitMidpointCollocation(const DynamicProblem& problem,
                              const ImplicitMidpointCollocationOptions& options,
                              std::span<const SE3> g0)
      : rod_(problem, options.nodes, "implicit-midpoint-collocation", true,
             options.corrected_grid),
        kinsol_(constrained() ? rod_.constrained_pattern() : rod_.pattern(false),
                KluReuse::factors, KluOrder::fill_reducing,
                constrained() ? NewtonLinearSolver::klu : options.linear_solver),
        tangent_(options.nodes, problem.model()) {
    if (!(options.tol > 0.0))
      throw std::invalid_argument("implicit-midpoint-collocation: tol must be > 0");
    RODLAB_THROW_UNLESS(options.max_iterations >= 1 && options.max_setup_calls >= 1 &&
                            options.jacobian_max_age >= 0,
                        "implicit-midpoint-collocation: max_iterations and max_setup_calls must "
                        "be >= 1 and jacobian_max_age >= 0, got {}, {}, {}",
                        options.max_iterations, options.max_setup_calls, options.jacobian_max_age);
    n_ = rod_.node_size();
    nc_ = rod_.constraint_size();
    m_ = rod_.unknown_size();
    max_age_ = options.jacobian_max_age;
    max_setup_calls_ = options.max_setup_calls;
    max_iterations_ = options.max_iterations;
    y_ = rod_.rest_state(g0);
    ym_ = y1_ = y_.head(n_);
    z_ = z0_ = trial_ = F_ = Vector::Zero(n_ + nc_ + m_);
    forces_ = Vector::Zero(nc_);
    x_ = rod_.initial_unknowns(y_);
    k1_ = k2_ = Vector::Zero(n_);
    f_ = Vector::Zero(rod_.size());
    w_ = rod_.tolerance_scale().head(n_) * rod_.omega1();  // rate scale of each row
    // Residual scaling: node rows as rates (1 / w), constraint and actuator rows (strains,
    // lengths / L) by 1.
    fs_ = Vector::Ones(n_ + nc_ + m_);
    fs_.head(n_) = w_.cwiseInverse();
    const double omega_max = variational_max_frequency(problem, options.nodes);
    const double floor = kRoundingFloor * std::numeric_limits<double>::epsilon() *
                         std::pow(omega_max / rod_.omega1(), 2);
    ko_.fnormtol = std::max(options.tol, floor);
    ko_.max_iterations = options.max_iterations;
    ko_.max_setup_calls = options.max_setup_calls;
    ko_.f_scale = fs_;
    ko_.u_scale = Vector::Ones(n_ + nc_ + m_);
    for (int e = 0; e < m_; ++e) ko_.u_scale[n_ + nc_ + e] = 1.0 / rod_.unknown_scale(e);
    cached_ = Vector::Zero(
        (constrained() ? rod_.constrained_pattern() : rod_.pattern(false)).nonZeros());
    warm_ = evaluated_ = Vector::Zero(n_ + nc_ + m_);
    g_move_.assign(options.nodes, SE3::identity());
    xi_move_.assign(options.nodes - 1, Vector6::Zero());
    eta_move_.assign(options.nodes, Vector6::Zero());
    rod_.set_state(y_);
  }

  /// A deep copy (control snapshots): the rod, and KINSOL's vectors and kept KLU factors
  /// (KinsolSolver's copy constructor); the callbacks are bound to `this` in every solve().
  ImplicitMidpointCollocation(const ImplicitMidpointCollocation&) = default;

  /// One step of the user's dt. A step that KINSOL cannot solve (the midpoint rule's nonlinear
  /// system at steps far above the first bending period, e.g. 0.1 s on the viscous cantilever) is
  /// split into two halves, recursively up to kMaxSplits levels; the iterations of every
  /// substep are reported. The step fails only when the 2^kMaxSplits substeps fail too. There
  /// is nothing to split at small dt: the Newton matrix tends to (2/dt) I.
  StepStatus step(double t, double dt) override { return split_step(t, dt, 0); }

  StepStatus split_step(double t, double dt, int depth) {
    StepStatus status = single_step(t, dt);
    if (status.ok || depth >= kMaxSplits) return status;
    const int spent = status.iterations;
    StepStatus first = split_step(t, 0.5 * dt, depth + 1);
    if (!first.ok) {
      first.iterations += spent;
      return first;
    }
    StepStatus second = split_step(t + 0.5 * dt, 0.5 * dt, depth + 1);
    second.iterations += spent + first.iterations;
    return second;
  }

  StepStatus single_step(double t, double dt) {
    if (!(dt > 0.0) || !std::isfinite(t + dt))
      return StepStatus::failed("implicit-midpoint-collocation: dt must be > 0");
    h_ = t + 0.5 * dt;
    t_end_ = t + dt;
    a_ = 2.0 / dt;
    const bool continues =
        history_ > 0 && std::abs(t - t_) <= 1e-12 * std::max(1.0, std::abs(t));
    if (!continues) history_ = 0;
    // Predictor of the mean rate over the step (z is dt/2 times it): the linear extrapolation of
    // the last two steps' mean rates (at their midpoints) to this step's midpoint; after one
    // step, the last mean rate; at the first step (and after a failure or a jump in t) the
    // better, by scaled residual, of no change and the explicit rate f(h, y0). Until session 24
    // every step chose among all four by residual: three more evaluations of f per step, and
    // more iterations (bench_dynamics N = 20: 9.85 / 6.33 per step at dt auto / 1 ms, against
    // 9.69 / 6.07 with the extrapolation), because the max norm of the residual is dominated by
    // the stiff modes, which the midpoint rule does not damp: "no change" won every step at
    // dt auto. The constraint forces and actuator unknowns are predicted by the last step's.
    z_.segment(n_, nc_) = forces_;
    z_.tail(m_) = x_;
    if (history_ >= 2) {
      z_.head(n_) = (0.5 * dt) * (k1_ + ((dt + dt1_) / (dt1_ + dt2_)) * (k1_ - k2_));
    } else if (history_ == 1) {
      z_.head(n_) = (0.5 * dt) * k1_;
    } else {
      z_.head(n_).setZero();
      const double still = residual_norm(z_);
      trial_ = z_;
      trial_.head(n_) = (0.5 * dt) * -F_.head(n_);  // F(0) = -f(h, y0) on the node rows
      if (residual_norm(trial_) < still) z_ = trial_;
    }
    // warm_start_from: the solution of a clone's same step from a nearby state (a difference
    // step, docs/control.md), for this step of the user's dt only (not its halves), where its
    // residual is the smaller.
    if (warm_pending_) {
      warm_pending_ = false;
      if (residual_norm(warm_) < residual_norm(z_)) z_ = warm_;
    }
    z0_ = z_;
    ko_.u_scale.head(n_) = w_.cwiseInverse() * a_;
    ko_.u_scale.segment(n_, nc_).setConstant(1.0 / rod_.force_scale());

    if (cache_valid_ && ++age_ > max_age_) cache_valid_ = false;
    ko_.max_setup_calls = max_setup_calls_;
    // A kept Jacobian of this a is the matrix KLU factorised last: start from its factors.
    ko_.reuse_factorisation = cache_valid_ && cached_a_ == a_;
    const bool fresh_start = !cache_valid_;
    // Full steps first: KINSOL's line search costs a quarter of the step at dt auto in trial
    // residuals (docs/dynamics.md, Benchmarks). Broyden's steps on the kept Jacobian's factors
    // (KinsolSolver::solve_broyden: a fresh Jacobian where they stop contracting), or, for exact
    // Newton (max_setup_calls = 1), KINSOL's. Where they do not converge in kChordIterations,
    // KINSOL's line search from the predictor again.
    ko_.line_search = false;
    ko_.max_iterations = std::min(max_iterations_, kChordIterations);
    KinsolStats s = solve(max_setup_calls_ > 1);
    long iterations = s.nonlinear_iterations;
    ko_.max_iterations = max_iterations_;
    if (!s.converged) {
      z_ = z0_;
      ko_.line_search = true;
      ko_.reuse_factorisation = cache_valid_ && cached_a_ == a_;
      s = solve();
      iterations += s.nonlinear_iterations;
    }
    // Fallbacks (large steps): exact Newton with full steps (a fresh Jacobian every
    // iteration; the line search can stall in a local minimum of |F|), from the predictor and
    // then from the explicit rate.
    for (int attempt = 0; attempt < 2 && !s.converged; ++attempt) {
      z_ = z0_;
      if (attempt == 1) {  // the explicit rate: F(0) = -f(h, y0) on the node rows
        z_.head(n_).setZero();
        residual(z_, F_);
        z_.head(n_) = (0.5 * dt) * -F_.head(n_);
      }
      cache_valid_ = false;
      ko_.reuse_factorisation = false;
      ko_.max_setup_calls = 1;
      ko_.line_search = false;
      s = solve();
      iterations += s.nonlinear_iterations;
    }
    if (!s.converged) {
      rod_.set_state(y_);
      StepStatus failed = StepStatus::failed(rodlab::format(
          "implicit-midpoint-collocation: KINSOL did not converge in the step from t = {:g} s "
          "(dt = {:g} s): {}, scaled residual {:g}{}",
          t, dt, s.flag_name, s.fnorm, s.message.empty() ? "" : " (" + s.message + ")"));
      failed.iterations = static_cast<int>(iterations);
      history_ = 0;
      return failed;
    }
    if (fresh_start && iterations == s.nonlinear_iterations)  // converged without a fallback
      fresh_iterations_ = static_cast<int>(iterations);
    if (iterations > std::max(kSlowSolve, fresh_iterations_ + kSlowMargin)) cache_valid_ = false;

    // Ledger powers at the midpoint (in f_ already where KINSOL's last residual was at z, as
    // it is after a converged solve), then y1 = y0 + 2 z.
    forces_ = z_.segment(n_, nc_);
    x_ = z_.tail(m_);
    if (!(evaluated_ == z_)) {
      ym_ = y_.head(n_) + z_.head(n_);
      rate(ym_, forces_, x_);
    }
    forces_used_ = rod_.last_forces();
    y_.head(n_) += 2.0 * z_.head(n_);
    y_[rod_.dissipated_index()] += dt * f_[rod_.dissipated_index()];
    y_[rod_.work_index()] += dt * f_[rod_.work_index()];
    rod_.set_state(y_);

    k2_.swap(k1_);
    k1_ = a_ * z_.head(n_);  // (y1 - y0) / dt
    dt2_ = dt1_;
    dt1_ = dt;
    history_ = std::min(history_ + 1, 2);
    t_ = t + dt;
    StepStatus ok;
    ok.iterations = static_cast<int>(iterations);
    return ok;
  }

  Energy energy() const override {
    return rod_.energy(y_[rod_.dissipated_index()], y_[rod_.work_index()]);
  }
  Vector3 tip_position() const override { return rod_.tip_position(); }
  double max_det_deviation() const override { return rod_.max_det_deviation(); }
  std::vector<result::CenterlineSample> centerline() const override { return rod_.centerline(); }
  std::vector<Vector6> velocities() const override {
    const auto eta = rod_.velocities();
    return {eta.begin(), eta.end()};
  }

  std::vector<ActuatorReading> actuator_readings() const override {
    std::vector<ActuatorReading> out(m_);
    if (m_ == 0) return out;
    Vector lengths(m_);
    rod_.path_lengths(y_, lengths);
    const auto& which = rod_.problem().unknown_actuators();
    for (int e = 0; e < m_; ++e) out[e] = {which[e], lengths[e], forces_used_[which[e]]};
    return out;
  }

  // --- control (stepper.hpp; docs/control.md "The state") ------------------------------------

  std::unique_ptr<Stepper> clone() const override {
    return std::make_unique<ImplicitMidpointCollocation>(*this);
  }

  // Every member a step changes, scratch included (tests/control/test_plant.cpp checks that a
  // rollout from a restored state repeats bit for bit): the state y_, the predictor's history
  // and candidates, the Jacobian kept across steps with KINSOL's vectors and KLU's kept factors
  // (KinsolSolver::assign: a step may start from them), the options a step adjusts. Fixed at
  // construction: sizes, scalings (fs_, w_), limits. The rod's work arrays are outputs of every
  // evaluation of f (written before they are read); they are set to y_ for the reports.
  void assign_state(const Stepper& other) override {
    const auto& o = dynamic_cast<const ImplicitMidpointCollocation&>(other);
    RODLAB_THROW_UNLESS(&o.rod_.problem() == &rod_.problem() && o.rod_.nodes() == rod_.nodes(),
                        "implicit-midpoint-collocation: assign_state from another problem or grid");
    kinsol_.assign(o.kinsol_);
    ko_ = o.ko_;
    x_ = o.x_, forces_used_ = o.forces_used_, t_end_ = o.t_end_;
    y_ = o.y_, y1_ = o.y1_, forces_ = o.forces_;
    ym_ = o.ym_, z_ = o.z_, z0_ = o.z0_, f_ = o.f_, trial_ = o.trial_, F_ = o.F_;
    h_ = o.h_, a_ = o.a_, t_ = o.t_, dt1_ = o.dt1_, dt2_ = o.dt2_;
    history_ = o.history_;
    k1_ = o.k1_, k2_ = o.k2_;
    cached_ = o.cached_, cached_a_ = o.cached_a_, cache_valid_ = o.cache_valid_;
    age_ = o.age_, jacobian_calls_ = o.jacobian_calls_, fresh_jacobians_ = o.fresh_jacobians_;
    fresh_iterations_ = o.fresh_iterations_;
    warm_ = o.warm_, warm_pending_ = o.warm_pending_, evaluated_ = o.evaluated_;
    g_move_ = o.g_move_, xi_move_ = o.xi_move_, eta_move_ = o.eta_move_;
    rod_.set_state(y_);
  }

  // The next step starts from the half-step increment (and constraint forces, actuator
  // unknowns) that `after` converged to, if its residual here is the smallest of the
  // predictor's candidates (it is, for a nearby state).
  void warm_start_from(const Stepper& after) override {
    const auto& o = dynamic_cast<const ImplicitMidpointCollocation&>(after);
    RODLAB_THROW_UNLESS(o.z_.size() == warm_.size(),
                        "implicit-midpoint-collocation: warm_start_from another grid");
    warm_ = o.z_;
    warm_pending_ = true;
  }

  int tangent_size() const override { return tangent_.size(); }
  // The rod's strains xi_j = log(g_j^-1 g_(j+1)) / ds (3.38) and node velocities of y_ (set at
  // the end of every step, assign_state and add_tangent).
  void read_tangent(std::span<double> x) const override {
    tangent_.read(rod_.strains(), rod_.velocities(), x);
  }
  // The poses follow the strains, g_(j+1) = g_j exp(ds xi_j) (3.38), a Kirchhoff rod's with
  // nu = nu* (on the constraint c = 0, as rest_state() puts the initial poses); the node rows of
  // y_ (p, q, eta) are rewritten from them. The ledger (D, W), the predictor's history (mean
  // rates of the last steps, one candidate among several) and the kept Jacobian stay.
  void add_tangent(std::span<const double> dx) override {
    const auto xi = rod_.strains();
    const auto eta = rod_.velocities();
    std::copy(xi.begin(), xi.end(), xi_move_.begin());
    std::copy(eta.begin(), eta.end(), eta_move_.begin());
    tangent_.add(dx, xi_move_, eta_move_);
    const bool kirchhoff = rod_.kirchhoff();
    const auto& model = rod_.problem().model();
    g_move_[0] = rod_.poses()[0];
    for (std::size_t j = 0; j < xi_move_.size(); ++j) {
      if (kirchhoff) xi_move_[j].tail<3>() = model.xi_star((j + 0.5) * rod_.ds()).tail<3>();
      g_move_[j + 1] = g_move_[j] * SE3::exp(rod_.ds() * xi_move_[j]);
    }
    rod_.pack_nodes(g_move_, eta_move_, y_);
    rod_.set_state(y_);
  }

  double max_quaternion_norm_deviation() const override {
    double worst = 0.0;
    for (int j = 0; j < n_; j += SemiDiscreteRod::kBlock)
      worst = std::max(worst,
                       std::abs(y_.segment<4>(j + SemiDiscreteRod::kQ).norm() - 1.0));
    return worst;
  }
  long jacobian_evaluations() const override { return fresh_jacobians_; }

 private:
  /// max_i |F_i(z)| / w_i, the norm KINSOL tests.
  double residual_norm(const Vector& u) {
    residual(u, F_);
    return F_.cwiseProduct(fs_).cwiseAbs().maxCoeff();
  }

  /// f(h, y) (ledger rows included) into f_, with the constraint forces of a Kirchhoff rod and
  /// the actuator unknowns.
  void rate(const ConstRef& y, const ConstRef& forces, const ConstRef& x) {
    if (!constrained())
      rod_.rhs(h_, y, f_);
    else
      rod_.rhs(h_, y, forces, x, f_);
  }

  // Unknowns u = [z; f]: the half-step increment of the node rows and, for Kirchhoff rods,
  // the step's mean constraint forces (3 per segment, N). Rows: the midpoint rule on the node
  // rows with f in the stresses, then the constraint at the end of the step, c(y0 + 2 z) = 0
  // (the midpoint analogue of SHAKE).
  // Actuator unknowns x (muscle lengths at the midpoint, length-controlled forces) follow,
  // with their rows: (Delta - L(y_m)) / L, and (L(y_1) - L_target(t + dt)) / L at the end of
  // the step.
  // f(h, y0 + z) goes to f_ with its ledger rows, and u to evaluated_: the step's ledger powers
  // need no evaluation of their own.
  void residual(const ConstRef& u, Eigen::Ref<Vector> F) {
    ym_ = y_.head(n_) + u.head(n_);
    rate(ym_, u.segment(n_, nc_), u.tail(m_));
    F.head(n_) = a_ * u.head(n_) - f_.head(n_);
    evaluated_ = u;
    if (!constrained()) return;
    y1_ = y_.head(n_) + 2.0 * u.head(n_);
    if (nc_ > 0) rod_.constraint(y1_, F.segment(n_, nc_));
    if (m_ > 0) rod_.actuator_rows(t_end_, y1_, u.tail(m_), F.tail(m_));
  }

  /// dF/du at z (KINSOL's Jacobian callback; F(z) is not needed).
  void jacobian(const ConstRef& z, KinsolSolver::SparseMatrix& J) {
    const bool reuse = jacobian_calls_ == 0 && cache_valid_;
    ++jacobian_calls_;
    if (reuse) {
      // dF/dz = a I - df/dy: the stored one with the diagonal moved to this step's a (and
      // stored so: the cache is always the matrix factorised last).
      std::copy(cached_.data(), cached_.data() + cached_.size(), J.valuePtr());
      if (a_ != cached_a_) {
        for (int i = 0; i < n_; ++i) J.coeffRef(i, i) += a_ - cached_a_;
        std::copy(J.valuePtr(), J.valuePtr() + cached_.size(), cached_.data());
        cached_a_ = a_;
      }
      return;
    }
    ym_ = y_.head(n_) + z.head(n_);
    if (!constrained()) {
      rod_.newton_matrix(h_, ym_, a_, 1.0, J);
    } else {
      y1_ = y_.head(n_) + 2.0 * z.head(n_);
      rod_.constrained_newton_matrix(h_, ym_, z.segment(n_, nc_), z.tail(m_), a_, 1.0, y1_,
                                     2.0, J);
    }
    std::copy(J.valuePtr(), J.valuePtr() + cached_.size(), cached_.data());
    cached_a_ = a_;
    cache_valid_ = true;
    age_ = 0;
    ++fresh_jacobians_;
  }

  /// Kirchhoff constraint forces or actuator unknowns: the extended system.
  bool constrained() const { return rod_.kirchhoff() || rod_.unknown_size() > 0; }

  KinsolStats solve(bool broyden = false) {
    // Starting from kept factors, KINSOL's first Jacobian request means they were too stale.
    jacobian_calls_ = ko_.reuse_factorisation ? 1 : 0;
    // (A lambda that captures only `this` sits in std::function's local buffer: no allocation.)
    const auto method = broyden ? &KinsolSolver::solve_broyden : &KinsolSolver::solve;
    return (kinsol_.*method)(
        z_, [this](const ConstRef& u, Eigen::Ref<Vector> F) { residual(u, F); },
        [this](const ConstRef& u, const ConstRef&, KinsolSolver::SparseMatrix& J) {
          jacobian(u, J);
        },
        ko_);
  }

  SemiDiscreteRod rod_;
  KinsolSolver kinsol_;
  StaggeredTangent tangent_;  ///< the control coordinates (tangent_state.hpp)
  KinsolOptions ko_;
  int n_ = 0, nc_ = 0;  ///< node unknowns; constraint forces (Kirchhoff rods, else 0)
  int m_ = 0;           ///< actuator unknowns (muscle lengths, length-controlled forces)
  Vector x_;            ///< the last step's actuator unknowns (predictor)
  DynamicProblem::Forces forces_used_{};  ///< the actuators' forces of the last step
  double t_end_ = 0.0;  ///< the end of the step in progress (length targets)
  Vector y_;           ///< state at t_ (nodes, D, W)
  Vector y1_;          ///< end-of-step node rows (constraint rows)
  Vector forces_;      ///< the last step's mean constraint forces (predictor)
  Vector fs_;          ///< residual scaling (KINSOL's f_scale)
  Vector ym_, z_, z0_, f_;  ///< midpoint, half-step increment (and its prediction), f
  Vector trial_, F_;        ///< predictor candidates and their residual
  Vector evaluated_;        ///< the unknowns of the last residual (f_ holds its rates)
  Vector w_;           ///< rate scale per node row, omega_1 tolerance_scale()
  // Step in progress and predictor history (mean rates of the last two steps).
  double h_ = 0.0, a_ = 1.0, t_ = 0.0, dt1_ = 0.0, dt2_ = 0.0;
  int history_ = 0;
  Vector k1_, k2_;
  // Jacobian kept across steps.
  Vector cached_;
  double cached_a_ = 0.0;
  bool cache_valid_ = false;
  int age_ = 0, jacobian_calls_ = 0, max_age_ = 50, max_setup_calls_ = 10, max_iterations_ = 50;
  long fresh_jacobians_ = 0;
  int fresh_iterations_ = 0;  ///< iterations of the last solve from a fresh Jacobian
  // Control: a warm start for the next step (warm_start_from) and add_tangent's work arrays.
  Vector warm_;
  bool warm_pending_ = false;
  std::vector<SE3> g_move_;
  std::vector<Vector6> xi_move_, eta_move_;
};

}  // namespace

std::unique_ptr<ImplicitMidpointCollocationStepper> make_implicit_midpoint_collocation(
    const DynamicProblem& problem, const ImplicitMidpointCollocationOptions& options,
    std::span<const SE3> g0) {
  return std::make_unique<ImplicitMidpointCollocation>(problem, options, g0);
}

std::unique_ptr<ImplicitMidpointCollocationStepper> make_implicit_midpoint_collocation(
    const DynamicProblem& problem, const ImplicitMidpointCollocationOptions& options,
    const RestState& initial) {
  return std::make_unique<ImplicitMidpointCollocation>(problem, options, initial.g);
}

}  // namespace rodlab::solvers::dynamics
