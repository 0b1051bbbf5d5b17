#include "rodlab/solvers/control/inverse_statics.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <stdexcept>

#include "ceres_module.hpp"
#include "rodlab/check.hpp"
#include "rodlab/module.hpp"
#include "rodlab/solvers/common/box_qp.hpp"
#include "rodlab/solvers/statics/chebyshev_tracker.hpp"
#include "rodlab/solvers/statics/workspace.hpp"

namespace rodlab::solvers::control {
namespace {

using Eigen::VectorXd;
using Matrix3X = statics::ChebyshevTracker::TipJacobian;

/// Central-difference step of each input for the scalars dF_k/du_k and d target/du_k inside
/// ChebyshevTracker::tip_jacobian, as a fraction of its scale s_k.
constexpr double kSensitivityStep = 1e-6;
/// A step is accepted when the cost falls by at least this fraction of the predicted fall.
constexpr double kAcceptRatio = 1e-4;
/// Damping trials per update before it gives up (each one statics solve).
constexpr int kMaxDampingTrials = 30;
/// Nothing moves: the box QP's step is below this (scaled inputs): a KKT point.
constexpr double kStationaryStep = 1e-12;
/// The first damping after a rejected undamped step, relative to the largest diagonal of J^T J.
constexpr double kInitialDamping = 1e-3;
/// Keeps the step's matrix positive definite without regularisation (relative to its diagonal).
constexpr double kDiagonalFloor = 1e-14;
/// An accepted step that lowers the cost by less than this fraction: converged (rounding level).
constexpr double kStalledFall = 1e-15;
/// Ceres: initial trust-region radius, pure Gauss-Newton steps at first (with damping above the
/// regularisation weight the step would barely move along the null space of J).
constexpr double kCeresInitialRadius = 1e12;

/// The forward model p(u) and dp/du: the tracked statics, solved at most once per point and
/// differentiated at most once per point (a Jacobian evaluation is one update).
class TipModel {
 public:
  TipModel(statics::ChebyshevTracker& tracker, const VectorXd& scale) : tracker_(tracker) {
    steps_ = kSensitivityStep * scale;
    u_.resize(scale.size());
  }
  int updates = 0, solves = 0, newton_iterations = 0;
  std::string failure;  ///< the last forward solve's reason, if it failed

  void reset_counters() {
    updates = solves = newton_iterations = 0;
    failure.clear();
  }
  bool solve_at(const double* u) {
    const auto m = u_.size();
    if (have_ && std::equal(u, u + m, u_.data())) return true;
    std::copy(u, u + m, u_.data());
    have_jacobian_ = false;
    ++solves;
    have_ = tracker_.solve(std::span<const double>(u, m));
    newton_iterations += tracker_.iterations();
    if (!have_) failure = tracker_.reason();
    return have_;
  }
  const Vector3& tip() const { return tracker_.tip_position(); }
  /// dp/du at the last solved point (after a successful solve_at): (4.10)'s J, exact
  /// (ChebyshevTracker::tip_jacobian).
  bool jacobian(Matrix3X& J) {
    if (!have_jacobian_) {
      ++updates;
      if (!tracker_.tip_jacobian(std::span<const double>(steps_.data(), steps_.size()), J_)) {
        failure = "singular statics Newton matrix at the equilibrium (no sensitivity)";
        return false;
      }
      have_jacobian_ = true;
    }
    J = J_;
    return true;
  }

 private:
  statics::ChebyshevTracker& tracker_;
  VectorXd steps_, u_;
  bool have_ = false, have_jacobian_ = false;
  Matrix3X J_;
};

/// The problem's data for one target.
struct Problem {
  TipModel& model;
  Vector3 target;
  const VectorXd& scale;  ///< s_k
  double weight, length;
  const std::vector<std::pair<double, double>>& limits;
  /// |p - p*|^2 / L^2 + w |u / s|^2 at the model's current point u.
  double cost(const VectorXd& u) const {
    return (model.tip() - target).squaredNorm() / (length * length) +
           weight * u.cwiseQuotient(scale).squaredNorm();
  }
};

/// What a method returns; the caller fills the rest of the result.
struct Outcome {
  bool converged = false;
  std::string failure;  ///< why the method stopped without converging
};

/// The Gauss-Newton model at u in the scaled inputs v = u / s: residual [e / L; sqrt(w) v],
/// Jacobian [dp/du diag(s) / L; sqrt(w) I]; the step d minimises
/// 1/2 d^T (H0 + mu I) d + g^T d within lo <= d <= hi (the limits, shifted by v).
struct LinearModel {
  explicit LinearModel(int m) : Jv(3, m), H0(m, m), H(m, m), g(m), lo(m), hi(m), v(m), delta(m) {}

