#pragma once
// Multiple shooting for the statics BVP with an RKMK integrator: the shooting schemes' solver
// for hard problems (shooting.cpp: their load continuation and last resort).
//
// Single shooting amplifies an error in the base wrench over the whole rod: under large loads
// (a dead tip force of tens of E I / L^2, a large follower load) a small change of Lambda(0)
// sends the tip far off, or the march blows up before the tip, and Newton finds no descent or
// jumps to another equilibrium branch. Here the grid's steps are split into at most
// kMaxShootingIntervals intervals, each marched by shoot_span from its own start (pose and
// wrench), and Newton (newton.hpp) solves for the base wrench, the interval starts and the
// actuator unknowns so that the intervals join and the tip conditions hold. The equations are
// the scheme's own (the same steps on the same nodes): a converged solution is the
// single-shooting solution, found from further away. The Jacobian is by forward differences
// interval by interval (an interval's start moves only its own march and the join before it):
// about two single-shooting Jacobians' work, whatever the number of intervals.
#include <span>
#include <vector>

#include "rodlab/solvers/common/newton.hpp"
#include "rodlab/solvers/statics/rkmk.hpp"

namespace rodlab::solvers::statics {

/// At most this many intervals: 12 (intervals - 1) + 6 + (actuator unknowns) unknowns, whose
/// Newton systems are solved densely.
inline constexpr int kMaxShootingIntervals = 8;

class MultipleShooting {
 public:
  /// The problem is shared (its load factor is the caller's; its extra unknowns are set from
  /// every state evaluated) and must outlive this.
  MultipleShooting(StaticProblem& problem, RkmkMethod method, int nodes);

  /// The unknowns: [Lambda(0) / wrench_scale; per interior interval start: rotation vector
  /// against the reference configuration's rotation, position / L, Lambda / wrench_scale;
  /// extra unknowns (scaled as StaticProblem's)].
  int size() const;
  /// The reference configuration at the problem's load factor: g(s) = base rest_pose(s) with
  /// the undeformed rod's equilibrium wrench (zero for a clamped tip: kinsol's start too), the
  /// extra unknowns at their initial guess. Exact at load factor 0.
  Eigen::VectorXd reference_guess() const;
  /// [joins of consecutive intervals (rotation, position / L, Lambda / wrench_scale); tip
  /// conditions; actuator conditions]. False where a march fails.
  bool residual(const Eigen::VectorXd& x, Eigen::VectorXd& r) const;
  /// Forward differences interval by interval (r = residual(x)).
  bool jacobian(const Eigen::VectorXd& x, const Eigen::VectorXd& r, Eigen::MatrixXd& J,
                double fd_step) const;
  /// Newton from `guess` with this residual and Jacobian.
  NewtonResult solve(const Eigen::VectorXd& guess, NewtonOptions options) const;
  /// The grid's nodes at x (an interval's first node is its start). False where a march fails.
  bool path(const Eigen::VectorXd& x, std::vector<Node>& nodes) const;

 private:
  struct Marched;  // one interval's end and its share of the actuator path lengths
  int intervals() const { return static_cast<int>(bounds_.size()) - 1; }
  int offset(int k) const { return 6 + 12 * (k - 1); }  // interval k's start unknowns, k >= 1
  int columns(int k) const { return k == 0 ? 6 : 12; }
  int column(int k) const { return k == 0 ? 0 : offset(k); }
  int tip_row() const { return 12 * (intervals() - 1); }
  Node start(const Eigen::VectorXd& x, int k) const;
  bool march(int k, const Node& from, Marched& out, std::span<Node> path = {}) const;
  /// Interval k's rows of the residual: its join with the next start, or the tip conditions.
  void interval_rows(int k, const Node& end, const Eigen::VectorXd& x,
                     Eigen::Ref<Eigen::VectorXd> rows) const;
  void set_extras(const Eigen::VectorXd& x) const;

  StaticProblem& P_;
  RkmkMethod method_;
  int nodes_, extra_;
  std::vector<int> bounds_;    // the intervals' first and last nodes
  std::vector<SO3> reference_; // the rotations the start unknowns are measured against
};

}  // namespace rodlab::solvers::statics
