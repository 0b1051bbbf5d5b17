#include "rodlab/solvers/learning/ddpg.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

MlpConfig network(int in, const std::vector<int>& hidden, int out, Activation h, Activation o,
                  std::uint64_t seed, double final_scale) {
  MlpConfig c;
  c.sizes.push_back(in);
  c.sizes.insert(c.sizes.end(), hidden.begin(), hidden.end());
  c.sizes.push_back(out);
  c.hidden = h;
  c.output = o;
  c.seed = seed;
  c.final_layer_scale = final_scale;
  return c;
}

AdamOptions adam(double learning_rate) {
  AdamOptions a;
  a.learning_rate = learning_rate;
  return a;
}

/// The seeds of the parts, from the run's seed (distinct streams).
std::uint64_t part_seed(std::uint64_t seed, std::uint64_t part) {
  return seed * 0x9E3779B97F4A7C15ULL + part;
}

}  // namespace

Ddpg::Ddpg(int observation_size, int action_size, const DdpgOptions& o)
    : options_(o), n_obs_(observation_size), n_act_(action_size),
      actor_(network(observation_size, o.actor_hidden, action_size, o.hidden, o.actor_output,
                     part_seed(o.seed, 1), o.final_layer_scale)),
      critic_(network(observation_size + action_size, o.critic_hidden, 1, o.hidden,
                      Activation::identity, part_seed(o.seed, 2), o.final_layer_scale)),
      actor_target_(actor_), critic_target_(critic_),
      actor_adam_(actor_.parameter_count(), adam(o.actor_learning_rate)),
      critic_adam_(critic_.parameter_count(), adam(o.critic_learning_rate)),
      rng_(part_seed(o.seed, 3)) {
  RODLAB_THROW_UNLESS(observation_size >= 1 && action_size >= 1,
                      "ddpg: observation and action sizes must be >= 1");
  RODLAB_THROW_UNLESS(o.gamma >= 0.0 && o.gamma <= 1.0 && o.tau > 0.0 && o.tau <= 1.0 &&
                          o.batch_size >= 1 && o.buffer_capacity >= 1 && o.warmup >= 0 &&
                          o.updates_per_step >= 0 && o.noise_theta >= 0.0 &&
                          o.noise_sigma >= 0.0,
                      "ddpg: gamma in [0, 1], tau in (0, 1], batch_size and buffer_capacity >= 1, "
                      "warmup, updates_per_step and the noise not negative");
  grad_actor_.resize(actor_.parameter_count());
  grad_critic_.resize(critic_.parameter_count());
  x_.resize(n_obs_);
  y_.resize(n_act_);
}

void Ddpg::act(std::span<const double> observation, std::span<double> action) {
  RODLAB_THROW_UNLESS(static_cast<int>(observation.size()) == n_obs_ &&
                          static_cast<int>(action.size()) == n_act_,
                      "ddpg: expected {} observations and {} actions", n_obs_, n_act_);
  x_ = Eigen::Map<const Eigen::VectorXd>(observation.data(), n_obs_);
  actor_.infer(x_, y_);
  for (int k = 0; k < n_act_; ++k) action[static_cast<std::size_t>(k)] = std::clamp(y_[k], -1.0, 1.0);
}

void Ddpg::update(const ReplayBuffer& buffer) {
  const int B = options_.batch_size;
  buffer.sample(rng_, B, S_, A_, R_, S2_, T_);
  // the target value y = r + gamma (1 - terminal) Q'(s', mu'(s'))  (4.38)
  const auto& A2 = actor_target_.forward(S2_, ws_actor_target_);
  SA_.resize(n_obs_ + n_act_, B);
  SA_.topRows(n_obs_) = S2_;
  SA_.bottomRows(n_act_) = A2;
  const auto& Q2 = critic_target_.forward(SA_, ws_critic_target_);
  Y_ = R_ + options_.gamma * (1.0 - T_.array()).matrix().cwiseProduct(Q2.row(0));
  // the critic: L_Q = 1/B sum (Q(s, a) - y)^2
  SA_.topRows(n_obs_) = S_;
  SA_.bottomRows(n_act_) = A_;
  const auto& Q = critic_.forward(SA_, ws_critic_);
  G_ = (2.0 / B) * (Q - Y_);
  grad_critic_.setZero();
  critic_.backward(ws_critic_, G_, &grad_critic_);
  critic_adam_.step(critic_.parameters(), grad_critic_);
  // the actor: ascend 1/B sum Q(s, mu(s)) through dQ/da (4.39), with the updated critic
  const auto& mu = actor_.forward(S_, ws_actor_);
  SA_.bottomRows(n_act_) = mu;
  critic_.forward(SA_, ws_critic_pi_);
  G_.setConstant(1, B, -1.0 / B);  // minimise -J
  critic_.backward(ws_critic_pi_, G_, nullptr, &dX_);
  grad_actor_.setZero();
  actor_.backward(ws_actor_, dX_.bottomRows(n_act_), &grad_actor_);
  actor_adam_.step(actor_.parameters(), grad_actor_);
  // the targets
  actor_target_.soft_update_from(actor_, options_.tau);
  critic_target_.soft_update_from(critic_, options_.tau);
}

DdpgLog Ddpg::train(LearningEnvironment& env, long samples,
                    const std::function<void(const DdpgEpisode&)>& progress) {
  RODLAB_THROW_UNLESS(env.observation_size() == n_obs_ && env.action_size() == n_act_,
                      "ddpg: the environment has {} observations and {} actions, the networks {} "
                      "and {}",
                      env.observation_size(), env.action_size(), n_obs_, n_act_);
  const auto t0 = std::chrono::steady_clock::now();
  ReplayBuffer buffer(n_obs_, n_act_, std::max(1L, std::min(options_.buffer_capacity, samples)));
  std::vector<double> s(static_cast<std::size_t>(n_obs_)), s2(s.size()),
      a(static_cast<std::size_t>(n_act_));
  std::vector<double> noise(a.size(), 0.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  DdpgLog log;
  while (log.samples < samples) {
    env.reset(rng_(), s);
    std::fill(noise.begin(), noise.end(), 0.0);
    DdpgEpisode e;
    e.min_error = std::numeric_limits<double>::infinity();
    for (Transition tr; !tr.done && log.samples < samples;) {
      if (log.samples < options_.warmup) {
        for (double& v : a) v = uniform(rng_);
      } else {
        act(s, a);
        for (std::size_t k = 0; k < a.size(); ++k) {  // Ornstein-Uhlenbeck, dt = 1 step
          noise[k] += -options_.noise_theta * noise[k] + options_.noise_sigma * normal(rng_);
          a[k] = std::clamp(a[k] + noise[k], -1.0, 1.0);
        }
      }
      tr = env.step(a, s2);
      ++log.samples;
      ++e.steps;
      e.return_sum += tr.reward;
      e.final_error = tr.error;
      e.min_error = std::min(e.min_error, tr.error);
      e.success = e.success || tr.success;
      if (tr.failed) e.failed = true, e.reason = tr.reason;
      buffer.add(s, a, tr.reward, s2, tr.terminal);
      std::swap(s, s2);
      if (log.samples >= options_.warmup && buffer.size() >= options_.batch_size)
        for (int u = 0; u < options_.updates_per_step; ++u, ++log.updates) update(buffer);
    }
    e.samples = log.samples;
    log.episodes.push_back(e);
    if (progress) progress(e);
  }
  log.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return log;
}

}  // namespace rodlab::solvers::learning
