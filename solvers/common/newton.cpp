#include "rodlab/solvers/common/newton.hpp"

#include <cmath>

#include <Eigen/LU>
#include <Eigen/QR>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/deadline.hpp"

namespace rodlab::solvers {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

struct Evaluator {
  const Residual& F;
  int count = 0;
  bool operator()(const VectorXd& x, VectorXd& out) {
    ++count;
    return F(x, out) && out.allFinite();
  }
};

bool fd_jacobian(Evaluator& eval, const VectorXd& x, VectorXd Fx, double step, MatrixXd& J,
                 bool own_base) {
  if (own_base && !eval(x, Fx)) return false;  // a separate Jacobian residual needs its own F(x)
  const Eigen::Index n = x.size();
  J.resize(Fx.size(), n);
  VectorXd xp = x, Fp(Fx.size());
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = step * std::max(1.0, std::abs(x[j]));
    xp[j] = x[j] + h;
    if (!eval(xp, Fp)) {  // try the other side before giving up
      xp[j] = x[j] - h;
      if (!eval(xp, Fp)) return false;
      J.col(j) = (Fx - Fp) / h;
    } else {
      J.col(j) = (Fp - Fx) / h;
    }
    xp[j] = x[j];
  }
  return true;
}

/// The Newton step -J^-1 F by column-pivoted Householder QR (a rank-deficient J gives its basic
/// solution). Six unknowns, the single-shooting statics' base wrench, take a fixed-size QR: the
/// same algorithm inlined here, where the dynamic one runs Eigen's out-of-line Householder and
/// GEMV kernels, whose code a fresh process faults in (6 of the 7 page faults of a cold
/// rkmk-euler-explicit solve at N = 100, about 30 us of it; docs/statics.md "Cold and warm
/// solves").
VectorXd newton_step(const MatrixXd& J, const VectorXd& F) {
  if (J.rows() == 6 && J.cols() == 6) {
    using Matrix6d = Eigen::Matrix<double, 6, 6>;
    using Vector6d = Eigen::Matrix<double, 6, 1>;
    return -Eigen::ColPivHouseholderQR<Matrix6d>(Matrix6d(J)).solve(Vector6d(F));
  }
  return -J.colPivHouseholderQr().solve(F);
}

/// Broyden's rank-one update of J for the step s that changed F by dF (the secant J s = dF).
void broyden_update(MatrixXd& J, const VectorXd& s, const VectorXd& dF) {
  J += (dF - J * s) * s.transpose() / s.squaredNorm();
}

}  // namespace

NewtonResult solve_newton(const Residual& F, VectorXd x0, const NewtonOptions& options) {
  NewtonResult out;
  Evaluator eval{F};
  Evaluator jacobian_eval{options.jacobian_residual ? options.jacobian_residual : F};
  const bool separate_jacobian = static_cast<bool>(options.jacobian_residual);
  out.x = std::move(x0);
  out.F.resize(out.x.size());
  auto finish = [&](bool converged, std::string reason) {
    out.converged = converged;
    out.reason = std::move(reason);
    out.residual_norm = out.F.size() ? out.F.lpNorm<Eigen::Infinity>() : 0.0;
    out.evaluations = eval.count + (separate_jacobian ? jacobian_eval.count : 0);
    return out;
  };
  if (!eval(out.x, out.F)) {
    out.F.setConstant(std::numeric_limits<double>::infinity());
    return finish(false, "the residual is not finite at the initial guess");
  }

  MatrixXd J;
  bool have_J = false;  // J is usable: a finite-difference Jacobian or its Broyden update
  bool J_is_fd = false; // J is a finite-difference Jacobian at the current x
  VectorXd x_new(out.x.size()), F_new(out.F.size());
  // Within the residual's tolerance, another step where the last Jacobian (fresh, updated or due
  // for a refresh) puts the root further than step_tol from x, kept where it lowers |F|_2
  // (NewtonOptions::step_tol). True where it was taken.
  auto polished = [&] {
    if (options.step_tol <= 0.0 || J.size() == 0) return false;
    const VectorXd dx = newton_step(J, out.F);
    if (!dx.allFinite() || dx.lpNorm<Eigen::Infinity>() <= options.step_tol) return false;
    x_new = out.x + dx;
    if (!eval(x_new, F_new) || F_new.norm() >= out.F.norm()) return false;
    if (options.broyden) broyden_update(J, dx, F_new - out.F);
    J_is_fd = false;
    out.x = x_new;
    out.F = F_new;
    return true;
  };
  for (out.iterations = 0; out.iterations < options.max_iterations; ++out.iterations) {
    check_deadline();  // the run's wall-time guard (deadline.hpp)
    if (out.F.lpNorm<Eigen::Infinity>() <= options.tol) {
      if (polished()) continue;
      return finish(true, "");
    }
    if (!have_J) {
      Evaluator& je = separate_jacobian ? jacobian_eval : eval;
      if (options.jacobian ? !options.jacobian(out.x, out.F, J)
                           : !fd_jacobian(je, out.x, out.F, options.fd_step, J, separate_jacobian))
        return finish(false, "the residual is not finite near the current iterate");
      have_J = J_is_fd = true;
    }
    const VectorXd dx = newton_step(J, out.F);
    if (!dx.allFinite()) return finish(false, "singular Jacobian");

    // Backtracking on |F|_2 (Armijo with a small slope fraction).
    const double f0 = out.F.norm();
    double alpha = 1.0;
    bool accepted = false;
    for (int k = 0; k < 12; ++k, alpha *= 0.5) {
      x_new = out.x + alpha * dx;
      if (eval(x_new, F_new) && F_new.norm() <= (1.0 - 1e-4 * alpha) * f0) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      if (J_is_fd) {
        if (options.rounding_floor &&
            out.F.lpNorm<Eigen::Infinity>() <= options.rounding_floor(out.x))
          return finish(true, "");
        return finish(false, "line search failed to reduce the residual");
      }
      have_J = false;  // a stale Broyden Jacobian: refresh it and retry from the same x
      continue;
    }
    if (alpha < 1.0) ++out.backtracks;
    const VectorXd s = x_new - out.x;
    const double ratio = F_new.norm() / f0;
    if (options.broyden && ratio < 0.5) {
      broyden_update(J, s, F_new - out.F);
      J_is_fd = false;
    } else {
      have_J = false;  // slow progress: a fresh Jacobian at the new point
    }
    out.x = x_new;
    out.F = F_new;
  }
  if (out.F.lpNorm<Eigen::Infinity>() <= options.tol) return finish(true, "");
  return finish(false, rodlab::format("no convergence within {} Newton iterations",
                                      options.max_iterations));
}

}  // namespace rodlab::solvers
