#pragma once
// The variational stepper (variational.hpp) as a class template, private to solvers/dynamics:
// Variational<false> is the plain step (variational.cpp), Variational<true> the step with
// muscles or length control (variational_actuated.cpp, variational_actuators.hpp). The two are
// instantiated in different translation units on purpose: in one unit the second
// instantiation's extra calls of small_angle::exp and ::log made GCC stop inlining them into the
// plain step, which cost it 10-15 % (bench_dynamics, A/B).
#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "discrete_legendre.hpp"
#include "kirchhoff_constraint.hpp"
#include "packed_pair.hpp"
#include "rodlab/check.hpp"
#include "rodlab/lie/small_angle.hpp"
#include "rodlab/rod/energies.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/variational/variational.hpp"
#include "../tangent_state.hpp"
#include "variational_actuators.hpp"

namespace rodlab::solvers::dynamics {
namespace {

namespace small = lie::small_angle;

/// kActuated: the scene has muscles or length-controlled actuators (variational_actuators.hpp);
/// the plain step is the same code without them.
template <bool kActuated>
class Variational final : public Stepper {
 public:
  Variational(const DynamicProblem& problem, const VariationalOptions& options,
              const RestState& initial)
      : P_(problem), opt_(options), n_(options.nodes), ds_(problem.length() / (n_ - 1)),
        tangent_(n_, problem.model()) {
    if (n_ < 3) throw std::invalid_argument("variational: nodes must be >= 3");
    problem.model().require_spans_on_grid(n_, "variational");
    const auto& g0 = initial.g;
    RODLAB_THROW_UNLESS(static_cast<int>(g0.size()) == n_,
                        "variational: expected {} initial poses, got {}", n_, g0.size());
    kirchhoff_ = problem.is_kirchhoff();
    clamped_ = problem.tip_clamped();
    if (kirchhoff_ && clamped_)
      throw std::invalid_argument(
          "variational: rod.model kirchhoff with tip.clamped is not supported yet (the constraint "
          "solve moves the tip); use implicit-midpoint or bdf-alpha, or rod.model cosserat");
    nu_star_.resize(n_ - 1);  // each segment's span's (spans begin on nodes)
    for (int j = 0; j + 1 < n_; ++j)
      nu_star_[j] = problem.model().segment_xi_star(j, n_).tail<3>();
    g_.assign(g0.begin(), g0.end());
    // A clamped tip holds the clamp's pose exactly (the initial state meets it to the statics'
    // tolerance); the segments below then rebuild it to rounding in every step.
    if (clamped_) g_.back() = problem.tip_target();
    G_.resize(n_ - 1);
    xi_.resize(n_ - 1);
    for (int j = 0; j + 1 < n_; ++j) {
      G_[j] = g_[j].inverse() * g_[j + 1];
      xi_[j] = G_[j].log() / ds_;
      if (kirchhoff_) {
        // Start on the constraint: a chord of the sampled initial shape is shorter than its arc
        // by O((kappa ds)^2); the segment keeps its rotation and gets nu = nu*.
        xi_[j].tail<3>() = nu_star_[j];
        G_[j] = SE3::exp(ds_ * xi_[j]);
        g_[j + 1] = g_[j] * G_[j];
      }
    }
    eta_.assign(n_, Vector6::Zero());
    mu_.assign(n_, Vector6::Zero());
    // Muscles and length control keep the symplectic-Euler start (their forces and length
    // multipliers at the initial state are not set up for a half kick; docs/dynamics.md).
    started_ = options.step == VariationalStep::symplectic_euler || kActuated;
    // Verlet's damping at the kick times (correct_damping): only scenes with viscosity or drag
    // pay for it, and not those with muscles or length control (first order there).
    viscous_ = (problem.model().V_diag().array() != 0.0).any();
    trapezoidal_damping_ = options.step == VariationalStep::verlet && !kActuated &&
                           (viscous_ || problem.has_drag());
    if (trapezoidal_damping_) {
      x_.assign(n_ - 1, Vector6::Zero());
      ef_.assign(n_ - 1, small::EF{});
      rate_.assign(n_ - 1, Vector6::Zero());
      eta_old_.assign(n_, Vector6::Zero());
    }
    const Vector6 M = problem.model().M_diag();
    legendre_ = {M, M.cwiseInverse(), options.tol, options.max_iterations};
    if (options.corrected_grid) {
      require_corrected_grid(problem);  // Cosserat, no actuators
      tip_cell_ = TipHalfCell::of(problem, n_);
    }
    entries_ = problem.entry_nodes(n_);
    if (kirchhoff_) constraint_.emplace(n_, ds_, nu_star_, legendre_, options.max_iterations);
    if constexpr (kActuated) {
      act_.emplace(problem, n_, legendre_);
      xi_new_.assign(n_ - 1, Vector6::Zero());
    }
    // The packed step (packed_pass) covers the plain rod with its loads: no actuators, no
    // cables entering from outside.
    packed_ = !kActuated && options.packed && entries_.empty() && !problem.has_actuators();
    if (packed_) {
      const packed::Pose identity = packed::load(SE3::identity(), SE3::identity());
      E_.assign(n_ / 2 + 1, identity);  // E_[0]: E^0 (the base) in both lanes
      lambda_.assign(n_, Vector6::Zero());
      const auto& model = problem.model();
      for (int j = 0; j + 1 < n_; j += 2)  // in the segment pass's pairs
        xi_star_.push_back(packed::load(model.segment_xi_star(j, n_),
                                        model.segment_xi_star(std::min(j + 1, n_ - 2), n_)));
    }
  }

