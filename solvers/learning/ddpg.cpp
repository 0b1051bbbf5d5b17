#include "rodlab/solvers/learning/ddpg.hpp"

#include <algorithm>
#include <chrono>
#include <future>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

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

Precision parse_precision(std::string_view name) {
  if (name == "float64") return Precision::float64;
  if (name == "float32") return Precision::float32;
  throw std::invalid_argument("ddpg: precision is float64 or float32 (got " + std::string(name) +
                              ")");
}

namespace detail {

/// The four networks, their optimisers and the update's workspace, in one precision.
class DdpgNetworks {
 public:
  virtual ~DdpgNetworks() = default;
  virtual void act(const Eigen::VectorXd& observation, Eigen::VectorXd& action) = 0;
  virtual void update(const ReplayBuffer& buffer, std::mt19937_64& rng) = 0;
  virtual Mlp<double> actor() const = 0;
  virtual Mlp<double> critic() const = 0;
};

}  // namespace detail

namespace {

template <class Scalar>
class NetworksOf final : public detail::DdpgNetworks {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Row = Eigen::Matrix<Scalar, 1, Eigen::Dynamic>;

 public:
  NetworksOf(int n_obs, int n_act, const DdpgOptions& o)
      : o_(o), n_obs_(n_obs), n_act_(n_act),
        actor_(network(n_obs, o.actor_hidden, n_act, o.hidden, o.actor_output,
                       part_seed(o.seed, 1), o.final_layer_scale)),
        critic_(network(n_obs + n_act, o.critic_hidden, 1, o.hidden, Activation::identity,
                        part_seed(o.seed, 2), o.final_layer_scale)),
        actor_target_(actor_), critic_target_(critic_),
        actor_adam_(actor_.parameter_count(), adam(o.actor_learning_rate)),
        critic_adam_(critic_.parameter_count(), adam(o.critic_learning_rate)),
        grad_actor_(actor_.parameter_count()), grad_critic_(critic_.parameter_count()),
        x_(n_obs), y_(n_act) {}

  void act(const Eigen::VectorXd& observation, Eigen::VectorXd& action) override {
    x_ = observation.cast<Scalar>();
    actor_.infer(x_, y_);
    action = y_.template cast<double>();
  }

  void update(const ReplayBuffer& buffer, std::mt19937_64& rng) override;

  Mlp<double> actor() const override { return converted<double>(actor_); }
  Mlp<double> critic() const override { return converted<double>(critic_); }

