// learning: the settings of `rodlab train` (docs/scene-reference.md "learning"): the
// environment's, the goals' and DDPG's hyper-parameters; each absent one keeps the solvers'
// default.
#include "scene_readers.hpp"

namespace rodlab::io::detail {
namespace {

/// A list of hidden layer sizes, each >= 1 (an empty list: no hidden layer).
std::optional<std::vector<int>> read_sizes(Checker& c, const Field& f) {
  if (!f.present()) return std::nullopt;
  const auto items = c.list(f);
  if (!items) return std::nullopt;
  std::vector<int> sizes;
  for (const Field& item : *items) {
    const auto n = c.integer(item, 1);
    if (!n) return std::nullopt;
    sizes.push_back(*n);
  }
  return sizes;
}

scene::LearningDdpg read_ddpg(Checker& c, const Field& f) {
  scene::LearningDdpg d;
  if (!c.keys(f, {"actor_hidden", "critic_hidden", "activation", "actor_learning_rate",
                  "critic_learning_rate", "gamma", "tau", "batch_size", "buffer_capacity",
                  "warmup", "updates_per_step", "noise_theta", "noise_sigma",
                  "final_layer_scale", "precision"}))
    return d;
  d.actor_hidden = read_sizes(c, Checker::child(f, "actor_hidden"));
  d.critic_hidden = read_sizes(c, Checker::child(f, "critic_hidden"));
  static constexpr std::string_view kActivations[] = {"tanh", "relu"};
  if (auto k = c.choice(Checker::child(f, "activation"), kActivations))
    d.activation = std::string(kActivations[*k]);
  d.actor_learning_rate = c.number(Checker::child(f, "actor_learning_rate"), Range::positive());
  d.critic_learning_rate = c.number(Checker::child(f, "critic_learning_rate"), Range::positive());
  d.gamma = c.number(Checker::child(f, "gamma"), Range{0.0, 1.0, false, false});
  d.tau = c.number(Checker::child(f, "tau"), Range{0.0, 1.0, true, false});
  d.batch_size = c.integer(Checker::child(f, "batch_size"), 1);
  d.buffer_capacity = c.integer(Checker::child(f, "buffer_capacity"), 1);
  d.warmup = c.integer(Checker::child(f, "warmup"), 0);
  d.updates_per_step = c.integer(Checker::child(f, "updates_per_step"), 0);
  d.noise_theta = c.number(Checker::child(f, "noise_theta"), Range::non_negative());
  d.noise_sigma = c.number(Checker::child(f, "noise_sigma"), Range::non_negative());
  d.final_layer_scale = c.number(Checker::child(f, "final_layer_scale"), Range::non_negative());
  static constexpr std::string_view kPrecisions[] = {"float64", "float32"};
  if (auto k = c.choice(Checker::child(f, "precision"), kPrecisions))
    d.precision = std::string(kPrecisions[*k]);
  return d;
}

scene::LearningGps read_gps(Checker& c, const Field& f) {
  scene::LearningGps g;
  if (!c.keys(f, {"conditions", "samples_per_condition", "steps", "policy_hidden", "activation",
                  "policy_learning_rate", "policy_epochs", "batch_size", "kl_step",
                  "min_step_mult", "max_step_mult", "initial_action", "initial_variance",
                  "noise_smoothing", "prior_clusters", "prior_trajectories", "entropy",
                  "sample_on_policy", "redraw_conditions", "cost"}))
    return g;
  g.conditions = c.integer(Checker::child(f, "conditions"), 1);
  g.samples_per_condition = c.integer(Checker::child(f, "samples_per_condition"), 2);
  g.steps = c.integer(Checker::child(f, "steps"), 2);
  g.policy_hidden = read_sizes(c, Checker::child(f, "policy_hidden"));
  static constexpr std::string_view kActivations[] = {"tanh", "relu"};
  if (auto k = c.choice(Checker::child(f, "activation"), kActivations))
    g.activation = std::string(kActivations[*k]);
  g.policy_learning_rate = c.number(Checker::child(f, "policy_learning_rate"), Range::positive());
  g.policy_epochs = c.integer(Checker::child(f, "policy_epochs"), 0);
  g.batch_size = c.integer(Checker::child(f, "batch_size"), 1);
  g.kl_step = c.number(Checker::child(f, "kl_step"), Range::positive());
  g.min_step_mult = c.number(Checker::child(f, "min_step_mult"), Range::positive());
  g.max_step_mult = c.number(Checker::child(f, "max_step_mult"), Range::positive());
  g.sample_on_policy = c.boolean(Checker::child(f, "sample_on_policy"));
  g.redraw_conditions = c.boolean(Checker::child(f, "redraw_conditions"));
  if (g.redraw_conditions.value_or(false) && !g.sample_on_policy.value_or(false))
    c.error(Checker::child(f, "redraw_conditions"), "needs sample_on_policy: true");
  g.entropy = c.number(Checker::child(f, "entropy"), Range::non_negative());
  g.initial_action = c.number(Checker::child(f, "initial_action"), Range{-1.0, 1.0, true, true});
  g.initial_variance = c.number(Checker::child(f, "initial_variance"), Range::positive());
  g.noise_smoothing = c.number(Checker::child(f, "noise_smoothing"), Range::non_negative());
  g.prior_clusters = c.integer(Checker::child(f, "prior_clusters"), 1);
  g.prior_trajectories = c.integer(Checker::child(f, "prior_trajectories"), 1);
  const Field cost = Checker::child(f, "cost");
  if (cost.present() &&
      c.keys(cost, {"alpha", "quadratic", "velocity", "action", "bound", "running", "final", "log"})) {
    g.cost_alpha = c.number(Checker::child(cost, "alpha"), Range::positive());
    g.cost_quadratic = c.number(Checker::child(cost, "quadratic"), Range::non_negative());
    g.cost_velocity = c.number(Checker::child(cost, "velocity"), Range::non_negative());
    g.cost_action = c.number(Checker::child(cost, "action"), Range::non_negative());
    g.cost_bound = c.number(Checker::child(cost, "bound"), Range::non_negative());
    g.cost_running = c.number(Checker::child(cost, "running"), Range::non_negative());
    g.cost_final = c.number(Checker::child(cost, "final"), Range::non_negative());
    g.cost_log = c.number(Checker::child(cost, "log"), Range::non_negative());
  }
  if (g.min_step_mult && g.max_step_mult && *g.max_step_mult < *g.min_step_mult)
    c.error(Checker::child(f, "max_step_mult"),
            "must be >= min_step_mult (" + format_number(*g.min_step_mult) + ")");
  return g;
}

}  // namespace

scene::Learning read_learning(Checker& c, const Field& f) {
  scene::Learning l;
  if (!c.keys(f, {"beta", "max_steps", "state_nodes", "track_duration", "track_end_speed",
                  "dynamic_holds", "static_points", "ddpg", "gps"}))
    return l;
  l.beta = c.number(Checker::child(f, "beta"), Range{0.0, 1.0, true, false});
  l.max_steps = c.integer(Checker::child(f, "max_steps"), 1);
  l.state_nodes = c.integer(Checker::child(f, "state_nodes"), 0);
  l.track_duration = c.number(Checker::child(f, "track_duration"), Range::positive());
  l.track_end_speed = c.number(Checker::child(f, "track_end_speed"), Range::non_negative());
  l.dynamic_holds = c.integer(Checker::child(f, "dynamic_holds"), 1);
  l.static_points = c.integer(Checker::child(f, "static_points"), 2);
  l.ddpg = read_ddpg(c, Checker::child(f, "ddpg"));
  l.gps = read_gps(c, Checker::child(f, "gps"));
  return l;
}

}  // namespace rodlab::io::detail
