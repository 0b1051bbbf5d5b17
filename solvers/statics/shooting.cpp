#include "rodlab/solvers/statics/shooting.hpp"

#include <algorithm>
#include <vector>

#include "rodlab/solvers/common/newton.hpp"
#include "rodlab/solvers/statics/result_builder.hpp"

namespace rodlab::solvers::statics {
namespace {

using Eigen::VectorXd;

/// (2.34) marched back from the tip along the undeformed rod (xi = xi*) with classical RK4:
/// the internal wrench of the unloaded geometry in equilibrium with the loads.
Vector6 march_back_undeformed(const StaticProblem& P, int steps) {
  const Vector6& xi = P.model().xi_star();
  const double L = P.length(), h = L / steps;
  auto rotation_at = [&](double s) { return P.base().rotation() * SO3::exp(s * xi.head<3>()); };
  auto f = [&](double s, const Vector6& Lambda) { return P.wrench_derivative(rotation_at(s), xi, Lambda); };
  Vector6 Lambda = P.tip_load(rotation_at(L));
  for (int i = steps; i > 0; --i) {
    const double s = i * h;
    const Vector6 k1 = f(s, Lambda);
    const Vector6 k2 = f(s - 0.5 * h, Lambda - 0.5 * h * k1);
    const Vector6 k3 = f(s - 0.5 * h, Lambda - 0.5 * h * k2);
    const Vector6 k4 = f(s - h, Lambda - h * k3);
    Lambda -= h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
  }
  return Lambda;
}

class ShootingSolver {
 public:
  ShootingSolver(const StaticProblem& problem, RkmkMethod method, const ShootingOptions& options)
      : P_(problem), method_(method), options_(options) {}

  /// Newton on the scaled Lambda(0) at one load factor.
  NewtonResult solve_at(double load_factor, const Vector6& Lambda0_guess) {
    P_.set_load_factor(load_factor);
    const Vector6 scale = P_.wrench_scale();
    Residual F = [&](const VectorXd& x, VectorXd& r) {
      const auto end = shoot(P_, method_, options_.nodes, Vector6(x.cwiseProduct(scale)));
      if (!end.ok) return false;
      r = P_.tip_residual(end.tip.g, end.tip.Lambda);
      return true;
    };
    NewtonOptions newton;
    newton.tol = options_.tol;
    newton.max_iterations = options_.max_iterations;
    auto result = solve_newton(F, VectorXd(Lambda0_guess.cwiseQuotient(scale)), newton);
    iterations_ += result.iterations;
    return result;
  }

  Vector6 unscale(const VectorXd& x) const { return x.cwiseProduct(P_.wrench_scale()); }

  /// Initial guess at a load factor: the equilibrium of the undeformed rod (exact to first order
  /// in the loads for a free tip; zero, the exact unloaded answer, for a clamped one).
  Vector6 rigid_guess(double load_factor) {
    P_.set_load_factor(load_factor);
    return rigid_base_wrench(P_, options_.nodes - 1);
  }

  result::StaticResult run() {
    NewtonResult direct = solve_at(1.0, rigid_guess(1.0));
    Vector6 Lambda0 = unscale(direct.x);
    bool converged = direct.converged;
    std::string reason = direct.reason;
    double residual = direct.residual_norm;
    if (!converged) {
      auto cont = continuation();
      converged = cont.converged;
      if (converged) {
        Lambda0 = unscale(cont.x);
        residual = cont.residual_norm;
        reason.clear();
      } else {
        reason = "direct Newton: " + reason + "; continuation: " + cont.reason;
      }
    }
    P_.set_load_factor(1.0);
    std::vector<Node> path(options_.nodes);
    shoot(P_, method_, options_.nodes, Lambda0, path);
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
    return out;
  }

 private:
  /// Walks the load factor from 0 (where Lambda(0) = 0 solves exactly) to 1, with a secant
  /// predictor, growing the step after a success and halving it after a failure.
  NewtonResult continuation() {
    double lf = 0.0, lf_prev = 0.0, step = 0.25;
    Vector6 x = Vector6::Zero(), x_prev = Vector6::Zero();
    bool have_prev = false;
    NewtonResult last;
    for (int attempt = 0; attempt < 400 && lf < 1.0; ++attempt) {
      const double target = std::min(1.0, lf + step);
      Vector6 guess;
      if (have_prev) guess = x + (x - x_prev) * ((target - lf) / (lf - lf_prev));
      else guess = x + rigid_guess(target) - rigid_guess(lf);
      last = solve_at(target, guess);
      if (last.converged) {
        x_prev = x;
        lf_prev = lf;
        x = unscale(last.x);
        lf = target;
        have_prev = true;
        step = std::min(1.5 * step, 0.5);
      } else {
        step *= 0.5;
        if (step < 1e-4) {
          last.reason = "stalled at load factor " + std::to_string(lf) + " (" + last.reason + ")";
          return last;
        }
      }
    }
    if (lf < 1.0) last.converged = false;
    return last;
  }

  StaticProblem P_;
  RkmkMethod method_;
  ShootingOptions options_;
  int iterations_ = 0;
};

}  // namespace

Vector6 rigid_base_wrench(const StaticProblem& problem, int steps) {
  if (problem.tip_clamped()) return Vector6::Zero();
  return march_back_undeformed(problem, std::max(steps, 4));
}

result::StaticResult solve_shooting(const StaticProblem& problem, RkmkMethod method,
                                    const ShootingOptions& options) {
  return ShootingSolver(problem, method, options).run();
}

}  // namespace rodlab::solvers::statics