  StepStatus step(double t, double dt) override {
    if (!started_) {
      if (StepStatus kicked = half_kick(t, dt); !kicked.ok) return kicked;
      started_ = true;
    }
    const double t1 = t + dt;
    const Vector6& V = P_.model().V_diag();
    // A scene pays only for the loads it has: the distributed wrench and drag are skipped when
    // absent (adding their zeros changed nothing, so the result is the same bit for bit).
    const bool applied = (P_.applied_load(SO3(), t1).array() != 0.0).any();
    const bool drag = P_.has_drag();
    const bool actuators = P_.has_actuators();
    double dissipated = 0.0, work = 0.0;
    kinetic_old_ = 0.0;
    const DynamicProblem::Forces* F = nullptr;
    // The actuators' work in the step is F times the change of their path lengths with F the
    // mean of the forces at the step's two configurations (the last step's and this one's):
    // exact for a force linear in the length (a constant tension, a linear muscle law), so the
    // ledger of a conservative tendon force does not drift (docs/dynamics.md).
    DynamicProblem::Forces F_work;  // set below where actuators exist
    if (actuators && !kActuated) {
      const auto F0 = P_.forces(t), F1 = P_.forces(t1);
      for (std::size_t k = 0; k < F0.size(); ++k) F_work[k] = 0.5 * (F0[k] + F1[k]);
    }
    if constexpr (kActuated) {
      // Pre-pass: the new segments (3.38) and strains, from which the muscles' lengths and the
      // step's forces follow before any stress is needed.
      SE3 E = SE3::identity();
      for (int j = 0; j + 1 < n_; ++j) {
        const SE3 E_next = small::exp(dt * eta_[j + 1]);
        G_[j] = E.inverse() * G_[j] * E_next;
        xi_new_[j] = G_[j].log() / ds_;
        E = E_next;
      }
      F = &act_->forces(t1, xi_new_);
      F_work = act_->work_forces();
    }
    const int tip = n_ - 1;
    if (packed_) {
      if (const int j = packed_pass(t1, dt, applied, drag, dissipated, work); j >= 0)
        return diverged(j, t1, dt);
    } else {
      // One pass from the base to the tip: segment j needs E^j and E^(j+1) (3.26) from the old
      // velocities; node j needs the stresses of segments j - 1 and j (3.41) and then updates its
      // velocity (3.42), which no later segment reads.
      SE3 E = SE3::identity();  // E^j; the base does not move
      Vector6 lambda_prev = Vector6::Zero();
      for (int j = 0; j + 1 < n_; ++j) {
        const SE3 E_next = small::exp(dt * eta_[j + 1]);
        // (3.38)-(3.40): the new strain from exact compatibility, the pose, the stress.
        if constexpr (!kActuated) G_[j] = E.inverse() * G_[j] * E_next;  // (else in the pre-pass)
        small::EF k;
        const Vector6 x = small::log(G_[j], k);  // ds xi
        const Vector6 xi = x / ds_;
        const Vector6 xi_dot = (xi - xi_[j]) / dt;
        const double s_mid = (j + 0.5) * ds_;
        if (actuators) {
          work -= ds_ * P_.actuator_length_change(xi_[j], xi, s_mid, F_work) / dt;
          if constexpr (kActuated) act_->add_segment_power(j, xi_[j], xi, dt);
        }
        xi_[j] = xi;
        g_[j + 1] = g_[j] * G_[j];
        Vector6 sigma;
        if constexpr (kActuated) {
          sigma = P_.internal_wrench(xi, xi_dot, s_mid, *F);  // with the muscles' own stiffness
          dissipated += ds_ * P_.embedded_dissipation(xi_dot, s_mid);
        } else {
          sigma = kirchhoff_ ? kirchhoff_stress(j, xi, xi_dot, t1)
                             : P_.internal_wrench(xi, xi_dot, s_mid, t1);
        }
        const Vector6 lambda = small::dexp_inv_transpose_apply(x, sigma, k);
        dissipated += ds_ * xi_dot.dot(V.cwiseProduct(xi_dot));
        if (trapezoidal_damping_) x_[j] = x, ef_[j] = k, rate_[j] = xi_dot;
        if (j > 0 &&
            !node(j, t1, dt, dt, E, lambda, lambda_prev, applied, drag, dissipated, work, F))
          return diverged(j, t1, dt);
        lambda_prev = lambda;
        E = E_next;
      }
      if (!node(tip, t1, dt, dt, E, P_.tip_load(g_[tip].rotation(), t1), lambda_prev, applied,
                drag, dissipated, work, F))
        return diverged(tip, t1, dt);
    }
    // A clamped tip node is held: its pose is the clamp's and eta = mu = 0 (so the last
    // segment's E^(N-1) above is the identity); the clamp's reaction, lambda^(N-2) carried to the
    // tip, does no work. The tip's node() above ran with eta_old = 0 (it added nothing to the
    // energies and the ledger); its update is undone here, after the call, so that the free
    // tip's path is the code it was (an `if` around the call cost the step 2-4 %: inlining).
    if (clamped_) {
      mu_[tip].setZero();
      eta_[tip].setZero();
    }
    if (trapezoidal_damping_) {
      // A Kirchhoff rod's predicted velocities are those on the constraint (its forces carry
      // the load: without them the predicted rates are wrong at O(1)); enforced again below.
      if (constraint_ && !constraint_->enforce(dt, G_, xi_, mu_, eta_))
        return constraint_failure(t1, dt);
      if (const int j = correct_damping(dt, drag, dissipated); j >= 0) return diverged(j, t1, dt);
    }
    if constexpr (kActuated) {
      double power = 0.0;
      if (!act_->enforce_lengths(t1, dt, G_, xi_, mu_, eta_, power))
        return StepStatus::failed(
            rodlab::format("variational: the length-control solve {} (t = {:g} s, dt = {:g} s)",
                           act_->failure(), t1, dt));
      work += power;
    }
    if (constraint_ && !constraint_->enforce(dt, G_, xi_, mu_, eta_))
      return constraint_failure(t1, dt);
    ledger_.dissipated += dt * dissipated;
    ledger_.work_in += dt * work;
    dt_last_ = dt;
    return {};
  }

