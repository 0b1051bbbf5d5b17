#pragma once
// The learning environment (issue #15 item 1, thesis 4.4.2; docs/learning.md "Environment"): an
// episode of the rod's plant (control/plant.hpp) under actions a in [-1, 1]^m, one per actuator,
// each mapped to its limits, u = lower + (a + 1) / 2 (upper - lower), held over a control step
// of dt_c (a is clipped to [-1, 1] first: exploration noise may leave the box). Every episode
// starts from the plant's initial state (at rest) and aims at a goal: a point (reach-one,
// reach-any) or a path p_des(t) (track). The reward is (4.40) with beta (reward.hpp).
//
// Observation: observer.hpp (the tip, its mean velocity over the last step, the goal, the
// path's velocity for track, optionally the state of a few nodes; dimensionless).
//
// An episode ends with success (reach: the tip within threshold L of the target, thesis 4.4.2:
// 5 %), at max_steps (reach) or at the path's end (track), or when the plant's step fails
// (reported in the transition: failed and its reason; the reward is -1 there, the observation
// and error those before the step: the state where the scheme stopped is none). Success and a
// failure are terminal; the end of a reach episode's steps or of a path is not.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/control/plant.hpp"
#include "rodlab/solvers/learning/learning_environment.hpp"
#include "rodlab/solvers/learning/tip_cost.hpp"
#include "rodlab/solvers/learning/trajectory_environment.hpp"
#include "rodlab/solvers/learning/observer.hpp"
#include "rodlab/solvers/learning/polynomial_path.hpp"

namespace rodlab::solvers::learning {

enum class LearningTask { reach_one, reach_any, track };

/// "reach-one", "reach-any", "track" (the names of `rodlab train --task`).
const char* task_name(LearningTask task);
/// Throws std::invalid_argument for another name.
LearningTask task_from_name(const std::string& name);

struct EnvironmentOptions {
  control::PlantOptions plant;  ///< scheme, nodes, dt_control (the thesis: implicit, 0.05 s)
  LearningTask task = LearningTask::reach_any;
  double beta = 0.3;            ///< (4.40)
  double threshold = 0.05;      ///< success: tip error below threshold * L
  int max_steps = 100;          ///< control steps of a reach episode
  int state_nodes = 0;          ///< K: the state of K nodes in the observation (header)
  double track_duration = 4.0;  ///< [s] of a random path (the middle circle's period)
  /// [m/s] bound of each component of a random path's end velocities ("small", thesis 4.4.2).
  double track_end_speed = 0.01;
  /// GPS's cost (tip_cost.hpp); its beta is set from `beta` above.
  TipCost cost;
};

/// What an episode aims at: a fixed point, or a path with its velocity.
struct Goal {
  std::optional<lie::Vector3> point;
  std::optional<PolynomialPath> path;
  std::optional<scene::Trajectory> trajectory;  ///< e.g. the middle circle (evaluation)

  lie::Vector3 position(double t) const;
  lie::Vector3 velocity(double t) const;  ///< zero for a point; by central differences for a trajectory
  /// The episode's length for a path [s]; 0 for a point.
  double duration() const;
};

/// Where goals are drawn from: reach-one, its one target; reach-any, candidate targets (tips of
/// the dynamic workspace); track, points of the static workspace (the paths' ends).
struct GoalPool {
  std::vector<lie::Vector3> points;
  /// reach-one: how far its target lies from the closest quasi-static tip [m]; 0 otherwise.
  double beyond_static = 0.0;
};

class RodEnvironment final : public TrajectoryEnvironment {
 public:
  /// Throws std::invalid_argument for bad options, an empty pool, or what the plant refuses.
  RodEnvironment(const scene::Scene& scene, const EnvironmentOptions& options, GoalPool pool);

  int observation_size() const override { return observer_.size(); }
  int action_size() const override { return plant_.input_count(); }
  double length() const { return plant_.length(); }
  /// T, the first bending period [s] (the observation's velocity scale).
  double period() const { return observer_.period(); }
  const EnvironmentOptions& options() const { return options_; }

  /// A new episode: the plant at rest, the goal drawn from the pool with `seed` (reach-one: its
  /// target; reach-any: a candidate; track: a path between two pool points with random end
  /// velocities). observation.size() == observation_size().
  void reset(std::uint64_t seed, std::span<double> observation) override;
  /// A new episode towards `goal` (evaluation: a listed target, the middle circle).
  void reset(const Goal& goal, std::span<double> observation);
  /// One control step under `action` (size action_size(), each clipped to [-1, 1]).
  Transition step(std::span<const double> action, std::span<double> observation) override;

  /// GPS (trajectory_environment.hpp): the state x is the observation without the goal's
  /// entries (the tip, its velocity, the K nodes' coordinates), so d o / d x is a selection.
  int state_size() const override { return observer_.size() - goal_entries(); }
  void state(std::span<double> x) const override;
  double cost(const Eigen::Ref<const Eigen::VectorXd>& x,
              const Eigen::Ref<const Eigen::VectorXd>& a, int t, CostExpansion* e) const override;
  const Eigen::MatrixXd& observation_jacobian() const override { return observation_jacobian_; }
  void set_fixed_length(int steps) override;

  /// The inputs an action holds (action_map.hpp; throws for a wrong number of actions).
  void action_to_input(std::span<const double> action, Eigen::VectorXd& u) const;

  const Goal& goal() const { return goal_; }
  /// The episode's last step: its length (reach) or the path's end (track), or the fixed length.
  int episode_steps() const;
  int steps() const { return steps_; }
  double time() const { return steps_ * plant_.dt_control(); }
  lie::Vector3 tip() const { return plant_.tip(); }
  const control::Plant& plant() const { return plant_; }

 private:
  void observe(std::span<double> observation);
  /// The goal's entries in the observation: 3, or 6 with its velocity (track).
  int goal_entries() const { return observer_.layout().goal_velocity ? 6 : 3; }

  EnvironmentOptions options_;
  GoalPool pool_;
  control::Plant plant_;
  control::PlantSnapshot initial_;
  Goal goal_;
  Observer observer_;
  Eigen::VectorXd u_;
  lie::Vector3 tip_before_ = lie::Vector3::Zero();
  int steps_ = 0;
  double error_sum_ = 0.0;
  double last_error_ = 0.0;               ///< the last step's error (a failed step repeats it)
  std::vector<double> last_observation_;  ///< the last observation (a failed step repeats it)
  bool done_ = true;
  int fixed_length_ = 0;  ///< > 0: episodes of exactly this many steps (GPS)
  Eigen::MatrixXd observation_jacobian_;
};

}  // namespace rodlab::solvers::learning
