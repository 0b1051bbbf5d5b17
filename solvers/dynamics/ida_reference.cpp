#include "rodlab/solvers/dynamics/ida_reference.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rodlab/solvers/common/ida_solver.hpp"
#include "rodlab/solvers/dynamics/semi_discrete_rod.hpp"

namespace rodlab::solvers::dynamics {
namespace {

using Vector = Eigen::VectorXd;
using ConstRef = Eigen::Ref<const Vector>;

class IdaReference final : public Stepper {
 public:
  IdaReference(const DynamicProblem& problem, const IdaOptions& options, std::span<const SE3> g0)
      : rod_(problem, options.nodes, "ida") {
    if (static_cast<int>(g0.size()) != rod_.nodes())
      throw std::invalid_argument("ida: expected " + std::to_string(rod_.nodes()) +
                                  " initial poses, got " + std::to_string(g0.size()));
    if (!(options.rtol > 0.0) || !(options.atol > 0.0))
      throw std::invalid_argument("ida: rtol and atol must be > 0");
    if (options.max_steps < 1) throw std::invalid_argument("ida: max_steps must be >= 1");
    dim_ = rod_.size();
    iD_ = rod_.dissipated_index();
    iW_ = rod_.work_index();

    // Absolute tolerances per component (ida_reference.hpp, semi_discrete_rod.hpp).
    IdaSolverOptions io;
    io.rtol = options.rtol;
    io.atol = options.atol * rod_.tolerance_scale();
    io.max_steps = options.max_steps;

    ida_ = std::make_unique<IdaSolver>(
        rod_.pattern(true),
        [this](double t, const ConstRef& y, const ConstRef& yp, Eigen::Ref<Vector> r) {
          rod_.rhs(t, y, r);
          r = yp - r;
          // muscle lengths: algebraic, Delta - L(y) (semi_discrete_rod.hpp)
          const int m = rod_.unknown_size();
          if (m > 0) rod_.actuator_rows(t, y, y.tail(m), r.tail(m));
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
    if (std::abs(t - ida_->time()) > 1e-12 * std::max(1.0, std::abs(t))) {
      // Not where IDA stands: restart there from the current state (an ODE: y' = f(t, y)).
      const Vector y = ida_->y();
      Vector yp(dim_);
      rod_.rhs(t, y, yp);
      ida_->initialize(t, y, yp);
    }
    const IdaStats s = ida_->advance(t + dt);
    rod_.set_state(ida_->y());
    if (!s.ok) {
      StepStatus failed = StepStatus::failed("ida: IDASolve failed with " + s.flag_name +
                                             " at t = " + std::to_string(s.t) + " s" +
                                             (s.message.empty() ? "" : " (" + s.message + ")"));
      failed.iterations = static_cast<int>(s.nonlinear_iterations);
      return failed;
    }
    StepStatus ok;
    ok.iterations = static_cast<int>(s.nonlinear_iterations);
    return ok;
  }

  Energy energy() const override {
    const auto y = ida_->y();
    return rod_.energy(y[iD_], y[iW_]);
  }

  Vector3 tip_position() const override { return rod_.tip_position(); }

  double max_det_deviation() const override { return rod_.max_det_deviation(); }

  std::vector<result::CenterlineSample> centerline() const override { return rod_.centerline(); }

  std::vector<ActuatorReading> actuator_readings() const override {
    const int m = rod_.unknown_size();
    std::vector<ActuatorReading> out(m);
    if (m == 0) return out;
    const auto y = ida_->y();
    Vector r(rod_.size());
    rod_.rhs(ida_->time(), y, r);  // the forces at the current state
    const auto& which = rod_.problem().unknown_actuators();
    for (int e = 0; e < m; ++e)
      out[e] = {which[e], y[rod_.unknown_index() + e], rod_.last_forces()[which[e]]};
    return out;
  }

 private:
  SemiDiscreteRod rod_;
  int dim_ = 0, iD_ = 0, iW_ = 0;
  std::unique_ptr<IdaSolver> ida_;
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
