#pragma once
// Trajectory optimisation of Guided Policy Search under a KL bound (Levine & Abbeel 2014,
// section 3.1; Montgomery & Levine 2016, the C-step of MDGPS): for one condition, with fitted
// linear-Gaussian dynamics, a quadratic cost expansion and a reference controller q (MDGPS: the
// global policy linearised about the samples),
//
//   min_p  E_p[sum_t l_t(x_t, a_t)]   s.t.   KL(p || q) = sum_t E_p[KL(p(.|x_t) || q(.|x_t))] <= epsilon.
//
// The Lagrangian with multiplier eta, divided by eta, is E_p[sum_t l_t / eta - log q(a_t | x_t)]
// - H(p): a maximum-entropy LQR whose solution is linear-Gaussian, p(a|x) = N(K x + k, Q_aa^-1),
// from the backward pass (kl_regularised_lqg)
//
//   Q_t = C_t / eta + [K_q^T P_q K_q, -K_q^T P_q; -P_q K_q, P_q],  q_t = c_t / eta + [K_q^T P_q k_q; -P_q k_q]
//        + F_t^T V_(t+1) F_t,                                          + F_t^T (v_(t+1) + V_(t+1) f_t)
//   K_t = -Q_aa^-1 Q_ax,  k_t = -Q_aa^-1 q_a,  S_t = Q_aa^-1,  V_t = Q_xx + Q_xa K_t,  v_t = q_x + Q_xa k_t,
//
// (P_q the reference's precision). With an entropy bonus nu > 0 (the reference code's
// max_ent_traj), the objective is E_p[l] - nu H(p) under the same bound, and the backward pass
// divides by eta + nu: Q_t = C_t / (eta + nu) + eta / (eta + nu) [policy terms] + ...; as eta
// falls the controllers' covariance then tends to nu Q_aa^-1 of the cost alone instead of to
// zero (without it MDGPS spends each step's KL on shrinking the covariance, and its mean
// stalls; docs/learning.md "GPS"). eta follows by dual gradient descent: bisection in log eta
// between brackets (the reference code's rule), until |KL - epsilon| < tolerance epsilon. A
// large eta keeps p at q, a small one follows the cost alone.
#include <optional>

#include "rodlab/solvers/learning/linear_gaussian.hpp"
#include "rodlab/solvers/learning/linear_gaussian_dynamics.hpp"

namespace rodlab::solvers::learning {

/// The distribution of z_t = [x_t; a_t] under `p` and `dynamics` from x_0 ~ N(x0_mean, x0_cov).
TrajectoryDistribution propagate(const LinearGaussianController& p,
                                 const LinearGaussianDynamics& dynamics);

/// E[sum_t l_t(z_t)] under `traj`: sum_t 1/2 tr(C_t Sigma_t) + 1/2 mu^T C_t mu + c_t^T mu + c0_t.
double expected_cost(const TrajectoryDistribution& traj, const QuadraticCost& cost);

/// sum_t E_(x_t ~ traj)[KL(p(.|x_t) || q(.|x_t))] (closed form for linear-Gaussian controllers).
double kl_divergence(const TrajectoryDistribution& traj, const LinearGaussianController& p,
                     const LinearGaussianController& q);

/// The backward pass above at one eta (entropy bonus nu >= 0); nullopt when some Q_aa is not
/// positive definite.
std::optional<LinearGaussianController> kl_regularised_lqg(const LinearGaussianDynamics& dynamics,
                                                           const QuadraticCost& cost,
                                                           const LinearGaussianController& q,
                                                           double eta, double nu = 0.0);

struct KlStepOptions {
  double min_eta = 1e-8, max_eta = 1e16;
  int max_iterations = 50;  ///< dual steps
  double tolerance = 0.1;   ///< relative to epsilon
  double entropy = 0.0;     ///< nu, the entropy bonus (max_ent_traj)
};

struct KlStep {
  LinearGaussianController controller;
  double eta = 1.0;  ///< the final multiplier (start of the next update)
  double kl = 0.0;   ///< KL(p || q) of the result
  int iterations = 0;
  bool converged = false;  ///< |KL - epsilon| within tolerance (else: the closest bracket)
};

/// The KL-constrained update above, eta starting at eta0. Throws std::runtime_error when no eta
/// up to max_eta gives a positive definite backward pass.
KlStep kl_constrained_lqg(const LinearGaussianDynamics& dynamics, const QuadraticCost& cost,
                          const LinearGaussianController& q, double epsilon, double eta0,
                          const KlStepOptions& options = {});

}  // namespace rodlab::solvers::learning
