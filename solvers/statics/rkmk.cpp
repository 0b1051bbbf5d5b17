#include "rodlab/solvers/statics/rkmk.hpp"

#include <algorithm>

#include <Eigen/LU>

namespace rodlab::solvers::statics {
namespace {

using Matrix6 = lie::Matrix6;

/// Right-hand side of (2.33)-(2.34) at a section: the strain xi and Lambda'.
struct Slope {
  Vector6 xi, dLambda;
};

/// One sub-step's context: the problem, the actuators active on it, and the accumulation of
/// actuator path lengths (stage weights w_j, sum_j w_j = 1).
struct Stretch {
  const StaticProblem& P;
  StaticProblem::Mask mask;
  std::array<double, StaticProblem::kMaxActuators>* lengths;  // null: not tracked
  double a, b;  // the sub-step [a, b]

  /// Actuator paths are evaluated strictly inside [a, b]: at a routing knot the offset rate r'
  /// jumps, and each sub-step must see the one-sided values of its own segment.
  double inside(double s) const {
    const double eps = 1e-9 * (b - a);
    return s < a + eps ? a + eps : (s > b - eps ? b - eps : s);
  }
  Vector6 strain(const Vector6& Lambda, double s) const {
    return P.strain(Lambda, inside(s), mask);  // inside: the sub-step's own xi* and offsets
  }
  Slope slope(const SO3& R, const Vector6& Lambda, double s) const {
    Slope k;
    k.xi = strain(Lambda, s);
    k.dLambda = P.wrench_derivative(R, k.xi, Lambda);
    return k;
  }
  void add_length(double h_weight, double s, const Vector6& xi) const {
    if (!lengths) return;
    for (std::size_t k = 0; k < P.actuators().size(); ++k)
      if ((mask >> k) & 1U) (*lengths)[k] += h_weight * P.actuators()[k].path.length_rate(inside(s), xi);
  }
};

/// R exp(Theta_omega): the stages need only the rotation (the loads depend on R, not on p).
inline SO3 rotate(const SO3& R, const Vector6& Theta) { return R * SO3::exp(Theta.head<3>()); }

/// Sum_k B_k/k! ad_{-Theta}^k y for k <= 2: y + ad_Theta y / 2 + ad_Theta^2 y / 12.
inline Vector6 dexp_inv_neg_q2(const Vector6& Theta, const Vector6& y) {
  const Vector6 a1 = lie::se3::ad_apply(Theta, y);
  return y + 0.5 * a1 + (1.0 / 12.0) * lie::se3::ad_apply(Theta, a1);
}

Node step_euler_explicit(const Stretch& X, const Node& n, double s, double h) {  // (2.106)
  const Slope k = X.slope(n.g.rotation(), n.Lambda, s);
  X.add_length(h, s, k.xi);
  return {n.g * SE3::exp(h * k.xi), n.Lambda + h * k.dLambda};
}

Node step_midpoint_explicit(const Stretch& X, const Node& n, double s, double h) {  // (2.108)
  const SO3& R = n.g.rotation();
  const Slope k1 = X.slope(R, n.Lambda, s);
  const Vector6 Theta2 = 0.5 * h * k1.xi;
  const Slope k2 = X.slope(rotate(R, Theta2), n.Lambda + 0.5 * h * k1.dLambda, s + 0.5 * h);
  X.add_length(h, s + 0.5 * h, k2.xi);
  return {n.g * SE3::exp(h * k2.xi), n.Lambda + h * k2.dLambda};
}

Node step_rk4(const Stretch& X, const Node& n, double s, double h) {  // classical RK4, Munthe-Kaas
  const SO3& R = n.g.rotation();
  const double sm = s + 0.5 * h;
  const Slope s1 = X.slope(R, n.Lambda, s);
  const Vector6 K1 = h * s1.xi, L1 = h * s1.dLambda;
  const Vector6 T2 = 0.5 * K1;
  const Slope s2 = X.slope(rotate(R, T2), n.Lambda + 0.5 * L1, sm);
  const Vector6 K2 = dexp_inv_neg_q2(T2, h * s2.xi), L2 = h * s2.dLambda;
  const Vector6 T3 = 0.5 * K2;
  const Slope s3 = X.slope(rotate(R, T3), n.Lambda + 0.5 * L2, sm);
  const Vector6 K3 = dexp_inv_neg_q2(T3, h * s3.xi), L3 = h * s3.dLambda;
  const Slope s4 = X.slope(rotate(R, K3), n.Lambda + L3, s + h);
  const Vector6 K4 = dexp_inv_neg_q2(K3, h * s4.xi), L4 = h * s4.dLambda;
  if (X.lengths) {
    X.add_length(h / 6.0, s, s1.xi);
    X.add_length(h / 3.0, sm, s2.xi);
    X.add_length(h / 3.0, sm, s3.xi);
    X.add_length(h / 6.0, s + h, s4.xi);
  }
  const Vector6 Theta = (K1 + 2.0 * K2 + 2.0 * K3 + K4) / 6.0;
  return {n.g * SE3::exp(Theta), n.Lambda + (L1 + 2.0 * L2 + 2.0 * L3 + L4) / 6.0};
}

/// Implicit steps solve G(y) = 0 for y = Lambda_{i+1} by a chord Newton method: a
/// finite-difference Jacobian at the explicit predictor, refreshed if the iteration stalls.
/// Implicit Euler (2.107): G = y - Lambda_i - h f(R_i exp(h xi(y)), y), g_{i+1} = g_i exp(h xi(y)).
/// Implicit midpoint (2.109), (2.91)-(2.92): Lambda_m = (Lambda_i + y)/2, Theta = h xi(Lambda_m),
/// G = y - Lambda_i - h f(R_i exp(Theta/2), Lambda_m), g_{i+1} = g_i exp(Theta).
template <bool Midpoint>
bool step_implicit(const Stretch& X, const Node& n, double s, double h, Node& next) {
  const SO3& R = n.g.rotation();
  const Vector6& scale = X.P.wrench_scale();
  const double s_eval = Midpoint ? s + 0.5 * h : s + h;
  auto state = [&](const Vector6& y) { return Midpoint ? Vector6(0.5 * (n.Lambda + y)) : y; };
  auto residual = [&](const Vector6& y) -> Vector6 {
    const Vector6 Ls = state(y);
    const Vector6 xi = X.strain(Ls, s_eval);
    const SO3 Rs = rotate(R, (Midpoint ? 0.5 * h : h) * xi);
    return (y - n.Lambda - h * X.P.wrench_derivative(Rs, xi, Ls)).cwiseQuotient(scale);
  };
  Vector6 y = n.Lambda + h * X.slope(R, n.Lambda, s).dLambda;  // explicit Euler predictor
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
  const Vector6 Ls = state(y);
  const Vector6 xi = X.strain(Ls, s_eval);
  X.add_length(h, s_eval, xi);
  next = {n.g * SE3::exp(h * xi), y};
  return true;
}

bool advance(const Stretch& X, RkmkMethod method, Node& node, double s, double h) {
  switch (method) {
    case RkmkMethod::euler_explicit: node = step_euler_explicit(X, node, s, h); return true;
    case RkmkMethod::midpoint_explicit: node = step_midpoint_explicit(X, node, s, h); return true;
    case RkmkMethod::rk4: node = step_rk4(X, node, s, h); return true;
    case RkmkMethod::euler_implicit: return step_implicit<false>(X, node, s, h, node);
    case RkmkMethod::midpoint_implicit: return step_implicit<true>(X, node, s, h, node);
  }
  return false;
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

ShootResult shoot_span(const StaticProblem& problem, RkmkMethod method, int nodes, int first,
                       int last, const Node& start, std::span<Node> path) {
  const double L = problem.length();
  const double h = L / (nodes - 1);
  const auto& breaks = problem.breakpoints();
  ShootResult out;
  auto* lengths = problem.tracks_lengths() ? &out.lengths : nullptr;
  Node node = start;
  if (!path.empty()) path[0] = node;
  // A breakpoint at node `first` belongs to the span that ends there (its jump is in `start`).
  std::size_t next_break =
      first == 0 ? 0 : std::upper_bound(breaks.begin(), breaks.end(), first * h) - breaks.begin();
  for (int i = first + 1; i <= last; ++i) {
    double s = (i - 1) * h;
    const double s_end = i == nodes - 1 ? L : i * h;
    // Sub-steps between breakpoints: the integrand is smooth on each.
    while (s < s_end) {
      double b = s_end;
      if (next_break < breaks.size() && breaks[next_break] < s_end) b = breaks[next_break];
      const Stretch X{problem, problem.has_actuators() ? problem.active_mask(0.5 * (s + b)) : 0U,
                      lengths, s, b};
      if (!advance(X, method, node, s, b - s) || !node.Lambda.allFinite()) {
        out.tip = node;
        out.ok = false;
        return out;
      }
      s = b;
      if (b < s_end || (next_break < breaks.size() && breaks[next_break] == b)) {
        // Crossing a breakpoint: cables entering here add their pull (strain continuous).
        const auto left = problem.active_mask(b - 1e-12 * L);
        const Vector6 xi_left = left ? problem.strain(node.Lambda, b, left)
                                     : problem.strain(node.Lambda, b - 1e-12 * L);
        node.Lambda += problem.entry_jump(b, xi_left);
        ++next_break;
      }
    }
    if (!path.empty()) path[i - first] = node;
  }
  out.tip = node;
  out.ok = node.g.translation().allFinite();
  return out;
}

ShootResult shoot(const StaticProblem& problem, RkmkMethod method, int nodes,
                  const Vector6& Lambda0, std::span<Node> path) {
  return shoot_span(problem, method, nodes, 0, nodes - 1, Node{problem.base(), Lambda0}, path);
}

}  // namespace rodlab::solvers::statics