  std::unique_ptr<Stepper> clone() const override { return std::make_unique<Variational>(*this); }

  // Every member a step changes (tests/control/test_plant.cpp checks bit-for-bit repetition).
  void assign_state(const Stepper& other) override {
    if constexpr (kActuated) {
      throw unsupported("assign_state: variational with muscles or length control");
    } else {
      const auto& o = dynamic_cast<const Variational&>(other);
      RODLAB_THROW_UNLESS(&o.P_ == &P_ && o.n_ == n_,
                          "variational: assign_state from another problem or grid");
      g_ = o.poses(), G_ = o.G_;
      positions_stale_ = false;
      xi_ = o.xi_, eta_ = o.eta_, mu_ = o.mu_;
      ledger_ = o.ledger_;
      kinetic_old_ = o.kinetic_old_;
      dt_last_ = o.dt_last_;
      started_ = o.started_;
      if (constraint_) *constraint_ = *o.constraint_;
    }
  }

  int tangent_size() const override { return tangent_.size(); }
  void read_tangent(std::span<double> x) const override { tangent_.read(xi_, eta_, x); }
  // The segments and poses follow the strains (3.38)-(3.39); the momenta follow the velocities
  // through (3.42) with the last step's dt (M eta at rest, before the first step).
  void add_tangent(std::span<const double> dx) override {
    tangent_.add(dx, xi_, eta_);
    for (int j = 0; j + 1 < n_; ++j) {
      G_[j] = SE3::exp(ds_ * xi_[j]);
      g_[j + 1] = g_[j] * G_[j];
    }
    positions_stale_ = false;
    for (int j = 1; j < n_; ++j) {
      const Vector6 M_eta = j == n_ - 1 && tip_cell_ ? Vector6(tip_cell_->M * eta_[j])
                                                     : Vector6(legendre_.M.cwiseProduct(eta_[j]));
      mu_[j] = lie::se3::dexp_inv_transpose_apply(dt_last_ * eta_[j], M_eta);  // (3.42)
    }
  }

  Energy energy() const override {
    Energy e = ledger_;
    // eta is the velocity over the coming step and the one before was summed during the step:
    // their mean is the kinetic energy at the current time, to O(dt^2).
    e.kinetic = 0.5 * (kinetic_old_ + kinetic_energy(P_.model(), eta_, ds_));
    e.strain = strain_energy_segments(P_.model(), xi_, ds_);
    e.gravity = gravity_energy(P_, poses(), ds_);
    if (tip_cell_) {  // the half cell's rigid-body terms (corrected_grid.hpp)
      // its share of the mean above: 1/2 x 1/2 eta^T (M_tip - M) eta x the cell ds / 2
      const Vector6& eta = eta_.back();
      e.kinetic += 0.5 * 0.5 * (0.5 * ds_) *
                   eta.dot(tip_cell_->M * eta - legendre_.M.cwiseProduct(eta));
      e.gravity += tip_cell_->gravity_energy(P_.weight_per_length(), g_.back().rotation(), ds_);
    }
    if constexpr (kActuated) {
      if (act_->muscles()) {
        e.kinetic = 0.5 * (kinetic_old_ + kinetic_energy(act_->inertias(), eta_, ds_));
        e.strain += embedded_strain_energy_segments(P_, xi_, ds_);
        e.gravity += embedded_gravity_energy(P_, poses(), ds_);
      }
    }
    return e;
  }

  std::vector<ActuatorReading> actuator_readings() const override {
    if constexpr (kActuated) return act_->readings(xi_);
    return {};
  }

  Vector3 tip_position() const override { return poses().back().translation(); }

  double max_det_deviation() const override { return dynamics::max_det_deviation(g_); }

  std::vector<result::CenterlineSample> centerline() const override {
    return staggered_centerline(poses(), xi_, ds_);
  }

  std::vector<Vector6> velocities() const override { return eta_; }

