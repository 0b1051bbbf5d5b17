#pragma once
// The linear-Gaussian objects of Guided Policy Search (Levine & Abbeel 2014; gps.hpp), over
// T time steps t = 0 .. T-1, a state x (n) and an action a (m), z = [x; a]:
//
//   controller   p(a_t | x_t) = N(K_t x_t + k_t, S_t)                   (local controllers; the
//                                                                         policy's linearisation)
//   dynamics     p(x_(t+1) | x_t, a_t) = N(F_t z_t + f_t, W_t)           (..._dynamics.hpp)
//   cost         l_t(z) ~ 1/2 z^T C_t z + c_t^T z + c0_t                  (a quadratic expansion)
//   trajectory   z_t ~ N(mu_t, Sigma_t)                                  (a controller under dynamics)
//
// all in absolute coordinates (not deviations from a nominal trajectory), as the reference code
// (cbfinn/gps) keeps them.
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace rodlab::solvers::learning {

struct LinearGaussianController {
  std::vector<Eigen::MatrixXd> K;           ///< m x n
  std::vector<Eigen::VectorXd> k;           ///< m
  std::vector<Eigen::MatrixXd> covariance;  ///< S_t, m x m
  std::vector<Eigen::MatrixXd> cholesky;    ///< lower L_t, S_t = L_t L_t^T
  std::vector<Eigen::MatrixXd> precision;   ///< S_t^-1

  int steps() const { return static_cast<int>(K.size()); }
  int state_size() const { return K.empty() ? 0 : static_cast<int>(K.front().cols()); }
  int action_size() const { return K.empty() ? 0 : static_cast<int>(K.front().rows()); }

  /// T steps of a = k0 + noise with covariance variance I (no feedback).
  static LinearGaussianController constant(int steps, int n, const Eigen::VectorXd& k0,
                                           double variance);
  /// Sets S_t with its Cholesky factor and precision; throws std::invalid_argument unless S_t
  /// is symmetric positive definite.
  void set_covariance(int t, const Eigen::MatrixXd& S);
};

struct QuadraticCost {
  std::vector<Eigen::MatrixXd> C;  ///< (n+m) x (n+m)
  std::vector<Eigen::VectorXd> c;  ///< n+m
  std::vector<double> c0;
};

struct TrajectoryDistribution {
  std::vector<Eigen::VectorXd> mean;        ///< mu_t of z_t
  std::vector<Eigen::MatrixXd> covariance;  ///< Sigma_t of z_t
};

}  // namespace rodlab::solvers::learning