 private:
  DdpgOptions o_;
  int n_obs_, n_act_;
  Mlp<Scalar> actor_, critic_, actor_target_, critic_target_;
  Adam<Scalar> actor_adam_, critic_adam_;
  Vector grad_actor_, grad_critic_, x_, y_;
  // update()'s workspace (allocated on the first update, reused)
  MlpWorkspace<Scalar> ws_actor_, ws_critic_, ws_critic_pi_, ws_actor_target_, ws_critic_target_;
  Matrix S_, A_, S2_, SA_, Y_, G_, dX_;
  Row R_, T_;
  Eigen::MatrixXd S64_, A64_, S2_64_;  // a float32 minibatch as sampled
  Eigen::RowVectorXd R64_, T64_;
};

template <class Scalar>
void NetworksOf<Scalar>::update(const ReplayBuffer& buffer, std::mt19937_64& rng) {
  const int B = o_.batch_size;
  if constexpr (std::is_same_v<Scalar, double>) {
    buffer.sample(rng, B, S_, A_, R_, S2_, T_);
  } else {
    buffer.sample(rng, B, S64_, A64_, R64_, S2_64_, T64_);
    S_ = S64_.cast<Scalar>();
    A_ = A64_.cast<Scalar>();
    R_ = R64_.cast<Scalar>();
    S2_ = S2_64_.cast<Scalar>();
    T_ = T64_.cast<Scalar>();
  }
  // the target value y = r + gamma (1 - terminal) Q'(s', mu'(s'))  (4.38)
  const auto& A2 = actor_target_.forward(S2_, ws_actor_target_);
  SA_.resize(n_obs_ + n_act_, B);
  SA_.topRows(n_obs_) = S2_;
  SA_.bottomRows(n_act_) = A2;
  const auto& Q2 = critic_target_.forward(SA_, ws_critic_target_);
  // (a terminal sample's Q' is not used at all: selected away, not multiplied by 0, so that a
  // non-finite next observation cannot leak in)
  const Scalar gamma(o_.gamma);
  Y_ = R_ + gamma * (T_.array() > Scalar(0.5)).select(Scalar(0), Q2.row(0).array()).matrix();
  // the critic: L_Q = 1/B sum (Q(s, a) - y)^2
  SA_.topRows(n_obs_) = S_;
  SA_.bottomRows(n_act_) = A_;
  const auto& Q = critic_.forward(SA_, ws_critic_);
  G_ = (Scalar(2) / B) * (Q - Y_);
  grad_critic_.setZero();
  critic_.backward(ws_critic_, G_, &grad_critic_);
  critic_adam_.step(critic_.parameters(), grad_critic_);
  // the actor: ascend 1/B sum Q(s, mu(s)) through dQ/da (4.39), with the updated critic
  const auto& mu = actor_.forward(S_, ws_actor_);
  SA_.bottomRows(n_act_) = mu;
  critic_.forward(SA_, ws_critic_pi_);
  G_.setConstant(1, B, Scalar(-1) / B);  // minimise -J
  critic_.backward(ws_critic_pi_, G_, nullptr, &dX_);
  grad_actor_.setZero();
  actor_.backward(ws_actor_, dX_.bottomRows(n_act_), &grad_actor_);
  actor_adam_.step(actor_.parameters(), grad_actor_);
  // the targets
  actor_target_.soft_update_from(actor_, Scalar(o_.tau));
  critic_target_.soft_update_from(critic_, Scalar(o_.tau));
}

std::unique_ptr<detail::DdpgNetworks> make_networks(int n_obs, int n_act, const DdpgOptions& o) {
  if (o.precision == Precision::float32) return std::make_unique<NetworksOf<float>>(n_obs, n_act, o);
  return std::make_unique<NetworksOf<double>>(n_obs, n_act, o);
}

}  // namespace

Ddpg::Ddpg(int observation_size, int action_size, const DdpgOptions& o)
    : options_(o), n_obs_(observation_size), n_act_(action_size), rng_(part_seed(o.seed, 3)),
      x_(observation_size), y_(action_size) {
  RODLAB_THROW_UNLESS(observation_size >= 1 && action_size >= 1,
                      "ddpg: observation and action sizes must be >= 1");
  RODLAB_THROW_UNLESS(o.gamma >= 0.0 && o.gamma <= 1.0 && o.tau > 0.0 && o.tau <= 1.0 &&
                          o.batch_size >= 1 && o.buffer_capacity >= 1 && o.warmup >= 0 &&
                          o.updates_per_step >= 0 && o.noise_theta >= 0.0 &&
                          o.noise_sigma >= 0.0,
                      "ddpg: gamma in [0, 1], tau in (0, 1], batch_size and buffer_capacity >= 1, "
                      "warmup, updates_per_step and the noise not negative");
  networks_ = make_networks(observation_size, action_size, o);
}

Ddpg::~Ddpg() = default;
Ddpg::Ddpg(Ddpg&&) noexcept = default;
Ddpg& Ddpg::operator=(Ddpg&&) noexcept = default;

Mlp<double> Ddpg::actor() const { return networks_->actor(); }
Mlp<double> Ddpg::critic() const { return networks_->critic(); }

void Ddpg::act(std::span<const double> observation, std::span<double> action) {
  RODLAB_THROW_UNLESS(static_cast<int>(observation.size()) == n_obs_ &&
                          static_cast<int>(action.size()) == n_act_,
                      "ddpg: expected {} observations and {} actions", n_obs_, n_act_);
  x_ = Eigen::Map<const Eigen::VectorXd>(observation.data(), n_obs_);
  networks_->act(x_, y_);
  for (int k = 0; k < n_act_; ++k) action[static_cast<std::size_t>(k)] = std::clamp(y_[k], -1.0, 1.0);
}

void Ddpg::update(const ReplayBuffer& buffer) { networks_->update(buffer, rng_); }

DdpgLog Ddpg::train(LearningEnvironment& env, long samples,
                    const std::function<void(const DdpgEpisode&)>& progress) {
  LearningEnvironment* one[] = {&env};
  return train(one, samples, progress);
}