 private:
  /// (3.41)-(3.42) at node j: the momentum balance with the inner wrench (lambda^j, or the tip
  /// wrench) and the outer one (lambda^(j-1)), its impulse over `kick` (dt in a step, dt / 2
  /// in the half kick), then the velocity over the next step of length dt. Accumulates the
  /// node's kinetic energy (old velocity), drag dissipation and external power.
  bool node(int j, double t1, double dt, double kick, const SE3& E, const Vector6& inner,
            const Vector6& lambda_prev, bool applied, bool drag, double& dissipated,
            double& work, const DynamicProblem::Forces* F) {
    const bool tip = j == n_ - 1;
    const double w = tip ? 0.5 * ds_ : ds_;
    const SO3& R = g_[j].rotation();
    const Vector6 outer = G_[j - 1].coAd_apply(lambda_prev);
    const Vector6& eta_old = eta_[j];
    const TipHalfCell* cell = tip && tip_cell_ ? &*tip_cell_ : nullptr;
    Vector6 bar = cell ? cell->at_centre_of_mass(P_.gravity_load(R)) : P_.gravity_load(R);
    if constexpr (kActuated) {
      if (act_->muscles()) {
        kinetic_old_ += 0.5 * w * eta_old.dot(act_->inertia(j) * eta_old);
        bar += act_->weight(j, R);
      } else {
        kinetic_old_ += 0.5 * w * eta_old.dot(legendre_.M.cwiseProduct(eta_old));
      }
    } else {
      kinetic_old_ += 0.5 * w * eta_old.dot(cell ? Vector6(cell->M * eta_old)
                                                 : Vector6(legendre_.M.cwiseProduct(eta_old)));
    }
    add_node_loads(R, eta_old, w, t1, applied, drag, bar, dissipated, work);
    if (tip) work += inner.dot(eta_old);
    Vector6 force = inner - outer + w * bar;
    for (const auto& e : entries_) {
      if (e.node != j) continue;
      // a point load at the node: its power is entry . eta (as in ida_reference)
      const Vector6& xi_entry = xi_[tip ? j - 1 : j];
      Vector6 entry;
      if constexpr (kActuated) {
        entry = P_.entry_load(e.s, xi_entry, *F);
        act_->add_entry_power(e.s, xi_entry, eta_old);
      } else {
        entry = P_.entry_load(e.s, xi_entry, t1);
      }
      force += entry;
      work += entry.dot(eta_old);
    }
    const Vector6 mu_old = mu_[j];
    if (trapezoidal_damping_) eta_old_[j] = eta_old;
    mu_[j] = E.coAd_apply(mu_old) + (kick / w) * force;
    if constexpr (kActuated) return act_->solve_velocity(j, dt, mu_[j], mu_old, eta_[j]);
    return solve_velocity(j, dt, mu_[j], mu_old);  // (3.42)
  }

  /// (3.42) at node j of the plain step: the rod's diagonal mass, or the corrected grid's tip
  /// half cell.
  bool solve_velocity(int j, double dt, const Vector6& mu, const Vector6& mu_old) {
    if (j == n_ - 1 && tip_cell_)
      return legendre_.solve(dt, mu, mu_old, eta_[j], tip_cell_->M, tip_cell_->M_inv);
    return legendre_.solve(dt, mu, mu_old, eta_[j]);
  }

  // --- the packed step (packed_pair.hpp): the plain step on pairs of nodes -------------------
  // The same equations as the general loop of step(), in three passes: every E^j (3.26) from the
  // old velocities; every segment (3.38), (3.40); every node's pose (3.39) and balance
  // (3.41)-(3.42). The segments are independent of one another given the E^j, and so are the
  // nodes given the stresses, so each pass takes two at a time. A pair with a lane above the
  // small-angle bounds takes the scalar kernels; the tip node, with its half cell and its load,
  // is node(). Returns -1, or the node whose (3.42) diverged.
  int packed_pass(double t1, double dt, bool applied, bool drag, double& dissipated,
                  double& work) {
    packed_exponentials(dt);
    packed_segments(dt, dissipated);
    const int tip = n_ - 1;
    if (const int j = packed_nodes(t1, dt, applied, drag, dissipated, work); j >= 0) return j;
    lambda_[tip] = P_.tip_load(g_[tip].rotation(), t1);
    return node(tip, t1, dt, dt, exponential(tip), lambda_[tip], lambda_[tip - 1], applied, drag,
                dissipated, work, nullptr)
               ? -1
               : tip;
  }

  /// E^j = exp(dt eta_j), j = 1..N-1, packed in pairs as the node pass takes them: E_[p] holds
  /// (E^(2p-1), E^(2p)), E_[0] E^0 (the base does not move) in both lanes; an odd count repeats
  /// the last node in both lanes. (Kept packed: stored lane by lane and loaded again they cost
  /// the step 1-2 %, bench_dynamics, session 28.)
  void packed_exponentials(double dt) {
    constexpr double kSmall2 = small::kSmallAngle * small::kSmallAngle;
    for (int j = 1, p = 1; j < n_; j += 2, ++p) {
      const int k = std::min(j + 1, n_ - 1);
      const packed::V6 x = dt * packed::load(eta_[j], eta_[k]);
      const packed::D2 t2 = packed::dot(x.w, x.w);
      E_[p] = packed::any(!(t2 < kSmall2))
                  ? packed::load(small::exp(dt * eta_[j]), small::exp(dt * eta_[k]))
                  : packed::exp(x, t2);
    }
  }

  /// E^j from its pair.
  SE3 exponential(int j) const { return packed::lane(E_[(j + 1) / 2], 1 - j % 2); }

