#include "rodlab/solvers/learning/trajectory_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

void require_compatible(const LinearGaussianController& p, const LinearGaussianDynamics& d) {
  RODLAB_THROW_UNLESS(p.steps() == d.steps() && p.state_size() == d.state_size() &&
                          p.action_size() == d.action_size(),
                      "GPS: a controller of {} steps ({} states, {} actions) for dynamics of {} "
                      "steps ({} states, {} actions)",
                      p.steps(), p.state_size(), p.action_size(), d.steps(), d.state_size(),
                      d.action_size());
}

/// log det S from its Cholesky factor L.
double log_det(const Eigen::MatrixXd& L) { return 2.0 * L.diagonal().array().log().sum(); }

/// -log p(a | x) = 1/2 z^T M z + z^T v + const for p(a|x) = N(K x + k, S), P = S^-1:
/// M = [K^T P K, -K^T P; -P K, P], v = [K^T P k; -P k], const = 1/2 k^T P k + 1/2 log det S
/// (+ m/2 log 2 pi).
void negative_log_quadratic(const LinearGaussianController& p, int t, Eigen::MatrixXd& M,
                            Eigen::VectorXd& v) {
  const auto n = p.state_size(), m = p.action_size();
  const Eigen::MatrixXd PK = p.precision[t] * p.K[t];
  M.resize(n + m, n + m);
  M.topLeftCorner(n, n) = p.K[t].transpose() * PK;
  M.topRightCorner(n, m) = -PK.transpose();
  M.bottomLeftCorner(m, n) = -PK;
  M.bottomRightCorner(m, m) = p.precision[t];
  v.resize(n + m);
  v.head(n) = PK.transpose() * p.k[t];
  v.tail(m) = -p.precision[t] * p.k[t];
}

}  // namespace

TrajectoryDistribution propagate(const LinearGaussianController& p,
                                 const LinearGaussianDynamics& d) {
  require_compatible(p, d);
  const int T = p.steps();
  const auto n = p.state_size(), m = p.action_size();
  TrajectoryDistribution traj;
  traj.mean.resize(T);
  traj.covariance.resize(T);
  Eigen::VectorXd mx = d.x0_mean;
  Eigen::MatrixXd Sx = d.x0_covariance;
  for (int t = 0; t < T; ++t) {
    Eigen::VectorXd& mu = traj.mean[t];
    Eigen::MatrixXd& S = traj.covariance[t];
    mu.resize(n + m);
    mu.head(n) = mx;
    mu.tail(m) = p.K[t] * mx + p.k[t];
    S.resize(n + m, n + m);
    S.topLeftCorner(n, n) = Sx;
    S.topRightCorner(n, m) = Sx * p.K[t].transpose();
    S.bottomLeftCorner(m, n) = p.K[t] * Sx;
    S.bottomRightCorner(m, m) = p.K[t] * Sx * p.K[t].transpose() + p.covariance[t];
    if (t + 1 < T) {
      mx = d.F[t] * mu + d.f[t];
      Sx = d.F[t] * S * d.F[t].transpose() + d.covariance[t];
      Sx = 0.5 * (Sx + Sx.transpose()).eval();
    }
  }
  return traj;
}

double expected_cost(const TrajectoryDistribution& traj, const QuadraticCost& cost) {
  RODLAB_THROW_UNLESS(traj.mean.size() == cost.C.size(),
                      "GPS: a trajectory of {} steps for a cost of {}", traj.mean.size(),
                      cost.C.size());
  double sum = 0.0;
  for (std::size_t t = 0; t < traj.mean.size(); ++t) {
    const Eigen::VectorXd& mu = traj.mean[t];
    sum += 0.5 * (cost.C[t].cwiseProduct(traj.covariance[t])).sum() +
           0.5 * mu.dot(cost.C[t] * mu) + cost.c[t].dot(mu) + cost.c0[t];
  }
  return sum;
}

double kl_divergence(const TrajectoryDistribution& traj, const LinearGaussianController& p,
                     const LinearGaussianController& q) {
  RODLAB_THROW_UNLESS(p.steps() == q.steps() && p.steps() == static_cast<int>(traj.mean.size()),
                      "GPS: KL of controllers of {} and {} steps over {}", p.steps(), q.steps(),
                      traj.mean.size());
  // KL(p || q) = E_p[log p - log q] with log p(a|x) = -(1/2 z^T M_p z + z^T v_p + c_p)
  // - 1/2 log det S_p, and E[z^T A z] = mu^T A mu + tr(A Sigma).
  Eigen::MatrixXd Mp, Mq;
  Eigen::VectorXd vp, vq;
  double sum = 0.0;
  for (int t = 0; t < p.steps(); ++t) {
    negative_log_quadratic(p, t, Mp, vp);
    negative_log_quadratic(q, t, Mq, vq);
    const Eigen::MatrixXd dM = Mq - Mp;
    const Eigen::VectorXd& mu = traj.mean[t];
    const double cp = 0.5 * p.k[t].dot(p.precision[t] * p.k[t]);
    const double cq = 0.5 * q.k[t].dot(q.precision[t] * q.k[t]);
    const double kl = 0.5 * mu.dot(dM * mu) + 0.5 * dM.cwiseProduct(traj.covariance[t]).sum() +
                      mu.dot(vq - vp) + cq - cp + 0.5 * log_det(q.cholesky[t]) -
                      0.5 * log_det(p.cholesky[t]);
    sum += std::max(0.0, kl);
  }
  return sum;
}

