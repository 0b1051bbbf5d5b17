#include "rodlab/solvers/learning/gaussian_mixture.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <utility>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

/// The parameters EM iterates on, with the Cholesky factors of the covariances.
struct Clusters {
  VectorXd weights;
  std::vector<VectorXd> means;
  std::vector<MatrixXd> covariances;
  std::vector<Eigen::LLT<MatrixXd>> factors;
};

/// log sum_j exp(v_j), the largest term taken out; -inf when every term is -inf.
double log_sum_exp(const Eigen::Ref<const VectorXd>& v) {
  const double top = v.maxCoeff();
  if (!std::isfinite(top)) return top;
  return top + std::log((v.array() - top).exp().sum());
}

/// Sets c.factors from c.covariances; throws std::runtime_error for one that is not positive
/// definite.
void factorise(Clusters& c, double regularization) {
  c.factors.resize(c.covariances.size());
  for (std::size_t k = 0; k < c.covariances.size(); ++k) {
    c.factors[k].compute(c.covariances[k]);
    if (c.factors[k].info() != Eigen::Success)
      throw std::runtime_error(
          rodlab::format("gaussian_mixture: the covariance of cluster {} is not positive definite "
                         "(regularization {:g}; raise it)",
                         k, regularization));
  }
}

/// Symmetrised, plus regularization on the diagonal.
void symmetrise_and_regularise(MatrixXd& S, double regularization) {
  S = 0.5 * (S + S.transpose()).eval();
  S.diagonal().array() += regularization;
}

/// log w_k + log N(q_j | mu_k, Sigma_k) into row k of L (K x M).
void log_joint(const VectorXd& weights, const std::vector<VectorXd>& means,
               const std::vector<Eigen::LLT<MatrixXd>>& factors,
               const Eigen::Ref<const MatrixXd>& Q, MatrixXd& L) {
  const auto K = static_cast<Eigen::Index>(means.size());
  const Eigen::Index d = Q.rows();
  L.resize(K, Q.cols());
  MatrixXd Z;
  for (Eigen::Index k = 0; k < K; ++k) {
    const auto& factor = factors[static_cast<std::size_t>(k)];
    Z = Q.colwise() - means[static_cast<std::size_t>(k)];
    factor.matrixL().solveInPlace(Z);  // L^-1 (q - mu)
    const double log_det = 2.0 * factor.matrixLLT().diagonal().array().log().sum();
    const double log_w =
        weights[k] > 0.0 ? std::log(weights[k]) : -std::numeric_limits<double>::infinity();
    L.row(k) = (-0.5 * (d * std::log(2.0 * std::numbers::pi) + log_det) + log_w) -
               0.5 * Z.colwise().squaredNorm().array();
  }
}

/// The E-step: the log responsibilities log r_ik into R (K x N); returns ll = sum_i log p(x_i).
double expectation(const VectorXd& weights, const std::vector<VectorXd>& means,
                   const std::vector<Eigen::LLT<MatrixXd>>& factors,
                   const Eigen::Ref<const MatrixXd>& X, MatrixXd& R) {
  log_joint(weights, means, factors, X, R);
  double ll = 0.0;
  for (Eigen::Index i = 0; i < X.cols(); ++i) {
    const double log_p = log_sum_exp(R.col(i));
    R.col(i).array() -= log_p;
    ll += log_p;
  }
  return ll;
}

/// The M-step from the log responsibilities R (K x N).
Clusters maximisation(const Eigen::Ref<const MatrixXd>& X, const MatrixXd& R,
                      double regularization) {
  const Eigen::Index K = R.rows(), N = X.cols();
  Clusters c;
  c.weights.resize(K);
  c.means.resize(K);
  c.covariances.resize(K);
  VectorXd a(N);
  MatrixXd D;
  for (Eigen::Index k = 0; k < K; ++k) {
    const double log_mass = log_sum_exp(R.row(k).transpose());  // log sum_i r_ik
    const double mass = std::exp(log_mass - std::log(static_cast<double>(N)));
    c.weights[k] = mass;
    if (mass < 1e-4 / static_cast<double>(K))
      a.setConstant(1.0 / static_cast<double>(N));  // reboot
    else
      a = (R.row(k).transpose().array() - log_mass).exp();
    c.means[k] = X * a;
    D = X.colwise() - c.means[k];
    c.covariances[k] = D * a.asDiagonal() * D.transpose();
    symmetrise_and_regularise(c.covariances[k], regularization);
  }
  c.weights /= c.weights.sum();
  factorise(c, regularization);
  return c;
}

/// The seeded random assignment (see the header).
Clusters random_start(const Eigen::Ref<const MatrixXd>& X, int K, std::uint64_t seed) {
  const Eigen::Index d = X.rows(), N = X.cols();
  std::mt19937_64 rng(seed);
  std::vector<int> cluster(static_cast<std::size_t>(N));
  std::vector<Eigen::Index> count(static_cast<std::size_t>(K), 0);
  for (auto& k : cluster) {
    k = static_cast<int>(rng() % static_cast<std::uint64_t>(K));
    ++count[static_cast<std::size_t>(k)];
  }
  const VectorXd overall_mean = X.rowwise().mean();
  const MatrixXd overall_D = X.colwise() - overall_mean;
  const MatrixXd overall_covariance = overall_D * overall_D.transpose() / static_cast<double>(N);
  Clusters c;
  c.weights = VectorXd::Constant(K, 1.0 / K);
  c.means.assign(static_cast<std::size_t>(K), overall_mean);
  c.covariances.assign(static_cast<std::size_t>(K), overall_covariance);
  for (int k = 0; k < K; ++k) {
    const Eigen::Index n_k = count[static_cast<std::size_t>(k)];
    if (n_k > 0) {
      MatrixXd P(d, n_k);
      for (Eigen::Index i = 0, j = 0; i < N; ++i)
        if (cluster[static_cast<std::size_t>(i)] == k) P.col(j++) = X.col(i);
      c.means[k] = P.rowwise().mean();
      P.colwise() -= c.means[k];
      c.covariances[k] = P * P.transpose() / static_cast<double>(n_k);
    }
    c.covariances[k] /= K;
    c.covariances[k].diagonal().array() += 2e-6;
  }
  return c;
}

}  // namespace