  /// Segments j and k (a pair) moved by the step's E: G = E_j^-1 G_j E_(j+1) (3.38) and its
  /// twist ds xi = log G with the coefficients e, f of its angle (the scalar log where a lane is
  /// above the series' bound).
  packed::V6 packed_segment_twist(int j, int k, packed::Pose& G, packed::D2& e, packed::D2& f) {
    const int p = j / 2;  // E^(j+1), E^(k+1) are the pair E_[p + 1]; E^j, E^k one node before
    G = packed::inverse_compose(packed::shifted(E_[p], E_[p + 1], k != j),
                                packed::load(G_[j], G_[k]), E_[p + 1]);
    bool small_angles;
    const packed::V6 x = packed::log(G, e, f, small_angles);
    if (small_angles) return x;
    small::EF k0, k1;
    const Vector6 x0 = small::log(packed::lane(G, 0), k0);
    const Vector6 x1 = small::log(packed::lane(G, 1), k1);
    e = packed::D2{k0.e, k1.e};
    f = packed::D2{k0.f, k1.f};
    return packed::load(x0, x1);
  }

  /// Nodes j and k (a pair): the velocities from (3.42) for the momenta mu (stored), mu_old the
  /// ones the current velocities solve; a pair that does not converge, or leaves the
  /// small-angle bound, is solved again lane by lane (which also names the node that diverged).
  /// Returns -1, or that node.
  int packed_velocities(int j, int k, double dt, const packed::V6& mu, const packed::V6& mu_old) {
    packed::V6 eta = packed::load(eta_[j], eta_[k]);
    const int solved = packed::solve_legendre(legendre_.M.data(), legendre_.M_inv.data(),
                                              legendre_.contraction, legendre_.tol,
                                              legendre_.max_iterations, dt, mu, mu_old, eta);
    for (int l = 0; l < (k != j ? 2 : 1); ++l) {
      const int s = l == 0 ? j : k;
      mu_[s] = packed::lane(mu, l);
      if (solved == 1)
        eta_[s] = packed::lane(eta, l);
      else if (!legendre_.solve(dt, mu_[s], packed::lane(mu_old, l), eta_[s]))
        return s;  // (3.42) diverged
    }
    return -1;
  }

  /// Segments j = 0..N-2: G_j = E_j^-1 G_j E_(j+1) (3.38), xi_j, the stress and its wrench
  /// lambda_j = dexp^-T_(ds xi) sigma (3.40), the viscous dissipation. The strain rates only
  /// where there is viscosity (a zero viscous stress added nothing: the result is the same bit
  /// for bit; the undamped step 2-3 % faster, bench_dynamics, session 28).
  void packed_segments(double dt, double& dissipated) {
    const double* K = P_.model().K_diag().data();
    const double* V = P_.model().V_diag().data();
    const double inv_ds = 1.0 / ds_, inv_dt = 1.0 / dt;
    const packed::D2 zero = packed::splat(0.0);
    packed::D2 dissipation = zero;
    for (int j = 0; j + 1 < n_; j += 2) {
      const int k = std::min(j + 1, n_ - 2);
      packed::Pose G;
      packed::D2 e, f;
      const packed::V6 x = packed_segment_twist(j, k, G, e, f);  // ds xi
      const packed::V6 xi = inv_ds * x;
      packed::V6 sigma = packed::diag(K, xi - xi_star_[j / 2]);  // (3.10)
      packed::V6 xi_dot{};  // (Verlet's damping corrector reads it only times V)
      if (viscous_) {
        xi_dot = inv_dt * (xi - packed::load(xi_[j], xi_[k]));
        sigma = sigma + packed::diag(V, xi_dot);
        dissipation += packed::counted(packed::dot(xi_dot, packed::diag(V, xi_dot)), k != j);
      }
      if (kirchhoff_) sigma.v = {zero, zero, zero};  // kirchhoff_stress: nu = nu* holds
      const packed::V6 lambda = packed::dexp_inv_transpose_apply(x, sigma, e, f);
      for (int l = 0; l < (k != j ? 2 : 1); ++l) {
        const int s = l == 0 ? j : k;
        G_[s] = packed::lane(G, l);
        xi_[s] = packed::lane(xi, l);
        lambda_[s] = packed::lane(lambda, l);
        if (trapezoidal_damping_)
          x_[s] = packed::lane(x, l), ef_[s] = {e[l], f[l]}, rate_[s] = packed::lane(xi_dot, l);
      }
    }
    dissipated += ds_ * (dissipation[0] + dissipation[1]);
  }

