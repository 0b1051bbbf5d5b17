#pragma once
// What a learning algorithm trains on (DDPG, ddpg.hpp; docs/learning.md): episodes of
// observations, actions in [-1, 1]^m and rewards. The rod's environment (rod_environment.hpp)
// is one; the tests' linear plants with known optimal controllers are others.
#include <cstdint>
#include <span>
#include <string>

namespace rodlab::solvers::learning {

/// One step's outcome.
struct Transition {
  double reward = 0.0;
  double error = 0.0;     ///< the task's error after the step (rod: ||tip - p_des|| [m])
  bool done = false;      ///< the episode ended: terminal, or its length reached
  /// The episode ended in a terminal state (reach: success; a failed step): nothing follows,
  /// a value estimate does not bootstrap from it. An episode that only reached its length is
  /// done but not terminal (time-limit truncation, Pardo et al. 2018).
  bool terminal = false;
  bool success = false;   ///< the task's success criterion
  bool failed = false;    ///< the simulation failed: `reason`
  std::string reason;
};

class LearningEnvironment {
 public:
  virtual ~LearningEnvironment() = default;
  virtual int observation_size() const = 0;
  virtual int action_size() const = 0;
  /// A new episode drawn with `seed`; writes the first observation.
  virtual void reset(std::uint64_t seed, std::span<double> observation) = 0;
  /// One step under `action` (each in [-1, 1], clipped); writes the next observation.
  virtual Transition step(std::span<const double> action, std::span<double> observation) = 0;
};

}  // namespace rodlab::solvers::learning
