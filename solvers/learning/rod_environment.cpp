#include "rodlab/solvers/learning/rod_environment.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "rodlab/check.hpp"
#include "rodlab/scene/trajectory.hpp"
#include "rodlab/solvers/learning/action_map.hpp"
#include "rodlab/solvers/learning/reward.hpp"

namespace rodlab::solvers::learning {
namespace {

/// Central-difference step of a trajectory's velocity [s].
constexpr double kVelocityStep = 1e-4;

}  // namespace

const char* task_name(LearningTask task) {
  switch (task) {
    case LearningTask::reach_one: return "reach-one";
    case LearningTask::reach_any: return "reach-any";
    case LearningTask::track: return "track";
  }
  return "?";
}

LearningTask task_from_name(const std::string& name) {
  for (const LearningTask t : {LearningTask::reach_one, LearningTask::reach_any, LearningTask::track})
    if (name == task_name(t)) return t;
  throw std::invalid_argument("learning: unknown task '" + name +
                              "' (reach-one, reach-any, track)");
}

lie::Vector3 Goal::position(double t) const {
  if (path) return path->position(t);
  if (trajectory) return scene::position(*trajectory, t);
  return point.value_or(lie::Vector3::Zero());
}

lie::Vector3 Goal::velocity(double t) const {
  if (path) return path->velocity(t);
  if (trajectory)
    return (scene::position(*trajectory, t + kVelocityStep) -
            scene::position(*trajectory, t - kVelocityStep)) /
           (2.0 * kVelocityStep);
  return lie::Vector3::Zero();
}

double Goal::duration() const {
  if (path) return path->duration();
  if (trajectory) return scene::duration(*trajectory);
  return 0.0;
}

RodEnvironment::RodEnvironment(const scene::Scene& scene, const EnvironmentOptions& options, GoalPool pool)
    : options_(options), pool_(std::move(pool)), plant_(scene, options.plant),
      initial_(plant_.snapshot()),
      observer_(plant_, options.plant.solver.nodes,
                {.goal_velocity = options.task == LearningTask::track,
                 .state_nodes = options.state_nodes}) {
  RODLAB_THROW_UNLESS(options.beta > 0.0 && options.beta <= 1.0,
                      "learning: beta must be in (0, 1] (got {:g})", options.beta);
  RODLAB_THROW_UNLESS(options.threshold > 0.0 && options.max_steps >= 1 &&
                          options.state_nodes >= 0 && options.track_duration > 0.0 &&
                          options.track_end_speed >= 0.0,
                      "learning: threshold, max_steps and track_duration must be positive, "
                      "state_nodes and track_end_speed not negative");
  RODLAB_THROW_UNLESS(!pool_.points.empty(), "learning: the goal pool is empty");
  RODLAB_THROW_UNLESS(options.task != LearningTask::track || pool_.points.size() >= 2,
                      "learning: track needs at least two points in the pool (got {})",
                      pool_.points.size());
  u_.resize(plant_.input_count());
  options_.cost.beta = options.beta;
  // o = J x + goal: x's first 6 entries (tip, velocity) are o's first 6; the goal's entries
  // follow in o; the node coordinates close both
  const int n = state_size(), g = goal_entries();
  observation_jacobian_ = Eigen::MatrixXd::Zero(observer_.size(), n);
  for (int i = 0; i < n; ++i) observation_jacobian_(i < 6 ? i : i + g, i) = 1.0;
}

void RodEnvironment::state(std::span<double> x) const {
  RODLAB_THROW_UNLESS(static_cast<int>(x.size()) == state_size() && !last_observation_.empty(),
                      "learning: expected a state of {} values after a reset (got {})",
                      state_size(), x.size());
  const int g = goal_entries();
  for (int i = 0; i < state_size(); ++i) x[i] = last_observation_[i < 6 ? i : i + g];
}

double RodEnvironment::cost(const Eigen::Ref<const Eigen::VectorXd>& x,
                            const Eigen::Ref<const Eigen::VectorXd>& a, int t,
                            CostExpansion* e) const {
  RODLAB_THROW_UNLESS(x.size() == state_size() && a.size() == action_size(),
                      "learning: the cost of {} states and {} actions (expected {} and {})",
                      x.size(), a.size(), state_size(), action_size());
  const double time = t * plant_.dt_control(), L = length();
  const lie::Vector3 goal = goal_.position(time) / L;
  const lie::Vector3 velocity = goal_.velocity(time) * period() / L;
  return options_.cost(x, a, goal, velocity, t == episode_steps() - 1, e);
}

void RodEnvironment::set_fixed_length(int steps) {
  RODLAB_THROW_UNLESS(steps >= 1, "learning: a fixed episode length must be >= 1 (got {})", steps);
  fixed_length_ = steps;
}

void RodEnvironment::reset(std::uint64_t seed, std::span<double> observation) {
  std::mt19937_64 rng(seed);
  const auto draw = [&] { return pool_.points[rng() % pool_.points.size()]; };
  Goal goal;
  switch (options_.task) {
    case LearningTask::reach_one: goal.point = pool_.points.front(); break;
    case LearningTask::reach_any: goal.point = draw(); break;
    case LearningTask::track: {
      const lie::Vector3 start = draw();
      lie::Vector3 end = draw();
      for (int tries = 0; tries < 16 && end == start; ++tries) end = draw();
      std::uniform_real_distribution<double> speed(-options_.track_end_speed,
                                                   options_.track_end_speed);
      const lie::Vector3 v0(speed(rng), speed(rng), speed(rng));
      const lie::Vector3 v1(speed(rng), speed(rng), speed(rng));
      goal.path.emplace(start, v0, end, v1, options_.track_duration);
      break;
    }
  }
  reset(goal, observation);
}

void RodEnvironment::reset(const Goal& goal, std::span<double> observation) {
  RODLAB_THROW_UNLESS(goal.point || goal.path || goal.trajectory, "learning: an empty goal");
  RODLAB_THROW_UNLESS((options_.task == LearningTask::track) == (goal.duration() > 0.0),
                      "learning: task {} needs a {}", task_name(options_.task),
                      options_.task == LearningTask::track ? "path" : "point");
  goal_ = goal;
  plant_.restore(initial_);
  tip_before_ = plant_.tip();
  steps_ = 0;
  error_sum_ = 0.0;
  last_error_ = (plant_.tip() - goal.position(0.0)).norm();
  done_ = false;
  observe(observation);
}

void RodEnvironment::action_to_input(std::span<const double> action, Eigen::VectorXd& u) const {
  RODLAB_THROW_UNLESS(static_cast<int>(action.size()) == action_size(),
                      "learning: expected {} actions, got {}", action_size(), action.size());
  input_of_action(action, plant_.lower(), plant_.upper(), u);
}

int RodEnvironment::episode_steps() const {
  if (fixed_length_ > 0) return fixed_length_;
  if (options_.task != LearningTask::track) return options_.max_steps;
  return std::max(1, static_cast<int>(std::ceil(goal_.duration() / plant_.dt_control() - 1e-9)));
}

Transition RodEnvironment::step(std::span<const double> action, std::span<double> observation) {
  RODLAB_THROW_UNLESS(!done_, "learning: step after the episode ended (reset first)");
  action_to_input(action, u_);
  plant_.set_input(u_);
  tip_before_ = plant_.tip();
  const dynamics::StepStatus status = plant_.advance();
  ++steps_;
  Transition tr;
  const double L = length();
  tr.error = (plant_.tip() - goal_.position(time())).norm();
  if (!status.ok) {  // the state where the scheme stopped is no observation: the last one stays
    tr.reward = -1.0;
    tr.done = tr.terminal = tr.failed = true;
    tr.reason = "the plant's step failed: " + status.reason;
    tr.error = last_error_;
    done_ = true;
    std::copy(last_observation_.begin(), last_observation_.end(), observation.begin());
    return tr;
  }
  tr.reward = reward(tr.error, options_.beta, L);  // (4.40)
  error_sum_ += tr.error;
  const bool track = options_.task == LearningTask::track;
  const bool last = steps_ >= episode_steps();
  tr.success = track ? last && error_sum_ / steps_ < options_.threshold * L
                     : tr.error < options_.threshold * L;
  tr.terminal = !track && tr.success && fixed_length_ == 0;
  tr.done = last || tr.terminal;
  done_ = tr.done;
  last_error_ = tr.error;
  observe(observation);
  return tr;
}

void RodEnvironment::observe(std::span<double> o) {
  // the goal at the end of the coming control step
  const double t_next = time() + plant_.dt_control();
  std::optional<lie::Vector3> before;
  if (steps_ > 0) before = tip_before_;
  observer_.observe(plant_, before, goal_.position(t_next), goal_.velocity(t_next), o);
  last_observation_.assign(o.begin(), o.end());  // no allocation after the first
}

}  // namespace rodlab::solvers::learning
