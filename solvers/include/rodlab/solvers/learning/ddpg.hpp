#pragma once
// Deep deterministic policy gradient (Lillicrap et al. 2016, Algorithm 1; thesis 4.3.1, (4.38)-
// (4.39), Algorithm 5; docs/learning.md "DDPG"). An actor mu(s) (tanh output: actions in
// [-1, 1]^m) and a critic Q(s, a) (the action concatenated with the observation at the input),
// their target copies mu', Q' following by soft updates theta' <- tau theta + (1 - tau) theta',
// a replay buffer, and Ornstein-Uhlenbeck exploration noise. Per environment step, after
// `warmup` steps of uniform random actions, `updates_per_step` updates on minibatches:
//
//   y   = r + gamma (1 - terminal) Q'(s', mu'(s'))                  (4.38), the target value
//   L_Q = 1/N sum (Q(s, a) - y)^2                                   critic, Adam
//   grad_theta_mu J = 1/N sum dQ/da (s, mu(s)) dmu/dtheta_mu       (4.39), actor, Adam ascent
//
// A time-limit end of an episode is not terminal: its target bootstraps (learning_environment.hpp).
// Every random draw comes from the options' seed (network initialisation, replay sampling,
// noise, the environments' episode seeds): the same seed gives the same training bit for bit.
// The networks compute in float64 (the default) or float32 (`precision`): the environment, the
// replay buffer and the exploration stay float64; a float32 run's actor converts to float64
// exactly for the policy file.
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rodlab/solvers/learning/activation.hpp"
#include "rodlab/solvers/learning/adam.hpp"
#include "rodlab/solvers/learning/learning_environment.hpp"
#include "rodlab/solvers/learning/mlp.hpp"
#include "rodlab/solvers/learning/replay_buffer.hpp"

namespace rodlab::solvers::learning {

/// The arithmetic of DDPG's networks and their updates.
enum class Precision { float64, float32 };

/// "float64" or "float32"; throws std::invalid_argument otherwise.
Precision parse_precision(std::string_view name);

struct DdpgOptions {
  std::vector<int> actor_hidden{64, 64};   ///< hidden layer sizes of mu
  std::vector<int> critic_hidden{64, 64};  ///< hidden layer sizes of Q
  Activation hidden = Activation::relu;    ///< both networks' hidden activation (the paper)
  /// mu's output: tanh keeps actions in [-1, 1] (the paper's bounded actions); identity for
  /// tests of linear policies (the environment clips).
  Activation actor_output = Activation::tanh;
  double actor_learning_rate = 1e-4;   ///< the paper's
  double critic_learning_rate = 1e-3;  ///< the paper's
  double gamma = 0.99;                 ///< discount (4.35)
  double tau = 1e-3;                   ///< soft target updates (the paper's)
  int batch_size = 64;                 ///< the paper's 64
  long buffer_capacity = 1'000'000;    ///< the paper's 1e6 (at most the samples of a run)
  long warmup = 0;                     ///< steps of uniform random actions before learning
  int updates_per_step = 1;
  double noise_theta = 0.15;  ///< Ornstein-Uhlenbeck mean reversion per step (the paper's)
  double noise_sigma = 0.2;   ///< its scale per step (the paper's), in action units
  double final_layer_scale = 3e-3;  ///< both output layers start in +-3e-3 (the paper's)
  /// float64, or float32: updates several times faster (docs/learning.md "DDPG"), the
  /// networks' rounding 1e-7 instead of 1e-16 (Adam's steps are far larger)
  Precision precision = Precision::float64;
  std::uint64_t seed = 1;
};

namespace detail {
class DdpgNetworks;  // the networks in the options' precision (ddpg.cpp)
}

/// What a training run measured, per episode.
struct DdpgEpisode {
  long samples = 0;  ///< environment steps so far, this episode included
  int steps = 0;
  double return_sum = 0.0;  ///< undiscounted sum of rewards
  double final_error = 0.0, min_error = 0.0;
  bool success = false, failed = false;
  std::string reason;  ///< why the environment's step failed (failed)
};

struct DdpgLog {
  std::vector<DdpgEpisode> episodes;
  long samples = 0, updates = 0;
  double wall_time_s = 0.0;
};

class Ddpg {
 public:
  /// Throws std::invalid_argument for bad sizes or options.
  Ddpg(int observation_size, int action_size, const DdpgOptions& options);
  ~Ddpg();
  Ddpg(Ddpg&&) noexcept;
  Ddpg& operator=(Ddpg&&) noexcept;

  /// The policy's action for an observation (no noise), each in [-1, 1] after clipping.
  void act(std::span<const double> observation, std::span<double> action);

  /// Trains on `env` for `samples` environment steps (whole episodes are cut at the budget).
  /// `progress` (if set) is called after every episode.
  DdpgLog train(LearningEnvironment& env, long samples,
                const std::function<void(const DdpgEpisode&)>& progress = {});
  /// The same on several environments that step in parallel (one thread each): per round
  /// every environment's action is chosen (in order), all step at once, then their transitions
  /// enter the buffer and the updates follow, in order, `updates_per_step` per transition. The
  /// same seed and number of environments give the same run bit for bit, whatever the timing;
  /// a different number of environments gives a different (equally valid) run.
  DdpgLog train(std::span<LearningEnvironment* const> envs, long samples,
                const std::function<void(const DdpgEpisode&)>& progress = {});

  /// One update of critic, actor and targets from a minibatch of `buffer`.
  void update(const ReplayBuffer& buffer);

  /// The actor mu and the critic Q, in float64 (a float32 run's converted exactly).
  Mlp<double> actor() const;
  Mlp<double> critic() const;
  const DdpgOptions& options() const { return options_; }

 private:
  DdpgOptions options_;
  int n_obs_, n_act_;
  std::unique_ptr<detail::DdpgNetworks> networks_;
  std::mt19937_64 rng_;
  Eigen::VectorXd x_, y_;  // act()'s
};

}  // namespace rodlab::solvers::learning