  void build(const Problem& P, const VectorXd& u, const Matrix3X& dpdu) {
    const int m = static_cast<int>(u.size());
    Jv = dpdu * P.scale.asDiagonal() / P.length;
    v = u.cwiseQuotient(P.scale);
    const Vector3 e = (P.model.tip() - P.target) / P.length;
    H0.noalias() = Jv.transpose() * Jv;
    H0.diagonal().array() += P.weight + kDiagonalFloor * H0.diagonal().maxCoeff();
    g.noalias() = Jv.transpose() * e;
    g += P.weight * v;
    for (int k = 0; k < m; ++k) {
      lo[k] = P.limits[k].first / P.scale[k] - v[k];
      hi[k] = P.limits[k].second / P.scale[k] - v[k];
    }
  }
  /// The damped step into `delta`; false if the box QP fails.
  bool step(double mu) {
    H = H0;
    H.diagonal().array() += mu;
    const BoxQpResult qp = solve_box_qp(H, g, lo, hi, Eigen::VectorXd::Zero(g.size()));
    delta = qp.x;
    return qp.ok;
  }
  /// The fall of the cost the undamped model predicts for `delta`.
  double predicted_fall() const { return -(2.0 * g.dot(delta) + delta.dot(H0 * delta)); }

  Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, statics::StaticProblem::kMaxActuators> Jv;
  Eigen::MatrixXd H0, H;
  Eigen::VectorXd g, lo, hi, v, delta;
};

/// Bounded Gauss-Newton with Levenberg-Marquardt damping (inverse_statics.hpp, "SOLVER"), in place
/// of (4.11)'s q <- q - 0.2 J^-1 e. u: feasible start on entry, the solution on return; the model
/// is left solved at u.
Outcome gauss_newton(const Problem& P, const InverseStaticsOptions& o, VectorXd& u) {
  const int m = static_cast<int>(u.size());
  Outcome out;
  if (!P.model.solve_at(u.data())) {
    out.failure = "the statics did not converge at the initial inputs: " + P.model.failure;
    return out;
  }
  double cost = P.cost(u), mu = 0.0, nu = 2.0;
  Matrix3X dpdu;
  LinearModel model(m);
  VectorXd trial(m);
  while (P.model.updates < o.max_updates) {
    if (!P.model.jacobian(dpdu)) {
      out.failure = P.model.failure;
      return out;
    }
    model.build(P, u, dpdu);
    bool accepted = false;
    for (int trials = 0; trials < kMaxDampingTrials && !accepted; ++trials) {
      if (!model.step(mu)) {
        out.failure = "the bounded step (box QP) did not converge";
        return out;
      }
      const double step = model.delta.lpNorm<Eigen::Infinity>();
      // No input moves although the damping is no larger than the model's curvature: a KKT point.
      if (step <= kStationaryStep && mu <= model.H0.diagonal().maxCoeff()) {
        out.converged = P.model.solve_at(u.data());
        return out;
      }
      for (int k = 0; k < m; ++k)
        trial[k] = std::clamp((model.v[k] + model.delta[k]) * P.scale[k], P.limits[k].first, P.limits[k].second);
      const bool solved = P.model.solve_at(trial.data());
      const double new_cost = solved ? P.cost(trial) : cost, predicted = model.predicted_fall();
      const double rho = solved && predicted > 0.0 ? (cost - new_cost) / predicted : -1.0;
      if (!(rho > kAcceptRatio)) {
        mu = mu == 0.0 ? kInitialDamping * model.H0.diagonal().maxCoeff() : mu * nu;
        nu *= 2.0;
        continue;
      }
      accepted = true;
      u = trial;
      const double fall = cost - new_cost;
      cost = new_cost;
      mu *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3));  // Nielsen
      nu = 2.0;
      const bool near = (P.model.tip() - P.target).norm() <= o.tolerance;
      out.converged = (near && step <= o.step_tolerance) || fall <= kStalledFall * cost;
      if (out.converged) return out;
    }
    if (!accepted) {
      P.model.solve_at(u.data());
      out.failure = rodlab::format("no decrease within {} damping trials{}", kMaxDampingTrials,
                                   P.model.failure.empty() ? "" : " (last statics failure: " + P.model.failure + ")");
      return out;
    }
  }
  out.failure = rodlab::format("no convergence within {} updates", o.max_updates);
  return out;
}

/// Method ceres: the forward model as residuals [(p(u) - p*) / L; sqrt(w) u_k / s_k] with their
/// Jacobian [dp/du / L; sqrt(w) diag(1 / s_k)], and the stop once the tip is within tolerance
/// after a small accepted step, for the Ceres module (ceres_module.hpp).
struct CeresTip {
  const Problem& P;
  double sqrt_w, tolerance, step_bound;
  Matrix3X dpdu;

