#pragma once
// A policy's actions onto the actuators' inputs (docs/learning.md "Environment"): each action a
// is clipped to [-1, 1] (exploration noise may leave the box) and mapped linearly onto its
// limits, u = lower + (a + 1) / 2 (upper - lower), kept inside them after rounding. The one map
// of training (rod_environment.hpp) and of control with a trained policy (control_run.cpp).
#include <algorithm>
#include <span>

#include <Eigen/Core>

namespace rodlab::solvers::learning {

/// u (resized to lower.size()) from `action` (action.size() == lower.size() == upper.size()).
inline void input_of_action(std::span<const double> action, const Eigen::VectorXd& lower,
                            const Eigen::VectorXd& upper, Eigen::VectorXd& u) {
  u.resize(lower.size());
  for (Eigen::Index k = 0; k < lower.size(); ++k) {
    const double a = std::clamp(action[static_cast<std::size_t>(k)], -1.0, 1.0);
    u[k] = std::clamp(lower[k] + 0.5 * (a + 1.0) * (upper[k] - lower[k]), lower[k], upper[k]);
  }
}

}  // namespace rodlab::solvers::learning
