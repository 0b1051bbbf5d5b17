#pragma once
// The discrete Legendre transform of the variational integrator (thesis (3.42)): the velocity
// eta over a step from the discrete momentum mu,
//
//   dexp^-T_{dt eta} M eta = mu,        M = diag(rho J, rho A)  (body frame, per unit length;
//                                       full where an embedded muscle sits off the centreline),
//
// solved by Newton from the previous step's velocity. Private to solvers/dynamics: the
// variational stepper and its Kirchhoff constraint solve share it. It is forced inline: it is
// the inner loop of the variational step (bench_dynamics), and GCC's own choice flipped with the
// number of callers; with the solve as a member that the Kirchhoff solve also called, the
// Cosserat step lost 30 % (A/B against 8698d27, docs/dynamics.md "Benchmarks").
#include "rodlab/lie/se3.hpp"
#include "rodlab/lie/small_angle.hpp"

namespace rodlab::solvers::dynamics {

/// The mass matrix of a node as (3.42) uses it: M x, M^-1 x and the operator (dt/2) M^-1.
/// Diagonal (a rod alone) or full (an embedded muscle off the centreline couples the linear and
/// angular velocities, (3.20)); both are applied without forming anything new.
struct DiagonalMass {
  const lie::Vector6& M;
  const lie::Vector6& M_inv;
  lie::Vector6 mul(const lie::Vector6& x) const { return M.cwiseProduct(x); }
  lie::Vector6 inv(const lie::Vector6& x) const { return x.cwiseProduct(M_inv); }
  struct Scaled {
    lie::Vector6 h;
    lie::Vector6 operator()(const lie::Vector6& x) const { return h.cwiseProduct(x); }
  };
  Scaled half_step_inverse(double dt) const { return {(0.5 * dt) * M_inv}; }
};

struct FullMass {
  const lie::Matrix6& M;
  const lie::Matrix6& M_inv;
  lie::Vector6 mul(const lie::Vector6& x) const { return M * x; }
  lie::Vector6 inv(const lie::Vector6& x) const { return M_inv * x; }
  struct Scaled {
    double h;
    const lie::Matrix6& M_inv;
    lie::Vector6 operator()(const lie::Vector6& x) const { return h * (M_inv * x); }
  };
  Scaled half_step_inverse(double dt) const { return {0.5 * dt, M_inv}; }
};

/// Solves (3.42) for eta, on entry the previous velocity eta_old, which solved it for the
/// momentum mu_old. Newton with the first-order Jacobian J = M - dt/2 B,
/// B d = ad_eta^T M d + ad_d^T M eta (from dexp^-T_x = I - ad_x^T / 2 + O(x^2)), at the current
/// iterate (at eta_old in the first step; frozen at eta_old, session 20 measured 23 % of the
/// packed step's pairs needing a third residual, 14 % at the iterate) and inverted to the same
/// order, J^-1 = (I + dt/2 M^-1 B) M^-1 + O(dt^2 |eta|^2), without forming a matrix. The
/// first residual needs no evaluation: r(eta_old) = mu_old - mu
/// (to the previous solve's tolerance, which the following exact residuals correct). Converged
/// when the step is below tol in the norm |x|_M^2 = x^T M x. Returns false on no convergence
/// (eta then holds the last iterate; a NaN or inf never converges).
template <class Mass>
[[gnu::always_inline]] inline bool solve_legendre(const Mass& mass, double tol, int max_iterations,
                                                  double dt, const lie::Vector6& mu,
                                                  const lie::Vector6& mu_old, lie::Vector6& eta) {
  using lie::Vector6;
  const Vector6 eta_old = eta;
  const auto half_dt_M_inv = mass.half_step_inverse(dt);
  // the first-order Jacobian at the iterate x (M x given)
  auto newton_step = [&](const Vector6& r, const Vector6& x, const Vector6& Mx)
                         __attribute__((always_inline)) {
    const Vector6 y = mass.inv(r);
    const Vector6 By = lie::se3::coad_apply(x, r) + lie::se3::coad_apply(y, Mx);
    return Vector6(y + half_dt_M_inv(By));
  };
  Vector6 x = eta_old - newton_step(mu_old - mu, eta_old, mass.mul(eta_old));
  const double tol2 = tol * tol;
  for (int it = 1; it < max_iterations; ++it) {
    const Vector6 Mx = mass.mul(x);
    const Vector6 r = lie::small_angle::dexp_inv_transpose_apply(dt * x, Mx) - mu;
    // The zeroth-order step M^-1 r first: when it is already below the tolerance, the
    // first-order correction (dt/2 M^-1 B, relative size ~dt |eta| ~ 1e-3) changes it by less
    // than tol * 1e-3 and is skipped (N = 100: most nodes converge here).
    const Vector6 y = mass.inv(r);
    if (y.dot(r) <= 0.25 * tol2 * x.dot(Mx)) {  // |y|_M^2
      eta = x - y;
      return true;
    }
    const Vector6 step = newton_step(r, x, Mx);
    x -= step;
    if (step.dot(mass.mul(step)) <= tol2 * x.dot(mass.mul(x))) {
      eta = x;
      return true;
    }
  }
  eta = x;
  return false;
}

struct DiscreteLegendre {
  lie::Vector6 M;      ///< diagonal of the mass matrix per unit length
  lie::Vector6 M_inv;  ///< its inverse
  double tol;          ///< relative tolerance in the kinetic-energy norm
  int max_iterations;

  /// (3.42) with the rod's diagonal mass matrix (solve_legendre).
  [[gnu::always_inline]] bool solve(double dt, const lie::Vector6& mu, const lie::Vector6& mu_old,
                                    lie::Vector6& eta) const {
    return solve_legendre(DiagonalMass{M, M_inv}, tol, max_iterations, dt, mu, mu_old, eta);
  }
  /// The same with a node's full mass matrix (embedded muscles) and its inverse.
  bool solve(double dt, const lie::Vector6& mu, const lie::Vector6& mu_old, lie::Vector6& eta,
             const lie::Matrix6& M_full, const lie::Matrix6& M_full_inv) const {
    return solve_legendre(FullMass{M_full, M_full_inv}, tol, max_iterations, dt, mu, mu_old, eta);
  }

  /// The momentum that a velocity eta solves (3.42) for: dexp^-T_{dt eta} M eta.
  lie::Vector6 momentum(double dt, const lie::Vector6& eta) const {
    return lie::small_angle::dexp_inv_transpose_apply(dt * eta, M.cwiseProduct(eta));
  }
  lie::Vector6 momentum(double dt, const lie::Vector6& eta, const lie::Matrix6& M_full) const {
    return lie::small_angle::dexp_inv_transpose_apply(dt * eta, M_full * eta);
  }
};

}  // namespace rodlab::solvers::dynamics
