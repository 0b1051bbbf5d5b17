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
                  "final_layer_scale"}))
    return d;
  d.actor_hidden = read_sizes(c, c.child(f, "actor_hidden"));
  d.critic_hidden = read_sizes(c, c.child(f, "critic_hidden"));
  static constexpr std::string_view kActivations[] = {"tanh", "relu"};
  if (auto k = c.choice(c.child(f, "activation"), kActivations))
    d.activation = std::string(kActivations[*k]);
  d.actor_learning_rate = c.number(c.child(f, "actor_learning_rate"), Range::positive());
  d.critic_learning_rate = c.number(c.child(f, "critic_learning_rate"), Range::positive());
  d.gamma = c.number(c.child(f, "gamma"), Range{0.0, 1.0, false, false});
  d.tau = c.number(c.child(f, "tau"), Range{0.0, 1.0, true, false});
  d.batch_size = c.integer(c.child(f, "batch_size"), 1);
  d.buffer_capacity = c.integer(c.child(f, "buffer_capacity"), 1);
  d.warmup = c.integer(c.child(f, "warmup"), 0);
  d.updates_per_step = c.integer(c.child(f, "updates_per_step"), 0);
  d.noise_theta = c.number(c.child(f, "noise_theta"), Range::non_negative());
  d.noise_sigma = c.number(c.child(f, "noise_sigma"), Range::non_negative());
  d.final_layer_scale = c.number(c.child(f, "final_layer_scale"), Range::non_negative());
  return d;
}

}  // namespace

scene::Learning read_learning(Checker& c, const Field& f) {
  scene::Learning l;
  if (!c.keys(f, {"beta", "max_steps", "state_nodes", "track_duration", "track_end_speed",
                  "dynamic_holds", "static_points", "ddpg"}))
    return l;
  l.beta = c.number(c.child(f, "beta"), Range{0.0, 1.0, true, false});
  l.max_steps = c.integer(c.child(f, "max_steps"), 1);
  l.state_nodes = c.integer(c.child(f, "state_nodes"), 0);
  l.track_duration = c.number(c.child(f, "track_duration"), Range::positive());
  l.track_end_speed = c.number(c.child(f, "track_end_speed"), Range::non_negative());
  l.dynamic_holds = c.integer(c.child(f, "dynamic_holds"), 1);
  l.static_points = c.integer(c.child(f, "static_points"), 2);
  l.ddpg = read_ddpg(c, Checker::child(f, "ddpg"));
  return l;
}

}  // namespace rodlab::io::detail
