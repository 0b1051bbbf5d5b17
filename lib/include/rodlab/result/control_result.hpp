#pragma once
// What `rodlab control` returns (interface spec "Control and learning",
// rodlab.control-result/1; docs/control.md "Result file"). Errors are in metres unless named
// _pct_L (percent of the rod length).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rodlab/lie/se3.hpp"

namespace rodlab::result {

/// Where the targets of a run came from (JSON "drawn_from").
enum class TargetSource {
  scene,              ///< listed in the scene's control.targets
  trajectory,         ///< the scene's control.trajectory (track)
  static_workspace,   ///< drawn with the seed from the static workspace ("static-workspace")
  dynamic_workspace,  ///< drawn with the seed from the dynamic workspace ("dynamic-workspace")
  policy,             ///< the target a reach-one policy was trained for ("policy")
};

struct ControlTargets {
  TargetSource drawn_from = TargetSource::scene;
  std::vector<lie::Vector3> points;  ///< [m], world; one per episode (empty for a trajectory)
};

/// One episode: one target reached (reach) or reached and held (hold), or one pass along the
/// trajectory (track).
struct ControlEpisode {
  lie::Vector3 target = lie::Vector3::Zero();  ///< track: the trajectory's point at t = 0
  bool success = false;
  int steps = 0;  ///< control updates (reach: until within the threshold)
  double final_error = 0.0, min_error = 0.0, mean_error = 0.0;  ///< [m]
  /// Why the episode ended early (an unreachable target, a solver failure); nullopt otherwise.
  std::optional<std::string> reason;
};

/// One entry per control step, the episodes one after the other. A step ends at t: u is the
/// input held over (t - dt_control, t], tip and error are measured at t.
struct ControlSeries {
  std::vector<double> t;                  ///< [s] since the episode's start
  std::vector<Eigen::VectorXd> u;         ///< one input per actuator, in scene order
  std::vector<lie::Vector3> tip, target;  ///< [m], world
  std::vector<double> error;              ///< ||tip - target|| [m]
  std::vector<double> solve_time_s;       ///< the controller's wall time for the step
  std::vector<int> iterations;            ///< the controller's solver iterations for the step
  std::vector<int> episode;               ///< index into ControlResult::episodes
};

struct ControlSummary {
  double success_rate = 0.0;      ///< successful episodes / episodes
  double mean_error_pct_L = 0.0;  ///< mean of series.error, in % of L
  /// controller wall time per control step / dt_control (the thesis' tau): mean and max
  double real_time_ratio_mean = 0.0, real_time_ratio_max = 0.0;
  double wall_time_s = 0.0;
  std::optional<long> samples;  ///< simulated transitions a trained policy cost; else null
};

struct ControlResult {
  std::string scene, controller, task, scheme;
  /// extension: the scheme the controller predicted with when not the plant's (control.model_scheme)
  std::optional<std::string> model_scheme;
  int nodes = 0;
  double dt_control = 0.0;
  int horizon = 0;
  bool converged = false;  ///< false: a solver failed
  /// null when fine; set whenever the run exits with status 1 (a solver failure, an
  /// unreachable target); "unknown" is written for converged = false without one
  std::optional<std::string> reason;
  std::vector<ControlEpisode> episodes;
  ControlSeries series;
  ControlSummary summary;
  unsigned seed = 0;  ///< extension: the seed targets were drawn with
  ControlTargets targets;  ///< extension: the targets and how they were drawn
};

}  // namespace rodlab::result
