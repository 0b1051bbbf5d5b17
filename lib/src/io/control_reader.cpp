// control: the task (targets or a trajectory), horizon, control step, success thresholds,
// cost weights, and how targets are drawn; and the limits it needs on every actuator.
#include <variant>

#include "rodlab/check.hpp"
#include "scene_readers.hpp"

namespace rodlab::io::detail {
namespace {

/// A unit normal: a non-zero 3-vector, normalised.
std::optional<scene::Vector3> read_normal(Checker& c, const Field& f) {
  const auto n = c.vector<3>(f);
  if (!n) return std::nullopt;
  if (n->isZero(0.0)) {
    c.error(f, "must not be zero (got " + describe(f.node) + ")");
    return std::nullopt;
  }
  return n->normalized();
}

scene::CircleTrajectory read_circle(Checker& c, const Field& f) {
  scene::CircleTrajectory circle;
  if (!c.keys(f, {"center", "radius", "period", "laps", "normal"})) return circle;
  if (auto center = c.vector<3>(c.require(f, "center"))) circle.center = *center;
  if (auto r = c.number(c.require(f, "radius"), Range::positive())) circle.radius = *r;
  if (auto T = c.number(c.require(f, "period"), Range::positive())) circle.period = *T;
  if (auto laps = c.number(c.child(f, "laps"), Range::positive())) circle.laps = *laps;
  if (auto n = read_normal(c, c.child(f, "normal"))) circle.normal = *n;
  return circle;
}

std::optional<scene::Trajectory> read_trajectory(Checker& c, const Field& f) {
  const KeyCheck kc = c.keys(f, {"circle"}, "trajectory type");
  if (!kc) return std::nullopt;
  // the only type so far; an unknown type is reported once, not also as a missing circle
  const Field circle = kc.unknown == 0 ? c.require(f, "circle") : Checker::child(f, "circle");
  if (!circle.present()) return std::nullopt;
  return scene::Trajectory{read_circle(c, circle)};
}

std::vector<scene::Vector3> read_targets(Checker& c, const Field& f) {
  std::vector<scene::Vector3> targets;
  const auto items = c.list(f, 1);
  if (!items) return targets;
  for (const Field& item : *items)
    if (auto p = c.vector<3>(item)) targets.push_back(*p);
  return targets;
}

scene::ControlWeights read_weights(Checker& c, const Field& f) {
  scene::ControlWeights w;
  if (!c.keys(f, {"input_rate", "input", "terminal"})) return w;
  if (auto v = c.number(c.child(f, "input_rate"), Range::non_negative())) w.input_rate = *v;
  if (auto v = c.number(c.child(f, "input"), Range::non_negative())) w.input = *v;
  if (auto v = c.number(c.child(f, "terminal"), Range::non_negative())) w.terminal = *v;
  return w;
}

/// The task, by default track when a trajectory is given and reach otherwise; targets belong to
/// reach and hold, a trajectory to track (which needs one: there is nothing to draw it from).
void read_task(Checker& c, const Field& f, scene::Control& control) {
  const Field task = Checker::child(f, "task");
  static constexpr std::string_view kTasks[] = {"reach", "hold", "track"};
  const auto k = c.choice(task, kTasks);
  const Field targets = Checker::child(f, "targets");
  const Field trajectory = Checker::child(f, "trajectory");
  if (!k) {
    if (!task.present() && trajectory.present()) control.task = scene::ControlTask::track;
    return;
  }
  control.task = static_cast<scene::ControlTask>(*k);
  const std::string got = " (got task " + std::string(kTasks[*k]) + ")";
  if (control.task == scene::ControlTask::track && targets.present())
    c.error(targets.key_mark, targets.path,
            "task track follows a trajectory; targets are for reach and hold" + got);
  if (control.task != scene::ControlTask::track && trajectory.present())
    c.error(trajectory.key_mark, trajectory.path, "only task track follows a trajectory" + got);
  if (control.task == scene::ControlTask::track && !targets.present() && !trajectory.present())
    c.error(f.mark, trajectory.path, "is required by task track (the path to follow)");
}

/// The control steps: hold_steps counts the last of max_steps (compared only with a good
/// max_steps, so a bad one is reported once).
void read_steps(Checker& c, const Field& f, scene::Control& control) {
  const Field max = c.child(f, "max_steps");
  const auto max_steps = c.integer(max, 1);
  if (max_steps) control.max_steps = *max_steps;
  const Field hold = c.child(f, "hold_steps");
  if (auto n = c.integer(hold, 1)) {
    if ((max_steps || !max.present()) && *n > control.max_steps)
      c.error(hold, rodlab::format("must not exceed max_steps = {} (got {})", control.max_steps,
                                   describe(hold.node)));
    else
      control.hold_steps = *n;
  }
}

/// Every actuator needs limits [min, max] with min < max: the controller's bounds, and the range
/// its cost scales inputs by. Checked only when every actuator was read (indices then match).
void check_actuator_limits(Checker& c, const Field& control, const Field& actuators,
                           const std::vector<scene::Actuator>& read) {
  if (read.empty()) {
    c.error(control.key_mark, control.path, "needs at least one actuator to control (got none)");
    return;
  }
  if (!actuators.node.IsSequence() || actuators.node.size() != read.size()) return;
  for (std::size_t i = 0; i < read.size(); ++i) {
    const Field item = Checker::element(actuators, i);
    Field actuator;
    for (std::string_view type : {"cable", "fluidic", "muscle"})
      if (const Field a = Checker::child(item, type); a.present()) actuator = a;
    const Field limits = Checker::child(actuator, "limits");
    const auto range = std::visit([](const auto& a) { return a.limits; }, read[i]);
    if (!limits.present())
      c.error(actuator.mark, limits.path,
              "is required by control (the bounds of the input the controller sets)");
    else if (range && range->first == range->second)
      c.error(limits, "must have min < max for control (got " + describe(limits.node) + ")");
  }
}

}  // namespace

scene::Control read_control(Checker& c, const Field& f, const Field& actuators,
                            const std::vector<scene::Actuator>& read) {
  scene::Control control;
  if (!c.keys(f, {"task", "targets", "trajectory", "horizon", "iterations", "model_scheme",
                  "dt_control",
                  "threshold", "max_steps", "hold_steps", "stop_at_success", "weights", "seed",
                  "target_count"}))
    return control;
  const auto given = c.exactly_one(f, {"targets", "trajectory"}, false);
  if (given == "targets") control.targets = read_targets(c, Checker::child(f, "targets"));
  if (given == "trajectory")
    control.trajectory = read_trajectory(c, Checker::child(f, "trajectory"));
  read_task(c, f, control);

  if (auto h = c.integer(c.child(f, "horizon"), 1)) control.horizon = *h;
  if (auto k = c.integer(c.child(f, "iterations"), 1)) control.iterations = *k;
  if (auto k = c.choice(c.child(f, "model_scheme"), scene::kModelSchemes))
    control.model_scheme = std::string(scene::kModelSchemes[*k]);
  if (auto dt = c.number(c.child(f, "dt_control"), Range::positive())) control.dt_control = *dt;
  if (auto th = c.number(c.child(f, "threshold"), Range::positive())) control.threshold = *th;
  read_steps(c, f, control);
  if (auto stop = c.boolean(c.child(f, "stop_at_success"))) control.stop_at_success = *stop;
  control.weights = read_weights(c, Checker::child(f, "weights"));
  if (auto seed = c.integer(c.child(f, "seed"), 0)) control.seed = static_cast<unsigned>(*seed);

  const Field count = c.child(f, "target_count");
  if (auto n = c.integer(count, 1)) {
    if (given)
      c.error(count.key_mark, count.path,
              "has no effect: the targets come from control." + std::string(*given) +
                  " (target_count is how many are drawn when neither targets nor trajectory "
                  "is given)");
    else
      control.target_count = *n;
  }
  check_actuator_limits(c, f, actuators, read);
  return control;
}

}  // namespace rodlab::io::detail
