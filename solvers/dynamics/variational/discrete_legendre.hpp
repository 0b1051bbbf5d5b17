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
#include <cmath>

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

/// Bounds on how far an iterate of (3.42) can miss the root, for a diagonal M whose linear part
/// is isotropic (rho A I, a rod's; else no bound and the plain tests alone). Write
/// F(x) = dexp^-T_{dt x} M x, E(xi) = I - M^-1 J(xi) (J = F'), and in the scaled variables
/// M^(1/2) x: a = ||ad_xi^T|| <= cw |w| + s |v|, b = ||h -> ad_h^T M xi|| <= (J_max / J_min) |w|
/// + 2 s |v| (cw = sqrt(J_max / J_min) + 1, s = sqrt(rho A / J_min); the terms
/// (rho A h_v) x v + (rho A v) x h_v cancel). From dexp^-T_y = sum_k B_k / k! (ad_y^T)^k, with
/// theta = dt a <= dt (a + b) <= 1/2:
///   ||E|| <= dt (a + b) (1/2 + theta / 6 + theta^3 / 150) <= 0.6 dt (a + b),
///   ||E - E_1|| <= 0.17 (dt (a + b))^2      (E_1 the first-order part, linear in xi).
/// No square root is taken: (dt (a + b))^2 <= S2 = 2 dt^2 ((cw + J_max / J_min)^2 |w|^2
/// + 9 s^2 |v|^2) times the inflation below.
/// - The zeroth-order step x - y, y = M^-1 (F(x) - mu): its error is (I - M^-1 Jbar) e,
///   e = x - eta*, Jbar the mean Jacobian between x and eta*, so it is at most
///   q / (1 - q) |y|_M with q = sup ||E|| <= 0.6 sqrt(S2) <= 0.3: (q / (1 - q))^2 <= 0.735 S2.
/// - The Newton step x - P r, P = (I + E_1(x)) M^-1: its error is (I - P Jbar) e =
///   (E_1(xbar) - E_1(x) + (Ebar - E_1(xbar)) + E_1(x) Ebar) e, so it is at most
///   q_N / (1 - q_N) |step|_M with q_N <= 0.47 S2 + step_floor (E_1(x) Ebar <= 0.3 S2;
///   step_floor = 5e-7 (cw + J_max / J_min + 3) bounds E_1 of the segment, |e|_M <= 2e-6 |x|_M):
///   (q_N / (1 - q_N))^2 <= 1.3 q_N^2.
/// Both bounds hold along the segment from x to the root: a step is judged only where
/// |y|_M <= 1e-3 |x|_M (|step|_M <= 1e-6 |x|_M), which moves a + b by at most the factor
/// `inflation`, 1 + 2e-3 (cw + J_max / J_min + 3). tests/dynamics/test_discrete_legendre.cpp
/// checks ||E||, ||E_1|| <= 0.5 sqrt(S2) and ||E - E_1|| against the operator norms by central
/// differences (measured at most 0.19, 0.23, 0.032 of the bounds), and that the cantilever's
/// solves stop at their first residual (1.00 per solve, 1.99 with the plain tests alone).
struct LegendreContraction {
  // the constants of the derivation above (the packed solve, packed_pair.hpp, takes them too)
  static constexpr double kRange = 0.25;          ///< S2's range: dt (a + b) <= 1/2
  static constexpr double kZerothRange = 1e-6;    ///< |y|_M^2 / |x|_M^2 at most this
  static constexpr double kZerothFactor = 0.735;  ///< (q / (1 - q))^2 <= kZerothFactor S2
  static constexpr double kNewtonRange = 1e-12;   ///< |step|_M^2 / |x|_M^2 at most this
  static constexpr double kNewtonS2 = 0.47;       ///< q_N <= kNewtonS2 S2 + step_floor
  static constexpr double kNewtonFactor = 5.2;    ///< 4 (q_N / (1 - q_N))^2 <= this q_N^2

  double cw2 = -1.0;        ///< S2's coefficient of dt^2 |w|^2; negative where there is no bound
  double cv2 = -1.0;        ///< S2's coefficient of dt^2 |v|^2
  double step_floor = 1.0;  ///< q_N's floor

