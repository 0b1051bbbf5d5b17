#include "rodlab/solvers/dynamics/semi_discrete/ida_reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/ida_solver.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

namespace rodlab::solvers::dynamics {
namespace {

using Vector = Eigen::VectorXd;
using ConstRef = Eigen::Ref<const Vector>;

/// Internal steps per IDASolve call: a chunk, or the whole budget when that is smaller.
long chunk_steps(const IdaOptions& options) {
  return options.max_steps > 0 ? std::min(options.max_steps, kIdaChunkSteps) : kIdaChunkSteps;
}

class IdaReference final : public Stepper {
 public:
  IdaReference(const DynamicProblem& problem, const IdaOptions& options, std::span<const SE3> g0)
      : rod_(problem, options.nodes, "ida", true, options.corrected_grid) {
    RODLAB_THROW_UNLESS(static_cast<int>(g0.size()) == rod_.nodes(),
                        "ida: expected {} initial poses, got {}", rod_.nodes(), g0.size());
    if (!(options.rtol > 0.0) || !(options.atol > 0.0))
      throw std::invalid_argument("ida: rtol and atol must be > 0");
    if (options.max_steps < 0) throw std::invalid_argument("ida: max_steps must be >= 0");
    max_steps_ = options.max_steps;
    omega_max_ = variational_max_frequency(problem, options.nodes);
    if (rod_.has_position_constraints()) {
      init_stabilised(options, g0);
      return;
    }
    dim_ = rod_.size();
    iD_ = rod_.dissipated_index();
    iW_ = rod_.work_index();

    // Absolute tolerances per component (ida_reference.hpp, semi_discrete_rod.hpp).
    IdaSolverOptions io;
    io.rtol = options.rtol;
    io.atol = options.atol * rod_.tolerance_scale();
    io.max_steps = chunk_steps(options);
    if (rod_.unknown_size() == 0) io.linear_solver = options.linear_solver;

    ida_ = std::make_unique<IdaSolver>(
        rod_.pattern(true),
        [this](double t, const ConstRef& y, const ConstRef& yp, Eigen::Ref<Vector> r) {
          rod_.ida_residual(t, y, yp, r);
        },
        [this](double t, double cj, const ConstRef& y, const ConstRef&, const ConstRef&,
               IdaSolver::SparseMatrix& J) { rod_.newton_matrix(t, y, cj, 1.0, J); },
        io);

    // At rest from g0: y'0 = f(0, y0) is consistent (the system is an ODE).
    const Vector y0 = rod_.rest_state(g0);
    Vector yp0(dim_);
    rod_.rhs(0.0, y0, yp0);
    ida_->initialize(0.0, y0, yp0);
    rod_.set_state(ida_->y());
  }

  StepStatus step(double t, double dt) override {
    if (!(dt > 0.0) || !std::isfinite(t + dt)) return StepStatus::failed("ida: dt must be > 0");
    if (stabilised_) return stabilised_step(t, dt);
    if (std::abs(t - ida_->time()) > 1e-12 * std::max(1.0, std::abs(t))) {
      // Not where IDA stands: restart there from the current state (an ODE: y' = f(t, y)).
      const Vector y = ida_->y();
      Vector yp(dim_);
      rod_.rhs(t, y, yp);
      ida_->initialize(t, y, yp);
    }
    return advance(t + dt);
  }

  /// The internal steps allowed to reach tout from IDA's time (IdaOptions::max_steps).
  long step_budget(double tout) const {
    if (max_steps_ > 0) return max_steps_;
    const double scaled = kIdaStepsPerRadian * (tout - ida_->time()) * omega_max_;
    return std::max(kIdaMinStepBudget, static_cast<long>(std::min(scaled, 1e15)));
  }

