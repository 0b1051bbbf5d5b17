#pragma once
// Time-varying linear-Gaussian dynamics fitted to sampled trajectories, with a Gaussian-mixture
// prior: Guided Policy Search under unknown dynamics (Levine & Abbeel 2014; the reference
// implementation is Finn's cbfinn/gps). The model of one condition (one initial state
// distribution, one controller) over T states:
//   x_0 ~ N(x0_mean, x0_covariance),   x_(t+1) ~ N(F_t [x_t; u_t] + f_t, S_t),  t = 0 .. T-2,
// with F_t of size n x (n+m), n the state size and m the action size.
//
// The fit, per step t, from the N samples' points y_i = [x_t; u_t; x_(t+1)] (dimension
// d = 2n + m): the empirical mean mu = (1/N) sum_i y_i and covariance
// E = (1/N) sum_i (y_i - mu)(y_i - mu)^T. With the prior (mu0, Phi, m, n0) of these points from
// the mixture (gaussian_mixture.hpp), the joint covariance is the posterior scatter of the
// normal-inverse-Wishart update (Gelman et al., Bayesian Data Analysis, section 3.6) divided by
// N + n0, as the reference code does:
//   Sigma = (N E + Phi + N m / (N + m) (mu - mu0)(mu - mu0)^T) / (N + n0),
// and the mean stays mu; without the prior Sigma = E. Sigma is symmetrised and
// regularization * I added to its whole diagonal. With N < n + m + 1 samples, E's [x; u] block
// is singular (rank N - 1): the empirical fit is then (as the regularization goes to 0) the
// minimum-norm one, zero in every direction the samples do not span, and the prior is what
// fills those directions in. The prior is only as local as the mixture: where the dynamics of
// different steps share a region of [x; u; x'] it averages them, so it helps most when the
// dynamics are a function of the state (a nonlinear system linearised along trajectories).
// Conditioning the joint Gaussian on [x; u] (a = [x; u], b = x'):
//   F_t = (Sigma_aa^-1 Sigma_ab)^T  (a Cholesky solve, no inverse),   f_t = mu_b - F_t mu_a,
//   S_t = Sigma_bb - F_t Sigma_aa F_t^T, symmetrised.
// (x0_mean, x0_covariance): the samples' mean and covariance (1/N) of x_0, plus
// initial_state_variance * I.
//
// The prior is fitted on the points [x_t; u_t; x_(t+1)] of every transition of the last
// prior_trajectories trajectories given to update_prior (of any condition: GPS pools its
// conditions), refitted after each update (warm-started from the previous clusters when their
// number is unchanged, GaussianMixtureOptions::warm_start).
#include <deque>
#include <vector>

#include <Eigen/Core>

#include "rodlab/solvers/learning/gaussian_mixture.hpp"

namespace rodlab::solvers::learning {

/// x_(t+1) ~ N(F[t] [x_t; u_t] + f[t], covariance[t]), t = 0 .. T-2; x_0 ~ N(x0_mean,
/// x0_covariance).
struct LinearGaussianDynamics {
  std::vector<Eigen::MatrixXd> F;           ///< T-1 matrices, n x (n+m)
  std::vector<Eigen::VectorXd> f;           ///< T-1 vectors, n
  std::vector<Eigen::MatrixXd> covariance;  ///< T-1 matrices, n x n
  Eigen::VectorXd x0_mean;                  ///< n
  Eigen::MatrixXd x0_covariance;            ///< n x n

  int state_size() const { return static_cast<int>(x0_mean.size()); }  ///< n
  int action_size() const {                                            ///< m
    return F.empty() ? 0 : static_cast<int>(F.front().cols() - F.front().rows());
  }
  /// T, the number of states (0 for an empty model).
  int steps() const { return x0_mean.size() == 0 ? 0 : static_cast<int>(F.size()) + 1; }
};

struct DynamicsFitOptions {
  double regularization = 1e-6;          ///< added to the joint covariance's diagonal, >= 0
  double initial_state_variance = 1e-6;  ///< added to x0_covariance's diagonal, >= 0
  GaussianMixtureOptions prior;          ///< the mixture of the prior
  bool use_prior = true;                 ///< false: the empirical fit even when a prior exists
  int prior_trajectories = 20;           ///< the prior is fitted on the last this many, >= 1
};

class DynamicsFitter {
 public:
  /// n >= 1 states, m >= 0 actions. Throws std::invalid_argument for sizes or options out of
  /// range.
  DynamicsFitter(int n, int m, DynamicsFitOptions options);

  int state_size() const { return n_; }
  int action_size() const { return m_; }
  const DynamicsFitOptions& options() const { return options_; }
  /// The prior's mixture (not fitted before the first update_prior).
  const GaussianMixture& prior_model() const { return gmm_; }
  /// How many trajectories the prior holds (at most prior_trajectories).
  int prior_trajectory_count() const { return static_cast<int>(buffer_.size()); }

  /// Adds trajectories to the prior's buffer (keeping the last prior_trajectories) and refits
  /// the mixture on all their points [x_t; u_t; x_(t+1)]. X[i] is n x T_i, U[i] m x T_i (the
  /// last action is not used), T_i >= 2; the lengths may differ. Throws std::invalid_argument
  /// for no trajectories or wrong sizes (the buffer and the prior unchanged), and passes on
  /// the mixture's std::runtime_error (likewise).
  void update_prior(const std::vector<Eigen::MatrixXd>& X, const std::vector<Eigen::MatrixXd>& U);

  /// Fits the dynamics to the N >= 1 trajectories of one condition: X[i] n x T, U[i] m x T, one
  /// T >= 2 for all. Uses the prior when options().use_prior and the prior has been fitted.
  /// Throws std::invalid_argument for wrong sizes, and std::runtime_error when a joint
  /// covariance is not positive definite (regularization 0 with too few samples).
  LinearGaussianDynamics fit(const std::vector<Eigen::MatrixXd>& X,
                             const std::vector<Eigen::MatrixXd>& U) const;

 private:
  struct Trajectory {
    Eigen::MatrixXd X, U;
  };
  int n_, m_;
  DynamicsFitOptions options_;
  std::deque<Trajectory> buffer_;
  GaussianMixture gmm_;
};

}  // namespace rodlab::solvers::learning