namespace {

/// One environment's episode in progress.
struct Lane {
  LearningEnvironment* env = nullptr;
  std::vector<double> s, s2, a, noise;
  DdpgEpisode episode;
  Transition last;
  bool fresh = true;  ///< reset before the next step
};

}  // namespace

DdpgLog Ddpg::train(std::span<LearningEnvironment* const> envs, long samples,
                    const std::function<void(const DdpgEpisode&)>& progress) {
  RODLAB_THROW_UNLESS(!envs.empty(), "ddpg: no environment to train on");
  for (const auto* env : envs)
    RODLAB_THROW_UNLESS(env->observation_size() == n_obs_ && env->action_size() == n_act_,
                        "ddpg: an environment has {} observations and {} actions, the networks "
                        "{} and {}",
                        env->observation_size(), env->action_size(), n_obs_, n_act_);
  const auto t0 = std::chrono::steady_clock::now();
  ReplayBuffer buffer(n_obs_, n_act_, std::max(1L, std::min(options_.buffer_capacity, samples)));
  std::vector<Lane> lanes;
  for (auto* env : envs) {
    Lane lane;
    lane.env = env;
    lane.s.resize(static_cast<std::size_t>(n_obs_));
    lane.s2.resize(lane.s.size());
    lane.a.resize(static_cast<std::size_t>(n_act_));
    lane.noise.resize(lane.a.size());
    lanes.push_back(std::move(lane));
  }
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<std::future<void>> running;
  DdpgLog log;
  while (log.samples < samples) {
    // every lane's action, in lane order (the draws and the network are not shared across
    // threads: the same seed gives the same run whatever the timing)
    const long round = std::min<long>(static_cast<long>(lanes.size()), samples - log.samples);
    for (long k = 0; k < round; ++k) {
      Lane& lane = lanes[static_cast<std::size_t>(k)];
      if (lane.fresh) {
        lane.env->reset(rng_(), lane.s);
        std::fill(lane.noise.begin(), lane.noise.end(), 0.0);
        lane.episode = {};
        lane.episode.min_error = std::numeric_limits<double>::infinity();
        lane.fresh = false;
      }
      if (log.samples + k < options_.warmup) {
        for (double& v : lane.a) v = uniform(rng_);
      } else {
        act(lane.s, lane.a);
        for (std::size_t i = 0; i < lane.a.size(); ++i) {  // Ornstein-Uhlenbeck, dt = 1 step
          lane.noise[i] += -options_.noise_theta * lane.noise[i] + options_.noise_sigma * normal(rng_);
          lane.a[i] = std::clamp(lane.a[i] + lane.noise[i], -1.0, 1.0);
        }
      }
    }
    // the steps, in parallel: one thread per lane but the first, which steps here
    running.clear();
    for (long k = 1; k < round; ++k)
      running.push_back(std::async(std::launch::async, [&lane = lanes[static_cast<std::size_t>(k)]] {
        lane.last = lane.env->step(lane.a, lane.s2);
      }));
    lanes[0].last = lanes[0].env->step(lanes[0].a, lanes[0].s2);
    for (auto& f : running) f.get();  // rethrows a lane's exception
    // the transitions and updates, in lane order
    for (long k = 0; k < round; ++k) {
      Lane& lane = lanes[static_cast<std::size_t>(k)];
      const Transition& tr = lane.last;
      ++log.samples;
      DdpgEpisode& e = lane.episode;
      ++e.steps;
      e.return_sum += tr.reward;
      e.final_error = tr.error;
      e.min_error = std::min(e.min_error, tr.error);
      e.success = e.success || tr.success;
      if (tr.failed) e.failed = true, e.reason = tr.reason;
      buffer.add(lane.s, lane.a, tr.reward, lane.s2, tr.terminal);
      std::swap(lane.s, lane.s2);
      if (log.samples >= options_.warmup && buffer.size() >= options_.batch_size)
        for (int u = 0; u < options_.updates_per_step; ++u, ++log.updates) update(buffer);
      if (tr.done || log.samples >= samples) {
        e.samples = log.samples;
        log.episodes.push_back(e);
        if (progress) progress(e);
        lane.fresh = true;
      }
    }
  }
  log.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return log;
}

}  // namespace rodlab::solvers::learning