  /// IDASolve to tout in chunks of kIdaChunkSteps internal steps, within the step budget; the
  /// state is unpacked for the reports.
  StepStatus advance(double tout) {
    const long budget = step_budget(tout);
    long steps = 0, iterations = 0;
    IdaStats s;
    while (true) {
      s = ida_->advance(tout);
      steps += s.steps;
      iterations += s.nonlinear_iterations;
      if (s.ok || s.flag_name != "IDA_TOO_MUCH_WORK") break;
      if (steps >= budget) {
        s.message = rodlab::format("{} internal steps (the budget of this step) taken before "
                                   "reaching t = {:g} s", steps, tout);
        break;
      }
    }
    rod_.set_state(ida_->y().head(rod_.node_size()));
    if (!s.ok) {
      StepStatus failed = StepStatus::failed(
          rodlab::format("ida: IDASolve failed with {} at t = {:g} s{}", s.flag_name, s.t,
                         s.message.empty() ? "" : " (" + s.message + ")"));
      failed.iterations = static_cast<int>(iterations);
      failed.reached = s.t;
      return failed;
    }
    StepStatus ok;
    ok.iterations = static_cast<int>(iterations);
    return ok;
  }

  Energy energy() const override {
    const auto y = ida_->y();
    return rod_.energy(y[iD_], y[iW_]);
  }

  Vector3 tip_position() const override { return rod_.tip_position(); }

  double max_det_deviation() const override { return rod_.max_det_deviation(); }

  std::vector<result::CenterlineSample> centerline() const override { return rod_.centerline(); }
  std::vector<Vector6> velocities() const override {
    const auto eta = rod_.velocities();
    return {eta.begin(), eta.end()};
  }

  std::vector<ActuatorReading> actuator_readings() const override {
    const int m = rod_.unknown_size();
    std::vector<ActuatorReading> out(m);
    if (m == 0) return out;
    const auto y = ida_->y();
    if (stabilised_) {
      // lengths on the grid, forces of an evaluation at the current state
      const int n = rod_.node_size(), iX = rod_.stabilised_unknown_index();
      Vector lengths(m), f(n);
      rod_.path_lengths(y.head(n), lengths);
      rod_.rhs(ida_->time(), y.head(n), y.segment(rod_.stabilised_force_index(),
                                                   rod_.constraint_size()),
               y.segment(iX, m), f);
      const auto& which = rod_.problem().unknown_actuators();
      for (int e = 0; e < m; ++e)
        out[e] = {which[e], rod_.unknown_is_length(e) ? y[iX + e] : lengths[e],
                  rod_.last_forces()[which[e]]};
      return out;
    }
    Vector r(rod_.size());
    rod_.rhs(ida_->time(), y, r);  // the forces at the current state
    const auto& which = rod_.problem().unknown_actuators();
    for (int e = 0; e < m; ++e)
      out[e] = {which[e], y[rod_.unknown_index() + e], rod_.last_forces()[which[e]]};
    return out;
  }

 private:
  // --- Kirchhoff rods and length control: the stabilised index-2 form --------------------------
  // (semi_discrete_rod.hpp; docs/dynamics.md "ida: Kirchhoff rods and length control").
  void init_stabilised(const IdaOptions& options, std::span<const SE3> g0) {
    stabilised_ = true;
    dim_ = rod_.stabilised_size();
    iD_ = rod_.dissipated_index();
    iW_ = rod_.work_index();
    IdaSolverOptions io;
    io.rtol = options.rtol;
    io.max_steps = chunk_steps(options);
    io.id = rod_.stabilised_id();
    // Algebraic components (constraint and actuator forces, multipliers): their Newton corrections
    // carry the rounding of the constraint rows amplified by 1/h (mu) and 1/h^2 (f) at IDA's small
    // steps, which fails IDA's convergence test on the whole vector as h -> 0 (measured: at t = 0
    // down to h = 5e-17). Their tolerance is their characteristic scale itself; they are
    // converged through the differential components they drive (a force error df moves eta by
    // h M^-1 C^T df, which the test on eta sees).
    io.atol = rod_.stabilised_tolerance_scale();
    for (Eigen::Index i = 0; i < io.atol.size(); ++i)
      if (io.id[i] != 0.0) io.atol[i] *= options.atol;
    io.suppress_algebraic = true;  // f, F and mu are index-2 variables: no local error test
    ida_ = std::make_unique<IdaSolver>(
        rod_.stabilised_pattern(),
        [this](double t, const ConstRef& y, const ConstRef& yp, Eigen::Ref<Vector> r) {
          rod_.ida_residual_stabilised(t, piece_, y, yp, r);
        },
        [this](double t, double cj, const ConstRef& y, const ConstRef&, const ConstRef&,
               IdaSolver::SparseMatrix& J) { rod_.stabilised_newton_matrix(t, piece_, y, cj, J); },
        io);
    breaks_ = rod_.stabilised_breakpoints();
    Vector y0 = rod_.stabilised_from_rest(rod_.rest_state(g0));
    restart(0.0, y0, 0.0);
  }

