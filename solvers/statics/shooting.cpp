#include "rodlab/solvers/statics/shooting.hpp"

#include <algorithm>
#include <vector>

#include "rodlab/solvers/common/newton.hpp"
#include "rodlab/solvers/statics/continuation.hpp"
#include "rodlab/solvers/statics/multiple_shooting.hpp"
#include "rodlab/solvers/statics/result_builder.hpp"

namespace rodlab::solvers::statics {
namespace {

/// A direct Newton solve that needs more iterations than this (from the rigid-rod guess, ordinary
/// loads take 3-8) is checked by the load continuation, as one whose line search cut steps.
constexpr int kTrustedDirectIterations = 10;

using Eigen::VectorXd;

/// (2.34) marched back from the tip along the undeformed rod (xi = xi*) with classical RK4:
/// the internal wrench of the unloaded geometry in equilibrium with the loads. Actuator forces
/// are internal, so they enter only where a cable is pulled from outside (entry jumps).
/// Lambda is recorded at the ascending arclengths `samples` (steps are split there) into `out`.
void march_back_undeformed(const StaticProblem& P, int steps, std::span<const double> samples,
                           std::span<Vector6> out) {
  const rod::RodModel& model = P.model();
  const double L = P.length(), h = L / steps;
  auto rotation_at = [&](double s) { return P.base().rotation() * model.rest_rotation(s); };
  Vector6 xi = model.xi_star();  // the rest strain of the step in progress (steps split at breaks)
  auto f = [&](double s, const Vector6& Lambda) { return P.wrench_derivative(rotation_at(s), xi, Lambda); };
  auto rk4_back = [&](double s, double dh, Vector6& Lambda) {
    xi = model.xi_star(s - 0.5 * dh);
    const Vector6 k1 = f(s, Lambda);
    const Vector6 k2 = f(s - 0.5 * dh, Lambda - 0.5 * dh * k1);
    const Vector6 k3 = f(s - 0.5 * dh, Lambda - 0.5 * dh * k2);
    const Vector6 k4 = f(s - dh, Lambda - dh * k3);
    Lambda -= dh * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
  };
  const auto& breaks = P.breakpoints();
  int next_break = static_cast<int>(breaks.size()) - 1;
  Vector6 Lambda = P.tip_load(rotation_at(L));
  int next_sample = static_cast<int>(samples.size()) - 1;
  auto record = [&](double s) {
    for (; next_sample >= 0 && samples[next_sample] >= s; --next_sample) out[next_sample] = Lambda;
  };
  record(L);
  for (int i = steps; i > 0; --i) {
    double s = i * h;
    const double s_end = (i - 1) * h;
    while (s > s_end) {
      double b = (next_break >= 0 && breaks[next_break] > s_end) ? breaks[next_break] : s_end;
      if (next_sample >= 0 && samples[next_sample] > b) b = samples[next_sample];
      rk4_back(s, s - b, Lambda);
      s = b;
      if (next_break >= 0 && breaks[next_break] == b) {
        Lambda -= P.entry_jump(b, xi);
        --next_break;
      }
      record(s);
    }
  }
}

class ShootingSolver {
 public:
  static constexpr int kJacobianNodes = 11;

  ShootingSolver(const StaticProblem& problem, RkmkMethod method, const ShootingOptions& options)
      : P_(problem), method_(method), options_(options), extra_(problem.extra_unknowns()) {}

  /// Newton on x = [Lambda(0) / wrench_scale; extra unknowns] at one load factor; the residual
  /// is [tip conditions; actuator length conditions].
  NewtonResult solve_at(double load_factor, const VectorXd& guess) {
    P_.set_load_factor(load_factor);
    Residual F = [&](const VectorXd& x, VectorXd& r) {
      set_state(x);
      const auto end = shoot(P_, method_, options_.nodes, base_wrench(x));
      if (!end.ok) return false;
      r.resize(6 + extra_);
      r.head<6>() = P_.tip_residual(end.tip.g, end.tip.Lambda);
      if (extra_) P_.extra_residuals(end.lengths, std::span<double>(r.data() + 6, extra_));
      return true;
    };
    NewtonOptions newton = newton_options();
    // The Jacobian of the continuous shooting map, approximated by a coarse RK4 integration
    // (about 10x cheaper than one fine integration per column); Broyden corrects the rest.
    // Only for rk4: for the low-order methods the coarse Jacobian is far from their own
    // discrete one, and the first Newton step can land in another equilibrium's basin (seen on
    // the elastica with rkmk-euler-implicit at PL^2/EI = 10).
    // Not from a given start (ShootingOptions::base_wrench_guess): such a rod may turn many times
    // within a coarse step (the localised helix of the literature family failed with it).
    if (method_ == RkmkMethod::rk4 && options_.nodes > 2 * kJacobianNodes &&
        !options_.base_wrench_guess) {
      newton.jacobian_residual = [&](const VectorXd& x, VectorXd& r) {
        set_state(x);
        const auto end = shoot(P_, RkmkMethod::rk4, kJacobianNodes, base_wrench(x));
        if (!end.ok) return false;
        r.resize(6 + extra_);
        r.head<6>() = P_.tip_residual(end.tip.g, end.tip.Lambda);
        if (extra_) P_.extra_residuals(end.lengths, std::span<double>(r.data() + 6, extra_));
        return true;
      };
    }
    auto result = solve_newton(F, guess, newton);
    iterations_ += result.iterations;
    return result;
  }