  static LegendreContraction of(const lie::Vector6& M) {
    const double J_min = M.head<3>().minCoeff(), J_max = M.head<3>().maxCoeff();
    const double A = M[3];
    if (!(J_min > 0.0) || !(A > 0.0) || M[4] != A || M[5] != A) return {};
    const double ratio = J_max / J_min, cw = std::sqrt(ratio) + 1.0, c = cw + ratio + 3.0;
    const double inflation = 1.0 + 2e-3 * c, i2 = inflation * inflation;
    return {2.0 * i2 * (cw + ratio) * (cw + ratio), 18.0 * i2 * (A / J_min), 5e-7 * c};
  }
  /// S2 at the iterate x, or 1 (above every bound's range) where there is no bound.
  double S2(double dt, const lie::Vector6& x) const {
    if (cw2 < 0.0) return 1.0;
    return S2(dt * dt, x.head<3>().squaredNorm(), x.tail<3>().squaredNorm());
  }
  /// S2 from dt^2 and |w|^2, |v|^2 (a double, or a packed pair of them: packed_pair.hpp).
  template <class T>
  T S2(double dt2, T w2, T v2) const {
    return dt2 * (cw2 * w2 + cv2 * v2);
  }
  /// (q / (1 - q))^2, the factor of |y|_M^2 in the zeroth-order step's test, where S2 is in
  /// range and |y|_M^2 <= kZerothRange |x|_M^2.
  template <class T>
  static T zeroth_order_bound(T S2) {
    return kZerothFactor * S2;
  }
  /// 4 (q_N / (1 - q_N))^2, the factor of |step|_M^2 in a Newton step's test (below 0.08), where
  /// S2 is in range and |step|_M^2 <= kNewtonRange |x|_M^2.
  template <class T>
  T newton_bound(T S2) const {
    const T qN = kNewtonS2 * S2 + step_floor;
    return kNewtonFactor * qN * qN;
  }
  /// The factors with their ranges, else 1 (the plain tests): |y|_M^2 = y2, |step|_M^2 = s2,
  /// |x|_M^2 = x2.
  static double zeroth_order_factor(double S2, double y2, double x2) {
    return S2 <= kRange && y2 <= kZerothRange * x2 ? zeroth_order_bound(S2) : 1.0;
  }
  double newton_factor(double S2, double s2, double x2) const {
    return S2 <= kRange && s2 <= kNewtonRange * x2 ? newton_bound(S2) : 1.0;
  }
};

/// Solves (3.42) for eta, on entry the previous velocity eta_old, which solved it for the
/// momentum mu_old. Newton with the first-order Jacobian J = M - dt/2 B,
/// B d = ad_eta^T M d + ad_d^T M eta (from dexp^-T_x = I - ad_x^T / 2 + O(x^2)), at the current
/// iterate (at eta_old in the first step; frozen at eta_old, session 20 measured 23 % of the
/// packed step's pairs needing a third residual, 14 % at the iterate) and inverted to the same
/// order, J^-1 = (I + dt/2 M^-1 B) M^-1 + O(dt^2 |eta|^2), without forming a matrix. The
/// first residual needs no evaluation: r(eta_old) = mu_old - mu
/// (to the previous solve's tolerance, which the following exact residuals correct). An iterate x
/// with residual r and y = M^-1 r is done when x - y is within tol/2 of the root in the norm
/// |x|_M^2 = x^T M x: |y|_M <= tol/2 |x|_M, or by the bound of LegendreContraction; else a
/// Newton step follows, done when the step is below tol |x|_M or its bound below tol/2 |x|_M
/// (before session 26 every solve judged by |y|_M and |step|_M alone: two residuals for most of
/// the cantilever's nodes). Returns the number of residuals evaluated, 0 on no convergence
/// (eta then holds the last iterate; a NaN or inf never converges).
template <class Mass>
[[gnu::always_inline]] inline int solve_legendre(const Mass& mass,
                                                 const LegendreContraction& contraction,
                                                 double tol, int max_iterations, double dt,
                                                 const lie::Vector6& mu,
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
    // The zeroth-order step M^-1 r first: x - y is within q / (1 - q) |y|_M of the root
    // (LegendreContraction; N = 100: nearly every node converges here).
    const Vector6 y = mass.inv(r);
    const double y2 = y.dot(r), x2 = x.dot(Mx);  // |y|_M^2, |x|_M^2
    double S2 = 1.0;                              // no bound until the plain test fails
    if (y2 > 0.25 * tol2 * x2) S2 = contraction.S2(dt, x);
    if (LegendreContraction::zeroth_order_factor(S2, y2, x2) * y2 <= 0.25 * tol2 * x2) {
      eta = x - y;
      return it;
    }
    const Vector6 step = newton_step(r, x, Mx);
    x -= step;
    const double s2 = step.dot(mass.mul(step)), xn2 = x.dot(mass.mul(x));
    if (contraction.newton_factor(S2, s2, xn2) * s2 <= tol2 * xn2) {
      eta = x;
      return it;
    }
  }
  eta = x;
  return 0;
}

struct DiscreteLegendre {
  lie::Vector6 M;      ///< diagonal of the mass matrix per unit length
  lie::Vector6 M_inv;  ///< its inverse
  double tol;          ///< relative tolerance in the kinetic-energy norm
  int max_iterations;
  LegendreContraction contraction = LegendreContraction::of(M);  ///< for M (diagonal)

  /// (3.42) with the rod's diagonal mass matrix (solve_legendre): the residuals it took, 0 when
  /// it did not converge.
  [[gnu::always_inline]] int solve(double dt, const lie::Vector6& mu, const lie::Vector6& mu_old,
                                   lie::Vector6& eta) const {
    return solve_legendre(DiagonalMass{M, M_inv}, contraction, tol, max_iterations, dt, mu,
                          mu_old, eta);
  }
  /// The same with a node's full mass matrix (embedded muscles, the corrected grid's tip cell)
  /// and its inverse (no contraction bound: the plain tests alone).
  int solve(double dt, const lie::Vector6& mu, const lie::Vector6& mu_old, lie::Vector6& eta,
            const lie::Matrix6& M_full, const lie::Matrix6& M_full_inv) const {
    return solve_legendre(FullMass{M_full, M_full_inv}, LegendreContraction{}, tol,
                          max_iterations, dt, mu, mu_old, eta);
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