  static int evaluate(void* self, const double* u, double* r, double* jacobian) {
    auto& c = *static_cast<CeresTip*>(self);
    const Problem& P = c.P;
    const int m = static_cast<int>(P.scale.size());
    if (!P.model.solve_at(u)) return 0;
    Eigen::Map<Vector3> tip_rows(r);
    tip_rows = (P.model.tip() - P.target) / P.length;
    for (int k = 0; k < m; ++k) r[3 + k] = c.sqrt_w * u[k] / P.scale[k];
    if (!jacobian) return 1;
    if (!P.model.jacobian(c.dpdu)) return 0;
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(
        jacobian, 3 + m, m);
    J.topRows<3>() = c.dpdu / P.length;
    J.bottomRows(m) = (c.sqrt_w * P.scale.cwiseInverse()).asDiagonal();
    return 1;
  }
  // The model holds the accepted point: Ceres evaluated its Jacobian there last.
  static int accepted_step(void* self, double step_norm) {
    const auto& c = *static_cast<const CeresTip*>(self);
    return (c.P.model.tip() - c.P.target).norm() <= c.tolerance && step_norm <= c.step_bound;
  }
};

/// The same problem through Ceres (method ceres; for comparison, inverse_statics.hpp).
Outcome ceres_solve(const Problem& P, const InverseStaticsOptions& o, VectorXd& u) {
  std::string why;
  const auto* ceres = load_module_api<RodlabCeresApi>(RODLAB_CERES_MODULE,
                                                      kRodlabCeresApiSymbol, why);
  if (!ceres)
    throw std::runtime_error(
        rodlab::format("inverse statics: method ceres needs the Ceres module ({})", why));
  const int m = static_cast<int>(u.size());
  CeresTip tip{P, std::sqrt(P.weight), o.tolerance, o.step_tolerance * P.scale.norm(), {}};
  VectorXd lower(m), upper(m);
  for (int k = 0; k < m; ++k) lower[k] = P.limits[k].first, upper[k] = P.limits[k].second;
  RodlabLeastSquares problem{3 + m, m, u.data(), lower.data(), upper.data(),
                             &CeresTip::evaluate, &CeresTip::accepted_step, &tip,
                             kCeresInitialRadius, o.max_updates,
                             /*function_tolerance=*/1e-12, /*gradient_tolerance=*/1e-14,
                             /*parameter_tolerance=*/1e-10};
  RodlabLeastSquaresSummary summary{};
  ceres->solve(&problem, &summary);
  Outcome out;
  const bool solved = P.model.solve_at(u.data());  // Ceres may end on a rejected trial point
  out.converged = solved && summary.usable && !summary.no_convergence;
  if (!out.converged)
    out.failure = solved ? std::string("Ceres: ") + summary.message
                         : "the statics did not converge at the returned inputs: " + P.model.failure;
  return out;
}

std::vector<std::pair<double, double>> input_limits(const scene::Scene& scene_in) {
  scene::Scene scene = scene_in;  // workspace_inputs points into the scene it is given
  std::vector<std::pair<double, double>> limits;
  try {
    for (const auto& in : statics::workspace_inputs(scene)) limits.push_back(in.limits);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(rodlab::format("inverse statics: {}", e.what()));
  }
  RODLAB_THROW_UNLESS(static_cast<int>(limits.size()) <= statics::StaticProblem::kMaxActuators,
                      "inverse statics: at most {} actuators, got {}",
                      statics::StaticProblem::kMaxActuators, limits.size());
  for (std::size_t k = 0; k < limits.size(); ++k)
    RODLAB_THROW_UNLESS(limits[k].first <= limits[k].second && std::isfinite(limits[k].first) &&
                            std::isfinite(limits[k].second),
                        "inverse statics: actuators.{}: limits [{:g}, {:g}] are not an interval", k,
                        limits[k].first, limits[k].second);
  return limits;
}

/// The options, after checking that the scene's tip is free (a clamped tip has no target).
const InverseStaticsOptions& free_tip(const scene::Scene& scene, const InverseStaticsOptions& o) {
  RODLAB_THROW_UNLESS(!scene.tip_clamped(), "inverse statics needs a free tip (`tip: free`), got a clamped one");
  return o;
}

statics::ChebyshevOptions forward_options(const InverseStaticsOptions& o) {
  RODLAB_THROW_UNLESS(o.statics.scheme == "chebyshev",
                      "inverse statics runs on `chebyshev` (its Newton system gives the exact "
                      "sensitivities), got `{}`",
                      o.statics.scheme);
  RODLAB_THROW_UNLESS(o.tolerance > 0.0 && o.regularization >= 0.0 && o.max_updates >= 1 && o.step_tolerance > 0.0,
                      "inverse statics: tolerance > 0, regularization >= 0, max_updates >= 1 and "
                      "step_tolerance > 0 (got {:g}, {:g}, {}, {:g})",
                      o.tolerance, o.regularization, o.max_updates, o.step_tolerance);
  return {o.statics.nodes, o.statics.tol, o.statics.max_iterations, 0};
}

}  // namespace

