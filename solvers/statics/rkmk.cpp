#include "rodlab/solvers/statics/rkmk.hpp"

#include <Eigen/LU>

namespace rodlab::solvers::statics {
namespace {

using Matrix6 = lie::Matrix6;

/// Right-hand side of (2.33)-(2.34) at a section: the strain xi and Lambda'.
struct Slope {
  Vector6 xi, dLambda;
};

inline Slope slope(const StaticProblem& P, const SO3& R, const Vector6& Lambda) {
  Slope k;
  k.xi = P.strain(Lambda);
  k.dLambda = P.wrench_derivative(R, k.xi, Lambda);
  return k;
}

/// R exp(Theta_omega): the stages need only the rotation (the loads depend on R, not on p).
inline SO3 rotate(const SO3& R, const Vector6& Theta) { return R * SO3::exp(Theta.head<3>()); }

/// (2.84) theta' = dexp^-1_{-theta} xi, with dexp^-1 truncated after ad^2 (q = 2 >= p - 2 = 2).
/// Sum_k B_k/k! ad_{-Theta}^k y for k <= 2: y + ad_Theta y / 2 + ad_Theta^2 y / 12.
inline Vector6 dexp_inv_neg_q2(const Vector6& Theta, const Vector6& y) {
  const Vector6 a1 = lie::se3::ad_apply(Theta, y);
  return y + 0.5 * a1 + (1.0 / 12.0) * lie::se3::ad_apply(Theta, a1);
}

Node step_euler_explicit(const StaticProblem& P, const Node& n, double h) {  // (2.106)
  const Slope k = slope(P, n.g.rotation(), n.Lambda);
  return {n.g * SE3::exp(h * k.xi), n.Lambda + h * k.dLambda};
}

Node step_midpoint_explicit(const StaticProblem& P, const Node& n, double h) {  // (2.108)
  const SO3& R = n.g.rotation();
  const Slope k1 = slope(P, R, n.Lambda);
  const Vector6 Theta2 = 0.5 * h * k1.xi;
  const Slope k2 = slope(P, rotate(R, Theta2), n.Lambda + 0.5 * h * k1.dLambda);
  return {n.g * SE3::exp(h * k2.xi), n.Lambda + h * k2.dLambda};
}

Node step_rk4(const StaticProblem& P, const Node& n, double h) {  // classical RK4, Munthe-Kaas
  const SO3& R = n.g.rotation();
  const Slope s1 = slope(P, R, n.Lambda);
  const Vector6 K1 = h * s1.xi, L1 = h * s1.dLambda;
  const Vector6 T2 = 0.5 * K1;
  const Slope s2 = slope(P, rotate(R, T2), n.Lambda + 0.5 * L1);
  const Vector6 K2 = dexp_inv_neg_q2(T2, h * s2.xi), L2 = h * s2.dLambda;
  const Vector6 T3 = 0.5 * K2;
  const Slope s3 = slope(P, rotate(R, T3), n.Lambda + 0.5 * L2);
  const Vector6 K3 = dexp_inv_neg_q2(T3, h * s3.xi), L3 = h * s3.dLambda;
  const Slope s4 = slope(P, rotate(R, K3), n.Lambda + L3);
  const Vector6 K4 = dexp_inv_neg_q2(K3, h * s4.xi), L4 = h * s4.dLambda;
  const Vector6 Theta = (K1 + 2.0 * K2 + 2.0 * K3 + K4) / 6.0;
  return {n.g * SE3::exp(Theta), n.Lambda + (L1 + 2.0 * L2 + 2.0 * L3 + L4) / 6.0};
}

/// Implicit steps solve G(y) = 0 for y = Lambda_{i+1} by a chord Newton method: a
/// finite-difference Jacobian at the explicit predictor, refreshed if the iteration stalls.
/// Implicit Euler (2.107): G = y - Lambda_i - h f(R_i exp(h xi(y)), y), g_{i+1} = g_i exp(h xi(y)).
/// Implicit midpoint (2.109), (2.91)-(2.92): Lambda_m = (Lambda_i + y)/2, Theta = h xi(Lambda_m),
/// G = y - Lambda_i - h f(R_i exp(Theta/2), Lambda_m), g_{i+1} = g_i exp(Theta).
template <bool Midpoint>
bool step_implicit(const StaticProblem& P, const Node& n, double h, Node& next) {
  const SO3& R = n.g.rotation();
  const Vector6& scale = P.wrench_scale();
  auto residual = [&](const Vector6& y) -> Vector6 {
    if constexpr (Midpoint) {
      const Vector6 Lm = 0.5 * (n.Lambda + y);
      const Slope k = slope(P, rotate(R, 0.5 * h * P.strain(Lm)), Lm);
      return (y - n.Lambda - h * k.dLambda).cwiseQuotient(scale);
    } else {
      const Slope k = slope(P, rotate(R, h * P.strain(y)), y);
      return (y - n.Lambda - h * k.dLambda).cwiseQuotient(scale);
    }
  };
  Vector6 y = n.Lambda + h * slope(P, R, n.Lambda).dLambda;  // explicit Euler predictor
  Vector6 G = residual(y);
  Eigen::PartialPivLU<Matrix6> lu;
  bool have_jacobian = false;
  double previous = G.lpNorm<Eigen::Infinity>();
  for (int it = 0; it < 30; ++it) {
    if (!G.allFinite()) return false;
    if (previous <= 1e-14) break;
    if (!have_jacobian) {
      Matrix6 J;
      for (int j = 0; j < 6; ++j) {
        Vector6 yp = y;
        const double dy = 1e-7 * (std::abs(y[j]) + scale[j]);
        yp[j] += dy;
        J.col(j) = (residual(yp) - G) / dy;
      }
      lu.compute(J);
      have_jacobian = true;
    }
    y -= lu.solve(G);
    G = residual(y);
    const double norm = G.lpNorm<Eigen::Infinity>();
    if (norm > 0.5 * previous) have_jacobian = false;  // stalled: refresh the Jacobian
    previous = norm;
  }
  if (!(previous <= 1e-11)) return false;
  const Vector6 Theta = Midpoint ? Vector6(h * P.strain(0.5 * (n.Lambda + y))) : Vector6(h * P.strain(y));
  next = {n.g * SE3::exp(Theta), y};
  return true;
}

}  // namespace

int order(RkmkMethod method) {
  switch (method) {
    case RkmkMethod::euler_explicit:
    case RkmkMethod::euler_implicit: return 1;
    case RkmkMethod::midpoint_explicit:
    case RkmkMethod::midpoint_implicit: return 2;
    case RkmkMethod::rk4: return 4;
  }
  return 0;
}

ShootResult shoot(const StaticProblem& problem, RkmkMethod method, int nodes, const Vector6& Lambda0,
                  std::span<Node> path) {
  const double h = problem.length() / (nodes - 1);
  Node node{problem.base(), Lambda0};
  if (!path.empty()) path[0] = node;
  for (int i = 1; i < nodes; ++i) {
    bool ok = true;
    switch (method) {
      case RkmkMethod::euler_explicit: node = step_euler_explicit(problem, node, h); break;
      case RkmkMethod::midpoint_explicit: node = step_midpoint_explicit(problem, node, h); break;
      case RkmkMethod::rk4: node = step_rk4(problem, node, h); break;
      case RkmkMethod::euler_implicit: ok = step_implicit<false>(problem, node, h, node); break;
      case RkmkMethod::midpoint_implicit: ok = step_implicit<true>(problem, node, h, node); break;
    }
    if (!ok || !node.Lambda.allFinite()) return {node, false};
    if (!path.empty()) path[i] = node;
  }
  return {node, node.g.translation().allFinite()};
}

}  // namespace rodlab::solvers::statics