  /// Nodes j = 1..N-2 (node() without the tip and the cables), and every node's pose: the
  /// balance (3.41) with lambda_j and lambda_(j-1), gravity, the distributed load and drag, the
  /// impulse over dt and the velocity from (3.42).
  int packed_nodes(double t1, double dt, bool applied, bool drag, double& dissipated,
                   double& work) {
    const Vector3 weight = P_.weight_per_length();
    const packed::V3 weight_W{packed::splat(weight.x()), packed::splat(weight.y()),
                              packed::splat(weight.z())};
    const double* M = legendre_.M.data();
    const packed::D2 zero = packed::splat(0.0);
    packed::D2 kinetic = zero;
    for (int j = 1; j + 1 < n_; j += 2) {
      const int k = std::min(j + 1, n_ - 2);
      // the rotations of the poses g_(j+1) = g_j G_j (3.39): a serial chain, here where the
      // independent work of the pairs before hides its latency (as a pass of its own it was 9 %
      // of the step); the positions follow when read (poses())
      chain_rotation(j - 1);
      if (k != j) chain_rotation(j);
      const packed::V6 eta_old = packed::load(eta_[j], eta_[k]);
      const packed::V6 outer = packed::coAd_apply(packed::load(G_[j - 1], G_[k - 1]),
                                                  packed::load(lambda_[j - 1], lambda_[k - 1]));
      packed::V6 bar{{zero, zero, zero},
                     packed::rotate(packed::conjugate(packed::load(g_[j], g_[k]).q), weight_W)};
      if (applied || drag)
        bar = bar + packed_node_loads(j, k, t1, applied, drag, dissipated, work);
      kinetic += packed::counted(packed::dot(eta_old, packed::diag(M, eta_old)), k != j);
      const packed::V6 force = packed::load(lambda_[j], lambda_[k]) - outer + ds_ * bar;
      const packed::V6 mu_old = packed::load(mu_[j], mu_[k]);
      const packed::Pose& E = E_[(j + 1) / 2];  // E^j, E^k (k = j: E^j in both lanes)
      const packed::V6 mu =
          packed::coAd_apply(k != j ? E : packed::lane_twice(E, 0), mu_old) + (dt / ds_) * force;
      if (trapezoidal_damping_) eta_old_[j] = eta_[j], eta_old_[k] = eta_[k];
      if (const int s = packed_velocities(j, k, dt, mu, mu_old); s >= 0) return s;
    }
    kinetic_old_ += 0.5 * ds_ * (kinetic[0] + kinetic[1]);
    chain_rotation(n_ - 2);
    positions_stale_ = true;
    return -1;
  }

  /// Nodes j and k's distributed load and drag per unit length (node()'s), with their power.
  packed::V6 packed_node_loads(int j, int k, double t1, bool applied, bool drag,
                               double& dissipated, double& work) {
    Vector6 bar[2] = {Vector6::Zero(), Vector6::Zero()};
    add_node_loads(g_[j].rotation(), eta_[j], ds_, t1, applied, drag, bar[0], dissipated, work);
    if (k == j) return packed::load(bar[0], bar[0]);
    add_node_loads(g_[k].rotation(), eta_[k], ds_, t1, applied, drag, bar[1], dissipated, work);
    return packed::load(bar[0], bar[1]);
  }

  /// Adds a node's distributed load and drag per unit length (rotation R, velocity eta_old, cell
  /// w) to `bar`, their power times w to `work` and `dissipated`.
  void add_node_loads(const SO3& R, const Vector6& eta_old, double w, double t1, bool applied,
                      bool drag, Vector6& bar, double& dissipated, double& work) const {
    if (applied) {
      const Vector6 a = P_.applied_load(R, t1);
      bar += a;
      work += w * a.dot(eta_old);
    }
    if (drag) {
      const Vector6 d = P_.drag_load(eta_old);
      bar += d;
      dissipated -= w * d.dot(eta_old);
    }
  }


  /// Störmer-Verlet's first half kick (VariationalStep::verlet; docs/dynamics.md "Second order
  /// in time"): the velocity over the first step gets half a step's impulse at the initial
  /// configuration, nu_(1/2) = nu_0 + (dt / 2) F(g_0, t) per node, so that the velocities are
  /// those of the half steps and the poses second order. The strain rate in the stress is the
  /// one over the first step at the current velocities (zero from rest). No energy is booked:
  /// nothing moves.
  [[gnu::noinline]] StepStatus half_kick(double t, double dt) {
    const bool applied = (P_.applied_load(SO3(), t).array() != 0.0).any();
    double kinetic = kinetic_old_, dissipated = 0.0, work = 0.0;  // discarded
    Vector6 lambda_prev = Vector6::Zero();
    SE3 E_j = SE3::identity();
    for (int j = 0; j + 1 < n_; ++j) {
      const SE3 E_next = small::exp(dt * eta_[j + 1]);
      small::EF k;
      const Vector6 x = small::log(G_[j], k);
      const Vector6 xi = x / ds_;
      const Vector6 xi_dot = (small::log(E_j.inverse() * G_[j] * E_next) / ds_ - xi) / dt;
      const double s_mid = (j + 0.5) * ds_;
      const Vector6 sigma = kirchhoff_ ? kirchhoff_stress(j, xi, xi_dot, t)
                                       : P_.internal_wrench(xi, xi_dot, s_mid, t);
      const Vector6 lambda = small::dexp_inv_transpose_apply(x, sigma, k);
      if (j > 0 && !node(j, t, dt, 0.5 * dt, SE3::identity(), lambda, lambda_prev, applied,
                         P_.has_drag(), dissipated, work, nullptr))
        return diverged(j, t, dt);
      lambda_prev = lambda;
      E_j = E_next;
    }
    const int tip = n_ - 1;
    if (!node(tip, t, dt, 0.5 * dt, SE3::identity(), P_.tip_load(g_[tip].rotation(), t),
              lambda_prev, applied, P_.has_drag(), dissipated, work, nullptr))
      return diverged(tip, t, dt);
    if (clamped_) {
      mu_[tip].setZero();
      eta_[tip].setZero();
    }
    kinetic_old_ = kinetic;
    if (constraint_ && !constraint_->enforce(dt, G_, xi_, mu_, eta_))
      return constraint_failure(t, dt);
    return {};
  }

