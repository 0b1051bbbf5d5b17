// librodlab_ceres.so (solvers/CMakeLists.txt): bounded nonlinear least squares through Ceres
// for inverse statics' method `ceres` (control/ceres_module.hpp), the only code compiled against
// Ceres. Loaded by control/inverse_statics.cpp when that method runs.
#include <algorithm>
#include <cstring>

#include <ceres/ceres.h>

#include "control/ceres_module.hpp"

namespace {

/// The problem's residuals and Jacobian as Ceres sees them (one parameter block).
class Cost final : public ceres::CostFunction {
 public:
  explicit Cost(const RodlabLeastSquares& p) : p_(p) {
    set_num_residuals(p.residuals);
    mutable_parameter_block_sizes()->push_back(p.parameters);
  }
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    double* jacobian = jacobians ? jacobians[0] : nullptr;
    return p_.evaluate(p_.user, parameters[0], residuals, jacobian) != 0;
  }

 private:
  const RodlabLeastSquares& p_;
};

/// Stops successfully where the caller says so, after an accepted step.
class Stop final : public ceres::IterationCallback {
 public:
  explicit Stop(const RodlabLeastSquares& p) : p_(p) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (summary.iteration == 0 || !summary.step_is_successful) return ceres::SOLVER_CONTINUE;
    return p_.accepted_step(p_.user, summary.step_norm) ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                                         : ceres::SOLVER_CONTINUE;
  }

 private:
  const RodlabLeastSquares& p_;
};

void solve(const RodlabLeastSquares* p, RodlabLeastSquaresSummary* out) {
  Cost cost(*p);
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  problem.AddResidualBlock(&cost, nullptr, p->x);
  for (int k = 0; k < p->parameters; ++k) {
    problem.SetParameterLowerBound(p->x, k, p->lower[k]);
    problem.SetParameterUpperBound(p->x, k, p->upper[k]);
  }
  Stop stop(*p);
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.initial_trust_region_radius = p->initial_trust_region_radius;
  so.max_num_iterations = p->max_iterations;
  so.function_tolerance = p->function_tolerance;
  so.gradient_tolerance = p->gradient_tolerance;
  so.parameter_tolerance = p->parameter_tolerance;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  so.callbacks.push_back(&stop);
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  out->usable = summary.IsSolutionUsable() ? 1 : 0;
  out->no_convergence = summary.termination_type == ceres::NO_CONVERGENCE ? 1 : 0;
  const std::size_t n = std::min(summary.message.size(), sizeof(out->message) - 1);
  std::memcpy(out->message, summary.message.data(), n);
  out->message[n] = '\0';
}

constexpr RodlabCeresApi kApi{&solve};

}  // namespace

extern "C" __attribute__((visibility("default"))) const RodlabCeresApi* rodlab_ceres_api() {
  return &kApi;
}
