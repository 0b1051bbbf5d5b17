#pragma once
// Multiple shooting for the statics BVP with an RKMK integrator: the shooting schemes' last
// resort (shooting.cpp), when single shooting and its load continuation both fail.
//
// Single shooting amplifies an error in the base wrench over the whole rod: under large loads
// (a tension of tens of EI / L^2, a follower load) a small change of Lambda(0) sends the tip
// far off, or the march blows up before the tip, and Newton's line search finds no descent.
// Here the grid's steps are split into at most kMaxIntervals intervals, each marched by
// shoot_span from its own start (pose and wrench), and one Newton solve (newton.hpp) finds the
// base wrench, the interval starts and the actuator unknowns for which the intervals join and
// the tip conditions hold. The equations are the scheme's own (the same steps on the same
// nodes): a converged solution is the single-shooting solution, only found from further away.
#include <vector>

#include "rodlab/solvers/common/newton.hpp"
#include "rodlab/solvers/statics/rkmk.hpp"

namespace rodlab::solvers::statics {

struct MultipleShootingResult {
  /// x = [Lambda(0) / wrench_scale; per interior interval start: rotation vector against the
  /// reference configuration's, position / L, Lambda / wrench_scale; extra unknowns].
  NewtonResult newton;
  /// Every node of the grid (an interval's first node is its start), when converged.
  std::vector<Node> path;
};

/// At most this many intervals: (12 (intervals - 1) + 6 + actuators) unknowns, solved densely.
inline constexpr int kMaxShootingIntervals = 16;

/// Newton from the reference configuration (the rest shape with the undeformed rod's
/// equilibrium wrench, as kinsol's, or zero wrench for a clamped tip) at the problem's load
/// factor. Leaves the problem's extra unknowns at the returned iterate.
MultipleShootingResult solve_multiple_shooting(StaticProblem& problem, RkmkMethod method,
                                               int nodes, const NewtonOptions& options);

}  // namespace rodlab::solvers::statics
