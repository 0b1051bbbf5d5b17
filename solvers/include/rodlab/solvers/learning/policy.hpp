#pragma once
// A trained policy and its file (docs/learning.md "Policy file"): the actor network with what
// it needs to act on a plant again, the observation's layout and scales (observer.hpp) and the
// actions' limits, and how it was trained.
//
//   {"schema": "rodlab.policy/1", "algorithm": "ddpg", "task": "reach-one", "scene": "...",
//    "scheme": "implicit-midpoint", "nodes": 20, "dt_control": 0.05,
//    "observation": {"size": 9, "goal_velocity": false, "state_nodes": 0, "length": 0.1,
//                    "period": 0.226},
//    "action": {"size": 4, "lower": [...], "upper": [...]},
//    "training": {"samples": 500000, "episodes": 6000, "seed": 1, "wall_time_s": 812.0},
//    "goal": [x, y, z] (reach-one: its target, world frame [m]) or null,
//    "network": {rodlab.mlp/1 (mlp_json.hpp)}}
//
// The network maps the observation to actions a in [-1, 1]^m; the input held is
// u = lower + (a + 1) / 2 (upper - lower). Readable with Python's json and numpy alone.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "rodlab/solvers/learning/mlp.hpp"
#include "rodlab/solvers/learning/observer.hpp"

namespace rodlab::solvers::learning {

inline constexpr const char* kPolicySchema = "rodlab.policy/1";

struct PolicyTraining {
  long samples = 0;
  long episodes = 0;
  std::uint64_t seed = 0;
  double wall_time_s = 0.0;
  int episode_steps = 0;  ///< control steps of a training episode (GPS: its T; DDPG: max_steps)
};

struct Policy {
  std::string algorithm, task, scene, scheme;
  int nodes = 0;
  double dt_control = 0.0;
  ObservationLayout layout;
  double length = 0.0, period = 0.0;  ///< L [m] and T [s] of the observation's scales
  Eigen::VectorXd lower, upper;       ///< the actions' limits (scene order)
  PolicyTraining training;
  std::optional<lie::Vector3> goal;   ///< reach-one: the target it was trained for
  Mlp<double> network{MlpConfig{{1, 1}}};
};

/// The document (one line, final newline). Throws std::invalid_argument for a network that is
/// not finite or sizes that do not match.
std::string to_json(const Policy& policy);
/// The policy of a document; throws std::invalid_argument naming the field that is wrong.
Policy policy_from_json(std::string_view text);

}  // namespace rodlab::solvers::learning