  /// Verlet with damping: the kick at t1 needs the viscous stress and the drag at t1, that is at
  /// the mean of the rates over the steps before and after t1 (trapezoidal, second order). The
  /// main pass used the rate before t1 (rate_, eta_old_); the velocities it solved predict the
  /// rates after. This pass adds half their difference to every node's impulse and solves the
  /// velocities again (Heun's predictor-corrector for the damping; stable for dt (tau omega^2
  /// + c) <= 2 and omega dt < 2, where the lagged form needs omega^2 dt^2 + 2 dt (tau omega^2 +
  /// c) < 4: docs/dynamics.md "Second order in time"). The dissipation booked by the main pass
  /// is replaced by the mean rates'. Returns -1, or the node whose (3.42) diverged.
  [[gnu::noinline]] int correct_damping(double dt, bool drag, double& dissipated) {
    if (packed_) return packed_correct_damping(dt, drag, dissipated);
    const Vector6& V = P_.model().V_diag();
    SE3 E = SE3::identity();  // E^j at the predicted velocities; the base does not move
    Vector6 lambda_prev = Vector6::Zero();
    for (int j = 0; j < n_; ++j) {
      Vector6 lambda = Vector6::Zero();  // the tip's inner wrench: none
      SE3 E_next;
      if (j + 1 < n_) {
        E_next = small::exp(dt * eta_[j + 1]);
        const Vector6 rate_after =
            (small::log(E.inverse() * G_[j] * E_next) - x_[j]) / (ds_ * dt);
        const Vector6 mean = 0.5 * (rate_[j] + rate_after);
        Vector6 d_sigma = V.cwiseProduct(mean - rate_[j]);
        if (kirchhoff_) d_sigma.tail<3>().setZero();  // the constraint carries the force
        dissipated += ds_ * (mean.dot(V.cwiseProduct(mean)) - rate_[j].dot(V.cwiseProduct(rate_[j])));
        lambda = small::dexp_inv_transpose_apply(x_[j], d_sigma, ef_[j]);
      }
      if (j > 0 && !correct_node(j, dt, lambda, lambda_prev, drag, dissipated)) return j;
      lambda_prev = lambda;
      E = E_next;
    }
    return -1;
  }

  /// correct_damping at node j with the stress corrections lambda of segment j (zero at the
  /// tip) and lambda_prev of segment j - 1. A clamped tip is held.
  bool correct_node(int j, double dt, const Vector6& lambda, const Vector6& lambda_prev, bool drag,
                    double& dissipated) {
    if (clamped_ && j == n_ - 1) return true;
    const double w = j == n_ - 1 ? 0.5 * ds_ : ds_;
    Vector6 force = lambda - G_[j - 1].coAd_apply(lambda_prev);
    if (drag) force += drag_correction(j, w, dissipated);
    const Vector6 mu_predicted = mu_[j];
    mu_[j] += (dt / w) * force;
    return solve_velocity(j, dt, mu_[j], mu_predicted);  // (3.42)
  }

  /// Node j's drag at the mean of its velocities before and after t1 less the drag the main
  /// pass applied (at the velocity before), times w; the dissipation booked likewise.
  Vector6 drag_correction(int j, double w, double& dissipated) const {
    const Vector6 mean = 0.5 * (eta_old_[j] + eta_[j]);
    const Vector6 d_mean = P_.drag_load(mean), d_old = P_.drag_load(eta_old_[j]);
    dissipated -= w * (d_mean.dot(mean) - d_old.dot(eta_old_[j]));
    return w * (d_mean - d_old);
  }

  /// correct_damping on pairs (packed_pass): E^j at the predicted velocities, the segments'
  /// stress corrections, the interior nodes' impulses and velocities; the tip is correct_node.
  int packed_correct_damping(double dt, bool drag, double& dissipated) {
    packed_exponentials(dt);
    const double* V = P_.model().V_diag().data();
    const double inv_ds_dt = 1.0 / (ds_ * dt);
    packed::D2 dissipation = packed::splat(0.0);
    for (int j = 0; j + 1 < n_; j += 2) {
      const int k = std::min(j + 1, n_ - 2);
      packed::Pose G;
      packed::D2 e_after, f_after;
      const packed::V6 x_after = packed_segment_twist(j, k, G, e_after, f_after);
      const packed::V6 x = packed::load(x_[j], x_[k]), rate = packed::load(rate_[j], rate_[k]);
      const packed::V6 mean = 0.5 * (rate + inv_ds_dt * (x_after - x));
      const packed::D2 power =
          packed::dot(mean, packed::diag(V, mean)) - packed::dot(rate, packed::diag(V, rate));
      dissipation += packed::counted(power, k != j);
      packed::V6 d_sigma = packed::diag(V, mean - rate);
      if (kirchhoff_) d_sigma.v = {packed::splat(0.0), packed::splat(0.0), packed::splat(0.0)};
      const packed::V6 lambda = packed::dexp_inv_transpose_apply(
          x, d_sigma, packed::D2{ef_[j].e, ef_[k].e}, packed::D2{ef_[j].f, ef_[k].f});
      lambda_[j] = packed::lane(lambda, 0);
      lambda_[k] = packed::lane(lambda, 1);
    }
    dissipated += ds_ * (dissipation[0] + dissipation[1]);
    for (int j = 1; j + 1 < n_; j += 2) {
      const int k = std::min(j + 1, n_ - 2);
      packed::V6 force = packed::load(lambda_[j], lambda_[k]) -
                         packed::coAd_apply(packed::load(G_[j - 1], G_[k - 1]),
                                            packed::load(lambda_[j - 1], lambda_[k - 1]));
      if (drag) {
        const Vector6 d0 = drag_correction(j, ds_, dissipated);
        force = force + packed::load(d0, k != j ? drag_correction(k, ds_, dissipated) : d0);
      }
      const packed::V6 mu_predicted = packed::load(mu_[j], mu_[k]);
      const packed::V6 mu = mu_predicted + (dt / ds_) * force;
      if (const int s = packed_velocities(j, k, dt, mu, mu_predicted); s >= 0) return s;
    }
    const int tip = n_ - 1;
    return correct_node(tip, dt, Vector6::Zero(), lambda_[tip - 1], drag, dissipated) ? -1 : tip;
  }