  /// Initial guess at a load factor: the equilibrium of the undeformed rod (exact to first
  /// order in the loads for a free tip; zero, the exact unloaded answer, for a clamped one),
  /// zero actuator forces and rest lengths.
  VectorXd rigid_guess(double load_factor) {
    P_.set_load_factor(load_factor);
    VectorXd x(6 + extra_);
    const auto z = P_.extra_initial_guess();
    for (int j = 0; j < extra_; ++j) x[6 + j] = z[j];
    P_.set_extra_unknowns(z);
    x.head<6>() = rigid_base_wrench(P_, options_.nodes - 1).cwiseQuotient(P_.wrench_scale());
    return x;
  }

  result::StaticResult run() {
    VectorXd start = rigid_guess(1.0);
    if (options_.base_wrench_guess)
      start.head<6>() = options_.base_wrench_guess->cwiseQuotient(P_.wrench_scale());
    NewtonResult direct = solve_at(1.0, start);
    VectorXd x = direct.x;
    bool converged = direct.converged;
    std::string reason = direct.reason;
    double residual = direct.residual_norm;
    // The direct-solve rule (kinsol has its own): a direct solve whose line search had to cut
    // steps, or that wandered for many iterations, may have jumped to another equilibrium branch
    // (under a large dead load, an unstable one: the rod folded back over its base; measured with
    // rkmk-rk4 at P L^2/EI = 41, tests/statics/test_dead_load_branch).
    // The load continuation, by multiple shooting, follows the branch from the unloaded rod and
    // decides; a converged direct solution is kept if the continuation fails; if neither
    // converged, multiple shooting at the full load.
    const bool own_start = options_.base_wrench_guess.has_value();
    std::vector<Node> path(options_.nodes);
    bool marched = false;  // path holds the solution (or the best state) of multiple shooting
    if (!own_start &&
        (!converged || direct.backtracks > 0 || direct.iterations > kTrustedDirectIterations)) {
      MultipleShooting ms(P_, method_, options_.nodes);
      const ContinuationResult cont = continuation(ms);
      P_.set_load_factor(1.0);
      if (cont.converged && ms.path(cont.state, path)) {
        converged = marched = true;
        residual = cont.residual_norm;
        reason.clear();
      } else if (!converged) {
        reason = "direct Newton: " + reason + "; continuation: " + cont.reason;
        if (cont.load_factor == 1.0) {
          // On the branch at the full load, short only of the tolerance (the polish failed):
          // the result reports that state and its residual.
          marched = ms.path(cont.state, path);
          if (marched) residual = cont.residual_norm;
        } else {
          marched = converged = last_resort(ms, path, residual, reason);
        }
      }
    }
    if (!marched) {
      set_state(x);
      shoot(P_, method_, options_.nodes, base_wrench(x), path);
    }
    std::vector<double> s(options_.nodes);
    std::vector<SE3> g(options_.nodes);
    std::vector<Vector6> Lambda(options_.nodes);
    for (int i = 0; i < options_.nodes; ++i) {
      s[i] = P_.length() * i / (options_.nodes - 1);
      g[i] = path[i].g;
      Lambda[i] = path[i].Lambda;
    }
    result::StaticResult out;
    fill_static_result(P_, s, g, Lambda, out);
    out.scene = P_.name();
    out.converged = converged;
    out.reason = reason;
    out.iterations = iterations_;
    out.residual_norm = residual;
    check_cables_taut(P_, out);
    return out;
  }