  /// (Re)starts IDA at t from y: a consistent state on the piece of the length schedules that
  /// starts at `piece` (the breakpoint itself, not t + dt rounded below it; poses and velocities
  /// projected, forces from the acceleration level).
  /// The energy that the projections change (the velocity jump of an impulse: only the
  /// impulsive actuator forces work during it, so their work is the change of T + U + P) is
  /// booked as work_in: the ledger stays closed across the restart.
  void restart(double t, Vector y, double piece) {
    piece_ = piece;
    Vector yp;
    const int n = rod_.node_size();
    rod_.set_state(y.head(n));
    const double before = rod_.energy(0.0, 0.0).total();
    rod_.stabilised_consistent_state(t, piece_, y, yp);
    rod_.set_state(y.head(n));
    y[iW_] += rod_.energy(0.0, 0.0).total() - before;
    ida_->initialize(t, y, yp);
    rod_.set_state(y.head(rod_.node_size()));
  }

  /// One step, stopping at every kink or jump of a length schedule inside it and restarting
  /// there: a kink of a prescribed length is an impulse (a jump of the velocities), which the
  /// restart's velocity projection applies.
  StepStatus stabilised_step(double t, double dt) {
    const double tol = 1e-12 * std::max(1.0, std::abs(t + dt));
    StepStatus total;
    try {
      if (std::abs(t - ida_->time()) > tol) restart(t, Vector(ida_->y()), t);
      for (const double b : breaks_) {
        if (b <= ida_->time() + tol || b >= t + dt - tol) continue;
        StepStatus s = advance(b);
        total.iterations += s.iterations;
        if (!s.ok) return s;
        restart(b, Vector(ida_->y()), b);
      }
      StepStatus s = advance(t + dt);
      s.iterations += total.iterations;
      if (!s.ok) return s;
      for (const double b : breaks_)
        if (std::abs(b - (t + dt)) <= tol) restart(ida_->time(), Vector(ida_->y()), b);
      return s;
    } catch (const std::runtime_error& e) {
      return StepStatus::failed(std::string("ida: ") + e.what());
    }
  }

  SemiDiscreteRod rod_;
  long max_steps_ = 0;     ///< IdaOptions::max_steps
  double omega_max_ = 0.0;  ///< the highest frequency of the semi-discrete rod [rad/s]
  int dim_ = 0, iD_ = 0, iW_ = 0;
  std::unique_ptr<IdaSolver> ida_;
  bool stabilised_ = false;
  double piece_ = 0.0;          ///< start of the current piece of the length schedules
  std::vector<double> breaks_;  ///< their kinks and jumps
};

}  // namespace

std::unique_ptr<Stepper> make_ida(const DynamicProblem& problem, const IdaOptions& options,
                                  std::span<const SE3> g0) {
  return std::make_unique<IdaReference>(problem, options, g0);
}

std::unique_ptr<Stepper> make_ida(const DynamicProblem& problem, const IdaOptions& options,
                                  const RestState& initial) {
  return std::make_unique<IdaReference>(problem, options, initial.g);
}

}  // namespace rodlab::solvers::dynamics