  /// Kirchhoff rods: segment j's own wrench has no force part (nu = nu* holds; the force across
  /// the section is the constraint force f of KirchhoffConstraint), the actuators act as usual.
  Vector6 kirchhoff_stress(int j, Vector6 xi, Vector6 xi_dot, double t) const {
    xi.tail<3>() = nu_star_[j];
    xi_dot.tail<3>().setZero();
    return P_.internal_wrench(xi, xi_dot, (j + 0.5) * ds_, t);
  }

  StepStatus constraint_failure(double t1, double dt) const {
    return StepStatus::failed(
        rodlab::format("variational: the Kirchhoff constraint solve {} (t = {:g} s, dt = {:g} s)",
                       constraint_->failure(), t1, dt));
  }

  StepStatus diverged(int j, double t1, double dt) const {
    // (3.42) is a small perturbation of M eta = mu for any step below the stability limit;
    // divergence means the explicit scheme blew up.
    return StepStatus::failed(rodlab::format(
        "unstable: variational: Newton on (3.42) diverged at node {} (t = {:g} s, dt = {:g} s)", j,
        t1, dt));
  }

  /// g_(j+1)'s rotation from g_j's and segment j's (3.39); its position is left for poses().
  void chain_rotation(int j) {
    g_[j + 1] = SE3(g_[j].rotation() * G_[j].rotation(), g_[j + 1].translation());
  }

  /// The poses, their positions formed here after a packed step, which keeps the rotations
  /// alone (the dynamics needs no position): p_(j+1) = p_j + R_j p(G_j), SE3::operator*'s
  /// operations, so the same poses bit for bit as forming them in the step.
  const std::vector<SE3>& poses() const {
    if (positions_stale_) {
      for (int j = 0; j + 1 < n_; ++j)
        g_[j + 1] = SE3(g_[j + 1].rotation(),
                        g_[j].translation() + g_[j].rotation() * G_[j].translation());
      positions_stale_ = false;
    }
    return g_;
  }

  const DynamicProblem& P_;
  VariationalOptions opt_;
  int n_;
  double ds_;
  DiscreteLegendre legendre_;  ///< (3.42)
  // g_'s positions are formed lazily by poses() (a const reader) after a packed step
  mutable std::vector<SE3> g_;
  mutable bool positions_stale_ = false;
  std::vector<SE3> G_;
  std::vector<Vector6> xi_, eta_, mu_;
  std::vector<DynamicProblem::EntryNode> entries_;
  StaggeredTangent tangent_;
  Energy ledger_;
  std::optional<TipHalfCell> tip_cell_;  ///< the corrected grid's free tip
  double kinetic_old_ = 0.0;
  double dt_last_ = 0.0;  ///< the last step's dt (the momenta of a moved state, add_tangent)
  bool kirchhoff_ = false;
  bool clamped_ = false;  ///< the tip node is held by a clamp (not solved)
  bool started_ = false;  ///< the velocities are those over the steps (after the half kick)
  std::vector<Vector3> nu_star_;  ///< Kirchhoff: each segment's nu* (its span's)
  std::optional<KirchhoffConstraint> constraint_;  ///< Kirchhoff rods only
  std::optional<VariationalActuators> act_;        ///< muscles, length control (kActuated)
  std::vector<Vector6> xi_new_;                    ///< the pre-pass's strains (kActuated)
  // Verlet with viscosity or drag (correct_damping): per segment ds xi, its log coefficients and
  // the rate over the step; per node the velocity over the step.
  bool trapezoidal_damping_ = false;
  bool viscous_ = false;  ///< the rod has viscosity
  std::vector<Vector6> x_, rate_, eta_old_;
  std::vector<small::EF> ef_;
  // The packed step (packed_pass): whether it runs, and per step E^j, the segments' stresses
  // lambda_j (the tip load last) and each segment's rest strain.
  bool packed_ = false;
  std::vector<packed::Pose> E_;  ///< packed_exponentials' pairs
  std::vector<Vector6> lambda_;
  std::vector<packed::V6> xi_star_;  ///< in pairs of segments (2p, 2p + 1)
};

}  // namespace

}  // namespace rodlab::solvers::dynamics
