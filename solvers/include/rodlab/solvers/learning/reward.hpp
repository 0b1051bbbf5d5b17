#pragma once
// The learning tasks' reward (thesis 4.4.2, (4.40)), for every task:
//
//   R = -||p(L) - p_des|| / (beta L)   if ||p(L) - p_des|| <= beta L,
//       -1                             otherwise,
//
// in [-1, 0], continuous at the edge, 0 only on the target; beta in (0, 1], the thesis' 0.3.
// Outside beta L the reward is flat: it says nothing about the direction to the target there
// (the thesis chose the range for DDPG's sake, [75]); docs/learning.md.
#include <algorithm>

namespace rodlab::solvers::learning {

/// The thesis' beta.
inline constexpr double kThesisBeta = 0.3;

/// (4.40) for a tip error `error` [m] on a rod of length L [m].
inline double reward(double error, double beta, double L) {
  return -std::min(1.0, error / (beta * L));
}

}  // namespace rodlab::solvers::learning