 private:
  /// Multiple shooting at the full load from the reference configuration, as kinsol's last
  /// step: not held to the load path's branch. Measured: rkmk-euler-explicit at N = 5 under
  /// test_statics_robustness's large-shear constant twist, whose discrete load path stalls at
  /// load factor 0.54, reaches the closed form here. On success writes the path and residual
  /// and clears the reason; else adds to it.
  bool last_resort(const MultipleShooting& ms, std::vector<Node>& path, double& residual,
                   std::string& reason) {
    const NewtonResult last = ms.solve(ms.reference_guess(), newton_options());
    iterations_ += last.iterations;
    if (last.converged && ms.path(last.x, path)) {
      residual = last.residual_norm;
      reason.clear();
      return true;
    }
    reason += "; multiple shooting at the full load: " + last.reason;
    return false;
  }

  NewtonOptions newton_options() const {
    NewtonOptions newton;
    // The unknowns are wrenches in wrench_scale units: held to the residual's tolerance too.
    newton.tol = newton.step_tol = options_.tol;
    newton.max_iterations = options_.max_iterations;
    return newton;
  }
  Vector6 base_wrench(const VectorXd& x) const { return x.head<6>().cwiseProduct(P_.wrench_scale()); }
  void set_state(const VectorXd& x) {
    if (extra_) P_.set_extra_unknowns(std::span<const double>(x.data() + 6, extra_));
  }

  /// Walks the load factor from 0 (where the reference configuration solves exactly) to 1
  /// (continuation.hpp) with multiple shooting's corrector: single shooting's amplification
  /// made its correctors land on folded branches of large dead loads through clean steps
  /// (rkmk-midpoint-* at P L^2/EI = 30-80), or stall. The first step is predicted by the
  /// change of the reference configuration. A walk that fails below kWalkTol is walked again to
  /// it and polished at the full load (continue_load_to).
  ContinuationResult continuation(const MultipleShooting& ms) {
    auto walk_at = [this, &ms](double tol) {
      NewtonOptions corrector = newton_options();
      corrector.tol = tol;
      Continuation walk;
      walk.correct = [this, &ms, corrector](double lf, const VectorXd& guess) {
        P_.set_load_factor(lf);
        NewtonOptions at_lf = corrector;  // only the full load's state is the answer
        at_lf.step_tol = lf == 1.0 ? corrector.tol : 0.0;
        const NewtonResult r = ms.solve(guess, at_lf);
        iterations_ += r.iterations;
        // A corrector whose line search cut steps may have left the branch: a shorter step.
        const bool on_branch = r.converged && r.backtracks == 0;
        return CorrectorResult{on_branch, r.x, r.residual_norm,
                               r.converged && !on_branch ? "the corrector's line search cut steps"
                                                         : r.reason};
      };
      walk.first_predictor = [this, &ms](double from, double to, const VectorXd& x) {
        return VectorXd(x + reference_at(ms, to) - reference_at(ms, from));
      };
      return walk;
    };
    auto polish = [this, &ms](const VectorXd& state) {
      P_.set_load_factor(1.0);
      const NewtonResult r = ms.solve(state, newton_options());
      iterations_ += r.iterations;
      return CorrectorResult{r.converged, r.x, r.residual_norm, r.reason};
    };
    return continue_load_to(options_.tol, walk_at, reference_at(ms, 0.0), polish);
  }

  /// Multiple shooting's reference configuration at a load factor (the walk's start).
  VectorXd reference_at(const MultipleShooting& ms, double lf) {
    P_.set_load_factor(lf);
    return ms.reference_guess();
  }

  StaticProblem P_;
  RkmkMethod method_;
  ShootingOptions options_;
  int extra_;
  int iterations_ = 0;
};

}  // namespace

Vector6 rigid_base_wrench(const StaticProblem& problem, int steps) {
  const double base = 0.0;
  return rigid_wrench_profile(problem, std::span<const double>(&base, 1), steps).front();
}

std::vector<Vector6> rigid_wrench_profile(const StaticProblem& problem, std::span<const double> s,
                                          int steps) {
  std::vector<Vector6> Lambda(s.size(), Vector6::Zero());
  if (!problem.tip_clamped()) march_back_undeformed(problem, std::max(steps, 4), s, Lambda);
  return Lambda;
}

result::StaticResult solve_shooting(const StaticProblem& problem, RkmkMethod method,
                                    const ShootingOptions& options) {
  return ShootingSolver(problem, method, options).run();
}

}  // namespace rodlab::solvers::statics
