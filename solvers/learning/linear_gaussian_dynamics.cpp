#include "rodlab/solvers/learning/linear_gaussian_dynamics.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include <Eigen/Cholesky>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// Checks one trajectory: X n x T, U m x T, T >= 2, finite.
void check_trajectory(const MatrixXd& X, const MatrixXd& U, int n, int m, std::size_t i,
                      const char* caller) {
  RODLAB_THROW_UNLESS(X.rows() == n && X.cols() >= 2,
                      "{}: trajectory {} has states {}x{}, expected {} rows and >= 2 columns",
                      caller, i, X.rows(), X.cols(), n);
  RODLAB_THROW_UNLESS(U.rows() == m && U.cols() == X.cols(),
                      "{}: trajectory {} has actions {}x{}, expected {}x{} (one per state)", caller,
                      i, U.rows(), U.cols(), m, X.cols());
  RODLAB_THROW_UNLESS(X.allFinite() && U.allFinite(), "{}: trajectory {} is not finite", caller, i);
}

/// The points [x_t; u_t; x_(t+1)] of step t of one trajectory into column j of Y.
void transition(const MatrixXd& X, const MatrixXd& U, Eigen::Index t, MatrixXd& Y, Eigen::Index j) {
  const Eigen::Index n = X.rows(), m = U.rows();
  Y.col(j).head(n) = X.col(t);
  Y.col(j).segment(n, m) = U.col(t);
  Y.col(j).tail(n) = X.col(t + 1);
}

}  // namespace

DynamicsFitter::DynamicsFitter(int n, int m, DynamicsFitOptions options)
    : n_(n), m_(m), options_(std::move(options)) {
  RODLAB_THROW_UNLESS(n >= 1 && m >= 0,
                      "dynamics_fitter: expected n >= 1 states and m >= 0 actions (got {} and {})",
                      n, m);
  RODLAB_THROW_UNLESS(std::isfinite(options_.regularization) && options_.regularization >= 0.0 &&
                          std::isfinite(options_.initial_state_variance) &&
                          options_.initial_state_variance >= 0.0,
                      "dynamics_fitter: expected regularization >= 0 and initial_state_variance "
                      ">= 0 (got {:g} and {:g})",
                      options_.regularization, options_.initial_state_variance);
  RODLAB_THROW_UNLESS(options_.prior_trajectories >= 1,
                      "dynamics_fitter: expected prior_trajectories >= 1 (got {})",
                      options_.prior_trajectories);
}

void DynamicsFitter::update_prior(const std::vector<MatrixXd>& X, const std::vector<MatrixXd>& U) {
  RODLAB_THROW_UNLESS(!X.empty() && X.size() == U.size(),
                      "dynamics_fitter: update_prior expected as many action as state "
                      "trajectories, at least one (got {} and {})",
                      X.size(), U.size());
  for (std::size_t i = 0; i < X.size(); ++i)
    check_trajectory(X[i], U[i], n_, m_, i, "dynamics_fitter: update_prior");
  std::deque<Trajectory> buffer = buffer_;  // committed only when the mixture fits
  for (std::size_t i = 0; i < X.size(); ++i) {
    buffer.push_back({X[i], U[i]});
    if (buffer.size() > static_cast<std::size_t>(options_.prior_trajectories)) buffer.pop_front();
  }
  Eigen::Index count = 0;
  for (const auto& trajectory : buffer) count += trajectory.X.cols() - 1;
  MatrixXd Y(2 * n_ + m_, count);
  Eigen::Index j = 0;
  for (const auto& trajectory : buffer)
    for (Eigen::Index t = 0; t + 1 < trajectory.X.cols(); ++t)
      transition(trajectory.X, trajectory.U, t, Y, j++);
  gmm_.fit(Y, options_.prior);
  buffer_ = std::move(buffer);
}

LinearGaussianDynamics DynamicsFitter::fit(const std::vector<MatrixXd>& X,
                                           const std::vector<MatrixXd>& U) const {
  RODLAB_THROW_UNLESS(!X.empty() && X.size() == U.size(),
                      "dynamics_fitter: fit expected as many action as state trajectories, at "
                      "least one (got {} and {})",
                      X.size(), U.size());
  for (std::size_t i = 0; i < X.size(); ++i) {
    check_trajectory(X[i], U[i], n_, m_, i, "dynamics_fitter: fit");
    RODLAB_THROW_UNLESS(X[i].cols() == X[0].cols(),
                        "dynamics_fitter: fit expected trajectories of one length (trajectory {} "
                        "has {} states, trajectory 0 {})",
                        i, X[i].cols(), X[0].cols());
  }
  const auto N = static_cast<Eigen::Index>(X.size());
  const Eigen::Index T = X[0].cols(), a = n_ + m_, d = 2 * n_ + m_;
  const double Nd = static_cast<double>(N);
  const bool with_prior = options_.use_prior && gmm_.fitted();

  LinearGaussianDynamics dynamics;
  dynamics.F.reserve(static_cast<std::size_t>(T - 1));
  dynamics.f.reserve(static_cast<std::size_t>(T - 1));
  dynamics.covariance.reserve(static_cast<std::size_t>(T - 1));
  MatrixXd Y(d, N), D;
  Eigen::LLT<MatrixXd> factor;
  for (Eigen::Index t = 0; t + 1 < T; ++t) {
    for (Eigen::Index i = 0; i < N; ++i) transition(X[i], U[i], t, Y, i);
    const VectorXd mu = Y.rowwise().mean();
    D = Y.colwise() - mu;
    MatrixXd Sigma = D * D.transpose() / Nd;  // E
    if (with_prior) {
      const NormalInverseWishart p = gmm_.prior(Y);
      RODLAB_THROW_UNLESS(Nd + p.n0 > 0.0,
                          "dynamics_fitter: the prior's n0 = {:g} leaves N + n0 <= 0 with N = {} "
                          "samples (fit the prior on more points)",
                          p.n0, N);
      const VectorXd e = mu - p.mu0;
      Sigma = (Nd * Sigma + p.Phi + (Nd * p.m / (Nd + p.m)) * e * e.transpose()) / (Nd + p.n0);
    }
    Sigma = 0.5 * (Sigma + Sigma.transpose()).eval();
    Sigma.diagonal().array() += options_.regularization;

    factor.compute(Sigma.topLeftCorner(a, a));
    if (factor.info() != Eigen::Success)
      throw std::runtime_error(rodlab::format(
          "dynamics_fitter: the covariance of [x; u] at step {} is not positive definite "
          "(regularization {:g}, {} samples; raise the regularization or use the prior)",
          t, options_.regularization, N));
    MatrixXd F = factor.solve(Sigma.topRightCorner(a, n_)).transpose();
    VectorXd f = mu.tail(n_) - F * mu.head(a);
    MatrixXd S = Sigma.bottomRightCorner(n_, n_) - F * Sigma.topLeftCorner(a, a) * F.transpose();
    S = 0.5 * (S + S.transpose()).eval();
    dynamics.F.push_back(std::move(F));
    dynamics.f.push_back(std::move(f));
    dynamics.covariance.push_back(std::move(S));
  }

  MatrixXd X0(n_, N);
  for (Eigen::Index i = 0; i < N; ++i) X0.col(i) = X[i].col(0);
  dynamics.x0_mean = X0.rowwise().mean();
  D = X0.colwise() - dynamics.x0_mean;
  dynamics.x0_covariance = D * D.transpose() / Nd;
  dynamics.x0_covariance.diagonal().array() += options_.initial_state_variance;
  return dynamics;
}

}  // namespace rodlab::solvers::learning
