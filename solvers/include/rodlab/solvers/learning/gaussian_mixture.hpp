#pragma once
// A Gaussian mixture model with full covariances, fitted by expectation-maximisation: the prior
// of Guided Policy Search's dynamics fit under unknown dynamics (Levine & Abbeel 2014; the
// reference implementation is Finn's cbfinn/gps), fitted to the points [x_t; u_t; x_(t+1)] of
// recent trajectories (linear_gaussian_dynamics.hpp).
//
// The model: p(x) = sum_k w_k N(x | mu_k, Sigma_k), k = 0 .. K-1, for points x in R^d.
//
// EM (Dempster, Laird & Rubin 1977; Bishop 2006, PRML section 9.2.2), on the points x_i,
// i = 0 .. N-1 (the columns of X):
//   E-step: log r_ik = log w_k + log N(x_i | mu_k, Sigma_k) - log p(x_i), with
//     log N(x | mu, Sigma) = -(d log 2 pi + log det Sigma + |L^-1 (x - mu)|^2) / 2,
//     Sigma = L L^T (Cholesky; no inverse is formed), and log p(x_i) by log-sum-exp over k
//     (the largest term taken out, so no density underflows). The total log-likelihood is
//     ll = sum_i log p(x_i).
//   M-step: the masses w_k = (1/N) sum_i r_ik (log-sum-exp again). A cluster whose mass falls
//     below 1e-4 / K is rebooted: its normalised responsibilities are replaced by 1/N, so it
//     restarts from the mean and covariance of all the points (its weight stays its mass).
//     Otherwise a_ik = r_ik / sum_j r_jk, and
//       mu_k = sum_i a_ik x_i,  Sigma_k = sum_i a_ik (x_i - mu_k)(x_i - mu_k)^T,
//     symmetrised, plus regularization * I.
//   Each iteration is one M-step followed by the E-step of its parameters. The fit stops after
//   max_iterations M-steps, when ll changes by less than tolerance * |ll|, or when ll decreases
//   (EM cannot decrease it, Bishop 2006 section 9.4; the regularisation and the reboot can): the
//   parameters of the decrease are then dropped and the previous ones kept, so the fitted model
//   is always the one of the highest ll seen, and log_likelihood() is that ll divided by N.
//
// K = clamp(floor(N / min_points_per_cluster), 2, max_clusters), at most N (max_clusters = 1
// gives one cluster). Initialisation: with warm_start, when the previous fit has the same K and
// d, EM starts from its clusters (GPS refits the prior after every batch of samples). Otherwise
// each point is assigned to a random cluster, from the seed alone: std::mt19937_64, the cluster
// of point i the i-th draw modulo K (the modulo bias, below K / 2^64, does not matter; this
// mapping, unlike std::uniform_int_distribution, is the same with every standard library).
// Cluster k starts with weight 1/K, the mean of its points and their covariance (1/n_k) scaled
// by 1/K, plus 2e-6 I (random subsets of the points would otherwise each start as wide as all
// of them); an empty cluster starts with the mean and covariance of all the points, scaled alike.
// Every cluster thus starts over all of the data, and EM from there can end in a local optimum
// that merges well-separated groups (tests/learning/test_gaussian_mixture.cpp: 6 of 50 seeds on
// three 2-D groups); the seed or warm_start decide which.
//
// The prior (Levine & Abbeel 2014; Gelman et al., Bayesian Data Analysis, section 3.6, for the
// normal-inverse-Wishart conjugate prior): for query points q_j (the samples of one time step),
// the averaged responsibilities w'_k = (1/M) sum_j r_jk weigh the clusters, and the prior is the
// moment match of the mixture under w':
//   mu0 = sum_k w'_k mu_k,   Phi = sum_k w'_k (Sigma_k + (mu_k - mu0)(mu_k - mu0)^T),
// with m = 1 and n0 = (N - 2 - d) / N, N the number of points of the last fit: the reference
// code's normalisation of m = N, n0 = N - 2 - d by N, a prior worth about one sample.
#include <cstdint>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace rodlab::solvers::learning {

struct GaussianMixtureOptions {
  int max_clusters = 20;            ///< K's upper bound, >= 1
  int min_points_per_cluster = 40;  ///< K = N / this (at least 2, at most max_clusters), >= 1
  int max_iterations = 100;         ///< EM iterations (M-steps), >= 0 (0: the initialisation)
  double tolerance = 1e-5;          ///< stop when |ll change| < tolerance |ll|, >= 0
  double regularization = 1e-6;     ///< added to every covariance's diagonal, >= 0
  std::uint64_t seed = 0;           ///< the random initial assignment
  bool warm_start = true;           ///< start from the previous clusters when K and d agree
};

/// A normal-inverse-Wishart prior (mu0, Phi, m, n0) on a Gaussian's mean and covariance: mu0 the
/// prior mean, Phi the prior scatter, m the prior count of the mean, n0 that of the covariance.
struct NormalInverseWishart {
  Eigen::VectorXd mu0;
  Eigen::MatrixXd Phi;
  double m = 0, n0 = 0;
};

class GaussianMixture {
 public:
  /// Fits the mixture to the points X (d x N, one column per point, d >= 1, N >= 1) by EM (see
  /// above). Throws std::invalid_argument for an empty X, non-finite entries or options out of
  /// range, and std::runtime_error when a covariance is not positive definite (possible only
  /// with regularization = 0 or data so large that it is lost to rounding). The model changes
  /// only when the fit succeeds.
  void fit(const Eigen::Ref<const Eigen::MatrixXd>& X, const GaussianMixtureOptions& options);

  int clusters() const { return static_cast<int>(means_.size()); }  ///< K (0 before a fit)
  int dimension() const { return dimension_; }                      ///< d (0 before a fit)
  bool fitted() const { return !means_.empty(); }
  const Eigen::VectorXd& weights() const { return weights_; }  ///< w, sums to 1
  /// mu_k and Sigma_k; throw std::invalid_argument unless 0 <= k < clusters().
  const Eigen::VectorXd& mean(int k) const;
  const Eigen::MatrixXd& covariance(int k) const;
  /// The mean log-density of the last fit's points under the fitted model: ll / N.
  double log_likelihood() const { return log_likelihood_; }
  /// The number of points of the last fit (the N of n0).
  int points() const { return points_; }

  /// The normal-inverse-Wishart prior of the query points Q (d x M, M >= 1; see above).
  /// Throws std::invalid_argument when the model is not fitted or Q has the wrong rows or no
  /// columns.
  NormalInverseWishart prior(const Eigen::Ref<const Eigen::MatrixXd>& Q) const;

 private:
  Eigen::VectorXd weights_;
  std::vector<Eigen::VectorXd> means_;
  std::vector<Eigen::MatrixXd> covariances_;
  std::vector<Eigen::LLT<Eigen::MatrixXd>> factors_;  // Sigma_k = L_k L_k^T
  int dimension_ = 0, points_ = 0;
  double log_likelihood_ = 0.0;
};

}  // namespace rodlab::solvers::learning
