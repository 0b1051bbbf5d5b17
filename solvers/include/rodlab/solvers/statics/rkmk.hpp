#pragma once
// Runge-Kutta-Munthe-Kaas integration of the statics ODE (2.33)-(2.34) from the base, for
// shooting (thesis 2.6.1, (2.83)-(2.92), (2.106)-(2.109)). The pose is advanced as
// g_{i+1} = g_i exp(Theta) with Theta from the RK stages of theta' = dexp^-1_{-theta} xi (2.84),
// the internal wrench by the same RK tableau. dexp^-1 is truncated at the order that keeps the
// method's order (q >= p - 2): the identity for the Euler and midpoint methods, q = 2 for RK4.
// One integration allocates nothing (fixed-size Eigen types; the optional path is pre-sized).
// Steps are split at the problem's breakpoints (actuator span ends, routing knots), so the
// integrand is smooth on every sub-step and the order is kept; a cable entering the rod at a
// breakpoint adds its jump to Lambda there (StaticProblem::entry_jump).
#include <array>
#include <span>

#include "rodlab/solvers/statics/static_problem.hpp"

namespace rodlab::solvers::statics {

enum class RkmkMethod { euler_explicit, euler_implicit, midpoint_explicit, midpoint_implicit, rk4 };

/// Order of accuracy of the method.
int order(RkmkMethod method);

/// State at one node.
struct Node {
  SE3 g;
  Vector6 Lambda;
};

/// Integrates from (base, Lambda0) over nodes - 1 uniform steps. Writes every node into
/// `path` when it is non-empty (path.size() must equal nodes). Returns the tip state; a
/// non-finite tip (or a failed implicit stage) is reported as `ok == false`.
struct ShootResult {
  Node tip;
  bool ok = true;
  /// Path length of each actuator over its span, integrated with the method's own weights
  /// (only when problem.tracks_lengths()).
  std::array<double, StaticProblem::kMaxActuators> lengths{};
};
ShootResult shoot(const StaticProblem& problem, RkmkMethod method, int nodes,
                  const Vector6& Lambda0, std::span<Node> path = {});

/// Integrates the nodes first..last (first < last) of the same grid of `nodes` nodes from
/// `start` at node `first`: a multiple-shooting interval (multiple_shooting.hpp). With start =
/// shoot()'s node `first` it is shoot()'s path between those nodes, bit for bit. A breakpoint
/// at node `first` belongs to the span that ends there (its jump is in `start`). `path`: empty
/// or last - first + 1 nodes. ShootResult::lengths is the span's share of the path lengths.
ShootResult shoot_span(const StaticProblem& problem, RkmkMethod method, int nodes, int first,
                       int last, const Node& start, std::span<Node> path = {});

}  // namespace rodlab::solvers::statics
