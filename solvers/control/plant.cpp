#include "rodlab/solvers/control/plant.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>

#include "rodlab/check.hpp"
#include "rodlab/rod/characteristics.hpp"
#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/registry.hpp"
#include "rodlab/solvers/statics/workspace.hpp"
#include "../dynamics/tangent_state.hpp"

namespace rodlab::solvers::control {
namespace {

/// Relative slack on a bound: an input on its limit after rounding is inside.
constexpr double kBoundSlack = 1e-12;
/// A variational step that is a divisor of dt_c within this of its stable step still counts.
constexpr double kStepRounding = 1e-9;

/// The number of equal scheme steps in one control step of length dt_c.
int substeps_of(const dynamics::DynamicProblem& problem, const PlantOptions& o) {
  return std::max(1, static_cast<int>(
                         std::ceil(o.dt_control / requested_step(problem, o) - kStepRounding)));
}

}  // namespace

double requested_step(const dynamics::DynamicProblem& problem, const PlantOptions& o) {
  if (o.solver.dt > 0.0) return o.solver.dt;
  return scheme_for(o.solver.scheme, Problem::dynamics).id == SchemeId::variational
             ? dynamics::auto_time_step(problem, "variational", o.solver.nodes)
             : o.dt_control;
}

Plant::Plant(const scene::Scene& scene, const PlantOptions& options)
    : dt_control_(options.dt_control) {
  RODLAB_THROW_UNLESS(std::isfinite(options.dt_control) && options.dt_control > 0.0,
                      "control: dt_control must be > 0 (got {:g})", options.dt_control);
  RODLAB_THROW_UNLESS(options.solver.nodes >= min_nodes(Problem::dynamics), "nodes must be >= {}",
                      min_nodes(Problem::dynamics));
  const SchemeInfo& scheme = scheme_for(options.solver.scheme, Problem::dynamics);
  RODLAB_THROW_UNLESS(!scene.actuators.empty(), "control: the scene '{}' has no actuators",
                      scene.name);
  problem_ = std::make_unique<dynamics::DynamicProblem>(dynamics::DynamicProblem::from_scene(scene));
  RODLAB_THROW_UNLESS(!problem_->tip_clamped(), "control: the tip must be free (tip.free)");

  // The inputs and their limits, as the workspaces take them (workspace.hpp); the scene is
  // copied because workspace_inputs hands out pointers into it.
  scene::Scene copy = scene;
  const auto inputs = statics::workspace_inputs(copy);
  const int m = static_cast<int>(inputs.size());
  lower_.resize(m);
  upper_.resize(m);
  u_.resize(m);
  for (int k = 0; k < m; ++k) {
    lower_[k] = inputs[k].limits.first;
    upper_[k] = inputs[k].limits.second;
    u_[k] = std::clamp(inputs[k].value->at(0.0), lower_[k], upper_[k]);
  }

  substeps_ = substeps_of(*problem_, options);
  dt_ = dt_control_ / substeps_;
  if (scheme.id == SchemeId::implicit_midpoint || scheme.id == SchemeId::bdf_alpha) {
    const std::string why = dynamics::shooting_step_problem(
        *problem_, options.solver.scheme, options.solver.grid, dt_, options.solver.tol);
    if (!why.empty()) throw std::invalid_argument(why);
  }
  set_input(u_);
  std::string failure;
  const dynamics::RestState initial = dynamics::initial_state(scene, *problem_, options.solver,
                                                              failure);
  if (!failure.empty()) throw std::invalid_argument("control: " + failure);
  stepper_ = stepper_factory(scheme.id)(*problem_, options.solver, initial);
  before_step_ = snapshot();

  // characteristic sizes of the tangent coordinates (header)
  const double L = problem_->length();
  const auto c = rod::characteristics(problem_->model(), options.solver.nodes,
                                      rod::TipSupport::free);
  const double T = 1.0 / c.first_bending_frequency_hz;
  state_scale_.resize(stepper_->tangent_size());
  const dynamics::StaggeredTangent layout(options.solver.nodes, problem_->model());
  layout.fill(1.0 / L, 1e-2, 1.0 / T, L / T,
              std::span<double>(state_scale_.data(), state_scale_.size()));
}

void Plant::set_input(const Eigen::Ref<const Eigen::VectorXd>& u) {
  RODLAB_THROW_UNLESS(u.size() == input_count(), "control: expected {} inputs, got {}",
                      input_count(), u.size());
  for (int k = 0; k < input_count(); ++k) {
    const double slack = kBoundSlack * std::max(1.0, upper_[k] - lower_[k]);
    RODLAB_THROW_UNLESS(u[k] >= lower_[k] - slack && u[k] <= upper_[k] + slack,
                        "control: input {} = {:g} outside its limits [{:g}, {:g}]", k, u[k],
                        lower_[k], upper_[k]);
    problem_->hold_input(k, u[k]);
  }
  u_ = u;
}

template <class Substep>
dynamics::StepStatus Plant::each_substep(Substep substep) {
  // The run's wall-time guard (common/deadline.hpp, --max-wall-time) once per control step: the
  // variational steps do not check it themselves, and a controller's rollouts are many steps.
  check_deadline();
  dynamics::StepStatus total;
  for (int k = 0; k < substeps_; ++k) {
    const dynamics::StepStatus s = substep(k);
    total.iterations += s.iterations;
    if (!s.ok) {
      total.ok = false;
      total.reason = s.reason;
      total.reached = s.reached;
      return total;
    }
    t_ += dt_;
  }
  return total;
}

dynamics::StepStatus Plant::advance() {
  save(before_step_);
  dynamics::StepStatus status = each_substep([this](int) { return stepper_->step(t_, dt_); });
  // A failed control step (single shooting that does not converge after an input jump) is
  // repeated from its start in 2, then 4 and 8 times as many scheme steps: the same held input
  // and ODE, solved with a finer step, as an ODE solver rejects a step.
  for (int split = 2; !status.ok && split <= kMaxStepSplit; split *= 2) {
    restore(before_step_);
    const double dt = dt_ / split;
    int iterations = status.iterations;
    status = {};
    for (int k = 0; k < substeps_ * split && status.ok; ++k) {
      status = stepper_->step(t_, dt);
      iterations += status.iterations;
      if (status.ok) t_ += dt;
    }
    status.iterations = iterations;
    if (status.ok) ++split_steps_;
  }
  return status;
}

dynamics::StepStatus Plant::advance_linearised(Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                               Eigen::MatrixXd& C, Eigen::MatrixXd& D) {
  const dynamics::StepStatus total = each_substep([&](int k) {
    if (k == 0) return stepper_->step_linearised(t_, dt_, A, B);
    // A = A_k ... A_1, B = A_k (... (A_2 B_1 + B_2) ...) + B_k
    const dynamics::StepStatus s = stepper_->step_linearised(t_, dt_, sub_A_, sub_B_);
    if (s.ok) {
      A = sub_A_ * A;
      B = sub_A_ * B + sub_B_;
    }
    return s;
  });
  if (!total.ok) return total;
  RODLAB_THROW_UNLESS(B.cols() == input_count(), "control: the linearised step has {} inputs, the plant {}",
                      B.cols(), input_count());
  stepper_->tip_jacobian(tip_J_);
  C.noalias() = tip_J_ * A;
  D.noalias() = tip_J_ * B;
  return total;
}

void Plant::set_state_of(const Plant& other) {
  RODLAB_THROW_UNLESS(other.state_size() == state_size(),
                      "control: the model's state has {} tangent coordinates, the plant's {} "
                      "(the same rod model and nodes are needed)",
                      state_size(), other.state_size());
  x_other_.resize(state_size());  // no-ops after the first call
  x_own_.resize(state_size());
  other.read_state(std::span<double>(x_other_.data(), x_other_.size()));
  read_state(std::span<double>(x_own_.data(), x_own_.size()));
  x_other_ -= x_own_;
  add_state(std::span<const double>(x_other_.data(), x_other_.size()));
  t_ = other.time();
  set_input(other.input());
}

PlantSnapshot Plant::snapshot() const { return {stepper_->clone(), t_, u_}; }

void Plant::save(PlantSnapshot& s) const {
  s.stepper->assign_state(*stepper_);
  s.t = t_;
  s.u = u_;
}

void Plant::restore(const PlantSnapshot& s) {
  stepper_->assign_state(*s.stepper);
  t_ = s.t;
  set_input(s.u);
}

}  // namespace rodlab::solvers::control