std::optional<LinearGaussianController> kl_regularised_lqg(const LinearGaussianDynamics& d,
                                                           const QuadraticCost& cost,
                                                           const LinearGaussianController& q,
                                                           double eta, double nu) {
  require_compatible(q, d);
  RODLAB_THROW_UNLESS(eta > 0.0 && nu >= 0.0,
                      "GPS: eta must be positive and nu not negative (got {:g}, {:g})", eta, nu);
  const double cost_weight = 1.0 / (eta + nu), policy_weight = eta / (eta + nu);
  const int T = q.steps();
  const auto n = q.state_size(), m = q.action_size();
  LinearGaussianController p;
  p.K.resize(T);
  p.k.resize(T);
  p.covariance.resize(T);
  p.cholesky.resize(T);
  p.precision.resize(T);
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(n, n), Q, M;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n), qv, w;
  for (int t = T - 1; t >= 0; --t) {
    negative_log_quadratic(q, t, M, w);
    Q = cost_weight * cost.C[t] + policy_weight * M;
    qv = cost_weight * cost.c[t] + policy_weight * w;
    if (t + 1 < T) {
      Q += d.F[t].transpose() * V * d.F[t];
      qv += d.F[t].transpose() * (v + V * d.f[t]);
    }
    Q = 0.5 * (Q + Q.transpose()).eval();
    const Eigen::MatrixXd Qaa = Q.bottomRightCorner(m, m);
    Eigen::LLT<Eigen::MatrixXd> llt(Qaa);
    if (llt.info() != Eigen::Success || !Qaa.allFinite()) return std::nullopt;
    p.K[t] = -llt.solve(Q.bottomLeftCorner(m, n));
    p.k[t] = -llt.solve(qv.tail(m));
    p.precision[t] = Qaa;
    p.covariance[t] = llt.solve(Eigen::MatrixXd::Identity(m, m));
    p.covariance[t] = 0.5 * (p.covariance[t] + p.covariance[t].transpose()).eval();
    Eigen::LLT<Eigen::MatrixXd> cov(p.covariance[t]);
    if (cov.info() != Eigen::Success) return std::nullopt;
    p.cholesky[t] = cov.matrixL();
    V = Q.topLeftCorner(n, n) + Q.topRightCorner(n, m) * p.K[t];
    V = 0.5 * (V + V.transpose()).eval();
    v = qv.head(n) + Q.topRightCorner(n, m) * p.k[t];
  }
  return p;
}

KlStep kl_constrained_lqg(const LinearGaussianDynamics& d, const QuadraticCost& cost,
                          const LinearGaussianController& q, double epsilon, double eta0,
                          const KlStepOptions& o) {
  RODLAB_THROW_UNLESS(epsilon > 0.0 && o.min_eta > 0.0 && o.max_eta > o.min_eta &&
                          o.max_iterations >= 1 && o.tolerance > 0.0 && o.entropy >= 0.0,
                      "GPS: bad KL step options (epsilon {:g}, eta in [{:g}, {:g}])", epsilon,
                      o.min_eta, o.max_eta);
  double lo = o.min_eta, hi = o.max_eta;
  double eta = std::clamp(eta0, lo, hi);
  std::optional<KlStep> best;  // the feasible result (KL <= epsilon) closest to epsilon
  KlStep last;
  for (int it = 1; it <= o.max_iterations; ++it) {
    auto p = kl_regularised_lqg(d, cost, q, eta, o.entropy);
    if (!p) {  // not positive definite: only a larger eta can help
      lo = eta;
      if (eta >= o.max_eta) break;
      eta = std::min(std::sqrt(lo * hi), 10.0 * lo);
      continue;
    }
    const double kl = kl_divergence(propagate(*p, d), *p, q);
    last = {std::move(*p), eta, kl, it, std::abs(kl - epsilon) < o.tolerance * epsilon};
    if (kl <= epsilon && (!best || kl > best->kl)) best = last;
    if (last.converged) return last;
    if (kl < epsilon) {  // eta too large: the bound is slack
      hi = eta;
      eta = std::max(std::sqrt(lo * hi), 0.1 * hi);
    } else {
      lo = eta;
      eta = std::min(std::sqrt(lo * hi), 10.0 * lo);
    }
    if (hi / lo < 1.0 + 1e-12) break;
  }
  if (best) return *best;
  if (last.iterations == 0)
    throw std::runtime_error(rodlab::format(
        "GPS: no multiplier up to {:g} gives a positive definite backward pass", o.max_eta));
  return last;
}

}  // namespace rodlab::solvers::learning
