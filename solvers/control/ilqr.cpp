#include "rodlab/solvers/control/ilqr.hpp"

#include <cmath>

#include <Eigen/Cholesky>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/box_qp.hpp"

namespace rodlab::solvers::control {
namespace {

constexpr int kLineSearchSteps = 10;

/// The linearisation of one stage.
struct Stage {
  Eigen::MatrixXd A, B, l_xx, l_uu, l_ux;
  Eigen::VectorXd l_x, l_u;
};

/// The nominal rollout: states kept by the model, cost J. False when a step fails.
bool nominal(IlqrModel& model, const std::vector<Eigen::VectorXd>& u,
             std::vector<Eigen::VectorXd>& x, double& J) {
  model.reset();
  J = 0.0;
  for (std::size_t k = 0; k < u.size(); ++k) {
    model.keep(static_cast<int>(k));
    model.state(x[k]);
    if (!model.step(static_cast<int>(k), u[k], J)) return false;
  }
  return std::isfinite(J);
}

/// The backward pass with regularisation mu; false when some Q_uu is not positive definite.
/// Fills the feed-forward k and feedback K, and the expected decrease's linear and quadratic
/// parts (dJ = alpha d1 + alpha^2 d2).
bool backward(const IlqrModel& model, const std::vector<Stage>& stages,
              const std::vector<Eigen::VectorXd>& u, double mu, std::vector<Eigen::VectorXd>& kff,
              std::vector<Eigen::MatrixXd>& K, double& d1, double& d2) {
  const int H = static_cast<int>(stages.size()), n = model.state_size(), m = model.input_size();
  Eigen::VectorXd Vx = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd Vxx = Eigen::MatrixXd::Zero(n, n);
  d1 = d2 = 0.0;
  for (int k = H - 1; k >= 0; --k) {
    const Stage& s = stages[k];
    const Eigen::VectorXd Qx = s.l_x + s.A.transpose() * Vx;
    const Eigen::VectorXd Qu = s.l_u + s.B.transpose() * Vx;
    const Eigen::MatrixXd VB = Vxx * s.B;
    const Eigen::MatrixXd Qxx = s.l_xx + s.A.transpose() * Vxx * s.A;
    Eigen::MatrixXd Quu = s.l_uu + s.B.transpose() * VB;
    Quu.diagonal().array() += mu;
    const Eigen::MatrixXd Qux = s.l_ux + VB.transpose() * s.A;
    const BoxQpResult qp =
        solve_box_qp(Quu, Qu, model.lower() - u[k], model.upper() - u[k], kff[k]);
    if (!qp.ok) return false;
    kff[k] = qp.x;
    // feedback on the free inputs only (box-DDP): K_f = -Q_uu,ff^-1 Q_ux,f
    K[k].setZero(m, n);
    std::vector<int> f;
    for (int i = 0; i < m; ++i)
      if (qp.free[i]) f.push_back(i);
    if (!f.empty()) {
      const int nf = static_cast<int>(f.size());
      Eigen::MatrixXd Qff(nf, nf), Qfx(nf, n);
      for (int a = 0; a < nf; ++a) {
        Qfx.row(a) = Qux.row(f[a]);
        for (int b = 0; b < nf; ++b) Qff(a, b) = Quu(f[a], f[b]);
      }
      const Eigen::LLT<Eigen::MatrixXd> llt(Qff);
      if (llt.info() != Eigen::Success) return false;
      const Eigen::MatrixXd Kf = -llt.solve(Qfx);
      for (int a = 0; a < nf; ++a) K[k].row(f[a]) = Kf.row(a);
    }
    const Eigen::VectorXd& kk = kff[k];
    d1 += kk.dot(Qu);
    d2 += 0.5 * kk.dot(Quu * kk);
    Vx = Qx + K[k].transpose() * (Quu * kk) + K[k].transpose() * Qu + Qux.transpose() * kk;
    Vxx = Qxx + K[k].transpose() * Quu * K[k] + K[k].transpose() * Qux + Qux.transpose() * K[k];
    Vxx = 0.5 * (Vxx + Vxx.transpose()).eval();
  }
  return true;
}

}  // namespace

IlqrResult solve_ilqr(IlqrModel& model, std::vector<Eigen::VectorXd> u, const IlqrOptions& o) {
  const int H = static_cast<int>(u.size()), n = model.state_size(), m = model.input_size();
  RODLAB_THROW_UNLESS(H >= 1, "ilqr: the horizon must be >= 1");
  for (auto& v : u) {
    RODLAB_THROW_UNLESS(v.size() == m, "ilqr: expected inputs of size {}, got {}", m, v.size());
    v = v.cwiseMax(model.lower()).cwiseMin(model.upper());
  }
  IlqrResult out;
  std::vector<Eigen::VectorXd> x(H, Eigen::VectorXd(n)), x_trial(H, Eigen::VectorXd(n)),
      kff(H, Eigen::VectorXd::Zero(m)), trial(H);
  std::vector<Eigen::MatrixXd> K(H);
  std::vector<Stage> stages(H);
  double J = 0.0;
  if (!nominal(model, u, x, J)) {
    out.reason = "ilqr: the rollout of the initial inputs failed";
    return out;
  }
  out.costs.push_back(J);
  double mu = o.initial_mu;
  bool linearised = false;
  for (out.iterations = 0; out.iterations < o.max_iterations; ++out.iterations) {
    for (int k = 0; k < H && !linearised; ++k) {
      Stage& s = stages[k];
      if (!model.linearise(k, u[k], s.A, s.B, s.l_x, s.l_u, s.l_xx, s.l_uu, s.l_ux)) {
        out.reason = "ilqr: a linearisation failed";
        return out;
      }
    }
    linearised = true;
    double d1 = 0.0, d2 = 0.0;
    while (!backward(model, stages, u, mu, kff, K, d1, d2)) {
      mu *= o.mu_factor;
      if (mu > o.max_mu) {
        out.reason = "ilqr: Q_uu stayed indefinite up to the largest regularisation";
        return out;
      }
    }
    bool accepted = false;
    double alpha = 1.0, J_new = 0.0;
    for (int ls = 0; ls < kLineSearchSteps && !accepted; ++ls, alpha *= 0.5) {
      model.reset();
      J_new = 0.0;
      bool ran = true;
      for (int k = 0; k < H && ran; ++k) {
        model.state(x_trial[k]);
        model.keep_trial(k);
        trial[k] = (u[k] + alpha * kff[k] + K[k] * (x_trial[k] - x[k]))
                       .cwiseMax(model.lower())
                       .cwiseMin(model.upper());
        ran = model.step(k, trial[k], J_new);
      }
      const double expected = -(alpha * d1 + alpha * alpha * d2);
      accepted = ran && std::isfinite(J_new) && J_new < J &&
                 J - J_new >= o.armijo * std::max(expected, 0.0);
    }
    if (!accepted) {
      if (mu >= o.max_mu || (std::abs(d1) <= o.tolerance * std::max(J, 1e-300))) break;
      mu *= o.mu_factor;  // a smaller, safer step next time
      continue;
    }
    u = trial;
    const double J_old = J;
    if (model.accept_trial()) {
      x.swap(x_trial);
      J = J_new;
    } else if (!nominal(model, u, x, J)) {
      out.reason = "ilqr: the rollout of the accepted inputs failed";
      return out;
    }
    out.costs.push_back(J);
    linearised = false;
    mu = std::max(o.initial_mu, mu / o.mu_factor);
    if (J_old - J <= o.tolerance * J_old) {
      ++out.iterations;
      break;
    }
  }
  out.ok = true;
  out.u = u;
  out.K = K;
  return out;
}

}  // namespace rodlab::solvers::control