void GaussianMixture::fit(const Eigen::Ref<const MatrixXd>& X,
                          const GaussianMixtureOptions& options) {
  const Eigen::Index d = X.rows(), N = X.cols();
  RODLAB_THROW_UNLESS(d >= 1 && N >= 1,
                      "gaussian_mixture: fit needs at least one point of dimension >= 1 (got "
                      "{}x{})",
                      d, N);
  RODLAB_THROW_UNLESS(X.allFinite(), "gaussian_mixture: the points must be finite");
  RODLAB_THROW_UNLESS(options.max_clusters >= 1 && options.min_points_per_cluster >= 1 &&
                          options.max_iterations >= 0,
                      "gaussian_mixture: expected max_clusters >= 1, min_points_per_cluster >= 1 "
                      "and max_iterations >= 0 (got {}, {} and {})",
                      options.max_clusters, options.min_points_per_cluster, options.max_iterations);
  RODLAB_THROW_UNLESS(std::isfinite(options.tolerance) && options.tolerance >= 0.0 &&
                          std::isfinite(options.regularization) && options.regularization >= 0.0,
                      "gaussian_mixture: expected tolerance >= 0 and regularization >= 0 (got {:g} "
                      "and {:g})",
                      options.tolerance, options.regularization);
  const Eigen::Index by_points = std::max<Eigen::Index>(N / options.min_points_per_cluster, 2);
  const int K = static_cast<int>(std::min({by_points, Eigen::Index{options.max_clusters}, N}));

  Clusters current;
  if (options.warm_start && clusters() == K && dimension_ == d) {
    current = Clusters{weights_, means_, covariances_, factors_};
  } else {
    current = random_start(X, K, options.seed);
    factorise(current, options.regularization);
  }
  MatrixXd R, R_next;
  double ll = expectation(current.weights, current.means, current.factors, X, R);
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    Clusters next = maximisation(X, R, options.regularization);
    const double ll_next = expectation(next.weights, next.means, next.factors, X, R_next);
    if (!(ll_next >= ll)) break;  // a decrease (or NaN): keep the previous parameters
    const bool converged = std::abs(ll_next - ll) < options.tolerance * std::abs(ll_next);
    current = std::move(next);
    std::swap(R, R_next);
    ll = ll_next;
    if (converged) break;
  }

  weights_ = std::move(current.weights);
  means_ = std::move(current.means);
  covariances_ = std::move(current.covariances);
  factors_ = std::move(current.factors);
  dimension_ = static_cast<int>(d);
  points_ = static_cast<int>(N);
  log_likelihood_ = ll / static_cast<double>(N);
}

const VectorXd& GaussianMixture::mean(int k) const {
  RODLAB_THROW_UNLESS(k >= 0 && k < clusters(),
                      "gaussian_mixture: cluster {} out of range (the model has {})", k,
                      clusters());
  return means_[static_cast<std::size_t>(k)];
}

const MatrixXd& GaussianMixture::covariance(int k) const {
  RODLAB_THROW_UNLESS(k >= 0 && k < clusters(),
                      "gaussian_mixture: cluster {} out of range (the model has {})", k,
                      clusters());
  return covariances_[static_cast<std::size_t>(k)];
}

NormalInverseWishart GaussianMixture::prior(const Eigen::Ref<const MatrixXd>& Q) const {
  RODLAB_THROW_UNLESS(fitted(), "gaussian_mixture: prior needs a fitted model");
  RODLAB_THROW_UNLESS(Q.rows() == dimension_ && Q.cols() >= 1,
                      "gaussian_mixture: prior expected query points with {} rows and >= 1 "
                      "column (got {}x{})",
                      dimension_, Q.rows(), Q.cols());
  MatrixXd R;
  expectation(weights_, means_, factors_, Q, R);  // log responsibilities of the query points
  VectorXd w(clusters());
  for (int k = 0; k < clusters(); ++k) w[k] = std::exp(log_sum_exp(R.row(k).transpose()));
  w /= w.sum();  // (1/M) sum_j r_jk, renormalised against rounding
  NormalInverseWishart p;
  p.mu0 = VectorXd::Zero(dimension_);
  for (int k = 0; k < clusters(); ++k) p.mu0 += w[k] * means_[static_cast<std::size_t>(k)];
  p.Phi = MatrixXd::Zero(dimension_, dimension_);
  for (int k = 0; k < clusters(); ++k) {
    const VectorXd e = means_[static_cast<std::size_t>(k)] - p.mu0;
    p.Phi += w[k] * (covariances_[static_cast<std::size_t>(k)] + e * e.transpose());
  }
  p.Phi = 0.5 * (p.Phi + p.Phi.transpose()).eval();
  p.m = 1.0;
  p.n0 = static_cast<double>(points_ - 2 - dimension_) / static_cast<double>(points_);
  return p;
}

}  // namespace rodlab::solvers::learning