struct InverseStatics::Impl {
  Impl(const scene::Scene& scene, const InverseStaticsOptions& o)
      : options(free_tip(scene, o)),
        limits(input_limits(scene)),
        tracker(statics::StaticProblem::from_scene(scene, o.statics.time), forward_options(o)),
        length(scene.rod.length) {
    const int m = static_cast<int>(limits.size());
    scale.resize(m);
    u = VectorXd::Zero(m);
    for (int k = 0; k < m; ++k) {
      const auto [lo, hi] = limits[k];
      scale[k] = std::max(std::abs(lo), std::abs(hi));
      if (!(scale[k] > 0.0)) scale[k] = 1.0;
      u[k] = std::clamp(0.0, lo, hi);
    }
    model.emplace(tracker, scale);
  }

  InverseStaticsResult solve(const Vector3& target, const VectorXd& u0);

  InverseStaticsOptions options;
  std::vector<std::pair<double, double>> limits;
  statics::ChebyshevTracker tracker;
  double length;
  VectorXd scale, u;
  std::optional<TipModel> model;
};

InverseStaticsResult InverseStatics::Impl::solve(const Vector3& target, const VectorXd& u0) {
  const auto start = std::chrono::steady_clock::now();
  const int m = static_cast<int>(limits.size());
  RODLAB_THROW_UNLESS(u0.size() == m, "inverse statics: expected {} initial inputs, got {}", m, u0.size());
  RODLAB_THROW_UNLESS(target.allFinite(), "inverse statics: the target is not finite");
  InverseStaticsResult out;
  out.u = u0;
  for (int k = 0; k < m; ++k) out.u[k] = std::clamp(out.u[k], limits[k].first, limits[k].second);
  model->reset_counters();
  const Problem P{*model, target, scale, options.regularization, length, limits};
  const Outcome o = options.method == InverseStaticsMethod::ceres ? ceres_solve(P, options, out.u)
                                                                  : gauss_newton(P, options, out.u);
  const bool solved = model->solve_at(out.u.data());
  out.updates = model->updates;
  out.statics_solves = model->solves;
  out.newton_iterations = model->newton_iterations;
  out.tip = model->tip();
  out.error = (out.tip - target).norm();
  out.converged = solved && o.converged;
  out.reached = solved && out.error <= options.tolerance;
  if (!solved) {
    out.reason = "the statics did not converge at the returned inputs: " + model->failure;
  } else if (!out.converged) {
    out.reason = o.failure;
  } else if (!out.reached) {
    std::string at_limits;
    for (int k = 0; k < m; ++k)
      if (out.u[k] <= limits[k].first || out.u[k] >= limits[k].second)
        at_limits += rodlab::format("{}{}", at_limits.empty() ? "" : ", ", k);
    out.reason = rodlab::format(
        "unreachable within the input limits: the closest tip is {:g} m from the target (tolerance "
        "{:g} m){}",
        out.error, options.tolerance,
        at_limits.empty() ? std::string() : " with actuators " + at_limits + " at their limits");
  }
  if (solved) u = out.u;
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

InverseStatics::InverseStatics(const scene::Scene& scene, const InverseStaticsOptions& options)
    : impl_(std::make_unique<Impl>(scene, options)) {}
InverseStatics::~InverseStatics() = default;
InverseStatics::InverseStatics(InverseStatics&&) noexcept = default;
InverseStatics& InverseStatics::operator=(InverseStatics&&) noexcept = default;

int InverseStatics::inputs() const { return static_cast<int>(impl_->limits.size()); }
const std::vector<std::pair<double, double>>& InverseStatics::limits() const { return impl_->limits; }
InverseStaticsResult InverseStatics::solve(const Vector3& target_world) {
  return impl_->solve(target_world, impl_->u);
}
InverseStaticsResult InverseStatics::solve(const Vector3& target_world, const Eigen::VectorXd& u0) {
  return impl_->solve(target_world, u0);
}

InverseStaticsResult solve_inverse_statics(const scene::Scene& scene, const Vector3& target_world,
                                           const InverseStaticsOptions& options, const Eigen::VectorXd& u0) {
  InverseStatics solver(scene, options);
  return u0.size() == 0 ? solver.solve(target_world) : solver.solve(target_world, u0);
}

}  // namespace rodlab::solvers::control
