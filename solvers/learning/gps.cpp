#include "rodlab/solvers/learning/gps.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <numbers>
#include <random>
#include <thread>

#include "rodlab/check.hpp"
#include "rodlab/solvers/learning/regression.hpp"

namespace rodlab::solvers::learning {
namespace {

/// SplitMix64 (Steele, Lea & Flood 2014): the seeds of the noise of each trajectory, from the
/// run's seed, the iteration and the trajectory's index.
std::uint64_t mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

/// A standard normal draw by Box-Muller from the top 53 bits of two draws (the same numbers
/// with every standard library, unlike std::normal_distribution).
double standard_normal(std::mt19937_64& rng) {
  const auto uniform = [&] { return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53; };
  const double u1 = uniform(), u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

/// m x T unit-variance noise: white, then (variance s > 0) filtered along time with a Gaussian
/// kernel of variance s (edges repeat the nearest column) and divided by the filter's
/// amplification sqrt(sum w^2), so each entry keeps unit variance.
Eigen::MatrixXd smooth_noise(int m, int T, double s, std::mt19937_64& rng) {
  Eigen::MatrixXd e(m, T);
  for (int t = 0; t < T; ++t)
    for (int i = 0; i < m; ++i) e(i, t) = standard_normal(rng);
  if (s <= 0.0) return e;
  const int half = static_cast<int>(std::ceil(3.0 * std::sqrt(s)));
  Eigen::VectorXd w(2 * half + 1);
  for (int k = -half; k <= half; ++k) w[k + half] = std::exp(-0.5 * k * k / s);
  w /= w.sum();
  const double gain = std::sqrt(w.squaredNorm());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(m, T);
  for (int t = 0; t < T; ++t)
    for (int k = -half; k <= half; ++k)
      out.col(t) += w[k + half] * e.col(std::clamp(t + k, 0, T - 1));
  return out / gain;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

struct Gps::Sample {
  int condition = 0;
  Eigen::MatrixXd X, U, O;  ///< states, actions, observations: one column per step
  QuadraticCost cost;       ///< the cost expanded about this sample, absolute coordinates
  double cost_sum = 0.0, return_sum = 0.0, min_error = 0.0, final_error = 0.0;
  bool success = false, failed = false;
  std::string reason;
};

Gps::Gps(int state_size, int observation_size, int action_size, const GpsOptions& o)
    : options_(o),
      n_(state_size),
      n_obs_(observation_size),
      m_(action_size),
      policy_([&] {
        MlpConfig c;
        c.sizes.push_back(observation_size);
        c.sizes.insert(c.sizes.end(), o.policy_hidden.begin(), o.policy_hidden.end());
        c.sizes.push_back(action_size);
        c.hidden = o.hidden;
        c.output = Activation::identity;  // the controllers' means are not bounded
        c.seed = o.seed;
        return c;
      }()),
      adam_(policy_.parameter_count(), AdamOptions{.learning_rate = o.policy_learning_rate}),
      policy_variance_(Eigen::VectorXd::Constant(action_size, o.initial_variance)) {
  RODLAB_THROW_UNLESS(state_size >= 1 && observation_size >= 1 && action_size >= 1,
                      "GPS: sizes must be positive (state {}, observation {}, action {})",
                      state_size, observation_size, action_size);
  RODLAB_THROW_UNLESS(o.conditions >= 1 && o.samples_per_condition >= 2 && o.steps >= 2 &&
                          o.policy_epochs >= 0 && o.batch_size >= 1 && o.kl_step > 0.0 &&
                          o.min_step_mult > 0.0 && o.max_step_mult >= o.min_step_mult &&
                          o.initial_variance > 0.0 && o.noise_smoothing >= 0.0 &&
                          o.policy_learning_rate > 0.0 &&
                          (o.sample_on_policy || !o.redraw_conditions),
                      "GPS: bad options (conditions >= 1, samples_per_condition >= 2, steps >= 2, "
                      "positive kl_step, variance and learning rate, 0 < min_step_mult <= "
                      "max_step_mult, redraw_conditions only with sample_on_policy)");
}

void Gps::act(std::span<const double> observation, std::span<double> action) {
  RODLAB_THROW_UNLESS(static_cast<int>(observation.size()) == n_obs_ &&
                          static_cast<int>(action.size()) == m_,
                      "GPS: expected {} observations and {} actions", n_obs_, m_);
  policy_.infer(Eigen::Map<const Eigen::VectorXd>(observation.data(), n_obs_),
                Eigen::Map<Eigen::VectorXd>(action.data(), m_));
}

Gps::Sample Gps::rollout(TrajectoryEnvironment& env, std::uint64_t episode_seed,
                         const LinearGaussianController* p, std::uint64_t noise_seed) const {
  const int T = options_.steps;
  std::mt19937_64 rng(noise_seed);
  const Eigen::MatrixXd noise = smooth_noise(m_, T, options_.noise_smoothing, rng);
  Sample s;
  s.X.resize(n_, T);
  s.U.resize(m_, T);
  s.O.resize(n_obs_, T);
  s.cost.C.resize(T);
  s.cost.c.resize(T);
  s.cost.c0.resize(T);
  Eigen::VectorXd x(n_), a(m_), o(n_obs_), z(n_ + m_);
  env.reset(episode_seed, {o.data(), static_cast<std::size_t>(n_obs_)});
  env.state({x.data(), static_cast<std::size_t>(n_)});
  CostExpansion e;
  MlpWorkspace<double> ws;  // the policy's, per trajectory: rollouts run on several threads
  const Eigen::VectorXd policy_std = policy_variance_.cwiseSqrt();
  s.min_error = std::numeric_limits<double>::infinity();
  for (int t = 0; t < T; ++t) {
    if (p)
      a = p->K[t] * x + p->k[t] + p->cholesky[t] * noise.col(t);
    else
      a = policy_.forward(o, ws).col(0) + policy_std.cwiseProduct(noise.col(t));
    s.X.col(t) = x;
    s.U.col(t) = a;
    s.O.col(t) = o;
    // l(z) ~ l_i + g^T (z - z_i) + 1/2 (z - z_i)^T C (z - z_i), in absolute coordinates:
    // C, c = g - C z_i, c0 = l_i - g^T z_i + 1/2 z_i^T C z_i
    s.cost_sum += env.cost(x, a, t, &e);
    z << x, a;
    Eigen::MatrixXd& C = s.cost.C[t];
    C.resize(n_ + m_, n_ + m_);
    C.topLeftCorner(n_, n_) = e.lxx;
    C.topRightCorner(n_, m_) = e.lax.transpose();
    C.bottomLeftCorner(m_, n_) = e.lax;
    C.bottomRightCorner(m_, m_) = e.laa;
    Eigen::VectorXd g(n_ + m_);
    g << e.lx, e.la;
    s.cost.c[t] = g - C * z;
    s.cost.c0[t] = e.value - g.dot(z) + 0.5 * z.dot(C * z);
    const Transition tr = env.step({a.data(), static_cast<std::size_t>(m_)},
                                   {o.data(), static_cast<std::size_t>(n_obs_)});
    if (tr.failed) {
      s.failed = true;
      s.reason = tr.reason;
      return s;
    }
    s.return_sum += tr.reward;
    s.min_error = std::min(s.min_error, tr.error);
    s.final_error = tr.error;
    s.success = s.success || tr.success;
    env.state({x.data(), static_cast<std::size_t>(n_)});
  }
  return s;
}

std::vector<Gps::Sample> Gps::collect(std::span<TrajectoryEnvironment* const> envs,
                                      std::span<const std::uint64_t> seeds, int iteration) {
  const int M = static_cast<int>(seeds.size()), N = options_.samples_per_condition;
  const int count = M * N, J = static_cast<int>(envs.size());
  std::vector<Sample> samples(static_cast<std::size_t>(count));
  const auto lane = [&](int j) {  // trajectory q on environment q mod J, in order
    for (int q = j; q < count; q += J) {
      const int c = q / N;
      const std::uint64_t noise_seed =
          mix(options_.seed ^ mix(static_cast<std::uint64_t>(iteration) * 1000003ULL + q));
      samples[q] = rollout(*envs[j], seeds[c],
                           options_.sample_on_policy ? nullptr : &controllers_[c], noise_seed);
      samples[q].condition = c;
    }
  };
  if (J == 1) {
    lane(0);
    return samples;
  }
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(J));
  std::vector<std::thread> threads;
  for (int j = 0; j < J; ++j)
    threads.emplace_back([&, j] {
      try {
        lane(j);
      } catch (...) {
        errors[j] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  return samples;
}

LinearGaussianController Gps::linearise_policy(const std::vector<const Sample*>& samples,
                                               const Eigen::MatrixXd& J) {
  const int T = options_.steps, N = static_cast<int>(samples.size());
  LinearGaussianController p = LinearGaussianController::constant(
      T, n_, Eigen::VectorXd::Zero(m_), 1.0);
  Eigen::MatrixXd batch(n_obs_, N), seed(m_, N), dinput;
  MlpWorkspace<double> ws;
  for (int t = 0; t < T; ++t) {
    Eigen::VectorXd x_mean = Eigen::VectorXd::Zero(n_);
    for (int i = 0; i < N; ++i) {
      batch.col(i) = samples[i]->O.col(t);
      x_mean += samples[i]->X.col(t) / N;
    }
    const Eigen::MatrixXd mu = policy_.forward(batch, ws);
    Eigen::MatrixXd dmu_do(m_, n_obs_);  // the mean over the samples of d mu / d o
    for (int r = 0; r < m_; ++r) {
      seed.setZero();
      seed.row(r).setOnes();
      policy_.backward(ws, seed, nullptr, &dinput);
      dmu_do.row(r) = dinput.rowwise().mean().transpose();
    }
    p.K[t] = dmu_do * J;
    p.k[t] = mu.rowwise().mean() - p.K[t] * x_mean;
    p.set_covariance(t, policy_variance_.asDiagonal().toDenseMatrix());
  }
  return p;
}

double Gps::fit_policy(const std::vector<std::vector<const Sample*>>& by_condition,
                       const std::vector<LinearGaussianController>& controllers) {
  const int T = options_.steps;
  long count = 0;
  for (const auto& v : by_condition) count += static_cast<long>(v.size()) * T;
  if (count == 0) return 0.0;
  Eigen::MatrixXd X(n_obs_, count), Y(m_, count);
  std::vector<Eigen::MatrixXd> precision;
  std::vector<int> index;
  index.reserve(static_cast<std::size_t>(count));
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(m_);
  long col = 0;
  for (std::size_t c = 0; c < by_condition.size(); ++c) {
    if (by_condition[c].empty()) continue;
    const int first = static_cast<int>(precision.size());
    for (int t = 0; t < T; ++t) precision.push_back(controllers[c].precision[t]);
    for (const Sample* s : by_condition[c])
      for (int t = 0; t < T; ++t, ++col) {
        X.col(col) = s->O.col(t);
        Y.col(col) = controllers[c].K[t] * s->X.col(t) + controllers[c].k[t];
        index.push_back(first + t);
        diagonal += controllers[c].precision[t].diagonal();
      }
  }
  diagonal /= static_cast<double>(count);
  // the loss in units of the mean precision (Adam is nearly scale free; this keeps the
  // reported loss comparable between iterations)
  const double scale = diagonal.mean();
  for (auto& P : precision) P /= scale;
  RegressionOptions ro;
  ro.epochs = options_.policy_epochs;
  ro.batch_size = options_.batch_size;
  ro.seed = mix(options_.seed ^ mix(0x5157ULL + fits_++));
  const RegressionWeights w{precision, index};
  const RegressionResult r = fit_regression<double>(policy_, adam_, X, Y, ro, &w);
  policy_variance_ = diagonal.cwiseInverse();  // S_pi = diag(1 / mean diag S^-1)
  return r.epoch_loss.empty() ? 0.0 : r.epoch_loss.back();
}

namespace {

/// The mean of the samples' quadratic cost expansions, step by step (step 3).
QuadraticCost mean_cost(const std::vector<const Gps::Sample*>& samples);

}  // namespace

/// What a condition carries from one iteration to the next: the dual variable, the step
/// multiplier, and the previous fits for the step adjustment.
struct Gps::Condition {
  double eta = 1.0, step_mult = 1.0;
  std::optional<LinearGaussianDynamics> dynamics;
  QuadraticCost cost;
  LinearGaussianController policy;
};

void Gps::adjust_step(Condition& c, const LinearGaussianController& policy,
                      const std::vector<const Sample*>& samples) const {
  // the reference's "classic" rule: the improvement the previous step predicted (under the
  // previous fit) against the one the samples measured
  double actual_cost = 0.0;
  for (const Sample* s : samples) actual_cost += s->cost_sum / static_cast<double>(samples.size());
  const double prev_laplace = expected_cost(propagate(c.policy, *c.dynamics), c.cost);
  const double cur_laplace = expected_cost(propagate(policy, *c.dynamics), c.cost);
  const double predicted = prev_laplace - cur_laplace;
  const double actual = prev_laplace - actual_cost;
  // improvement ~ predicted/KL * KL + penalty KL^2 is best at KL' = pred / (2 (pred - act)) KL
  const double mult = std::clamp(predicted / (2.0 * std::max(1e-4, predicted - actual)), 0.1, 5.0);
  c.step_mult = std::clamp(mult * c.step_mult, options_.min_step_mult, options_.max_step_mult);
}

std::optional<KlStep> Gps::improve(Condition& c, const std::vector<const Sample*>& samples,
                                   const DynamicsFitter& fitter, const Eigen::MatrixXd& J) {
  if (samples.size() < 2) return std::nullopt;  // too few trajectories survived: keep it
  std::vector<Eigen::MatrixXd> X, U;
  for (const Sample* s : samples) {
    X.push_back(s->X);
    U.push_back(s->U);
  }
  LinearGaussianDynamics dynamics = fitter.fit(X, U);  // step 2
  QuadraticCost cost = mean_cost(samples);              // step 3
  LinearGaussianController policy = linearise_policy(samples, J);  // step 4
  if (c.dynamics && !options_.redraw_conditions) adjust_step(c, policy, samples);  // step 5
  KlStep step = kl_constrained_lqg(dynamics, cost, policy,  // step 6
                                   options_.kl_step * c.step_mult * options_.steps, c.eta,
                                   options_.kl);
  c.eta = step.eta;
  c.dynamics = std::move(dynamics);
  c.cost = std::move(cost);
  c.policy = std::move(policy);
  return step;
}

GpsLog Gps::train(std::span<TrajectoryEnvironment* const> envs,
                  std::span<const std::uint64_t> seeds, long samples,
                  const std::function<void(const GpsIteration&)>& progress) {
  RODLAB_THROW_UNLESS(!envs.empty() && !seeds.empty(),
                      "GPS: at least one environment and one condition");
  for (auto* env : envs)
    RODLAB_THROW_UNLESS(env->state_size() == n_ && env->observation_size() == n_obs_ &&
                            env->action_size() == m_,
                        "GPS: an environment of {} states, {} observations and {} actions for a "
                        "learner of {}, {} and {}",
                        env->state_size(), env->observation_size(), env->action_size(), n_,
                        n_obs_, m_);
  const int M = static_cast<int>(seeds.size()), T = options_.steps;
  const long per_iteration = static_cast<long>(M) * options_.samples_per_condition * T;
  RODLAB_THROW_UNLESS(samples >= per_iteration,
                      "GPS: {} samples do not make one iteration ({} conditions x {} trajectories "
                      "x {} steps = {})",
                      samples, M, options_.samples_per_condition, T, per_iteration);
  for (auto* env : envs) env->set_fixed_length(T);
  const Eigen::MatrixXd J = envs.front()->observation_jacobian();
  controllers_.assign(M, LinearGaussianController::constant(
                             T, n_, Eigen::VectorXd::Constant(m_, options_.initial_action),
                             options_.initial_variance));
  DynamicsFitter fitter(n_, m_, options_.dynamics);
  std::vector<Condition> state(static_cast<std::size_t>(M));

  GpsLog log;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::uint64_t> conditions(seeds.begin(), seeds.end());
  for (int itr = 0; log.samples + per_iteration <= samples; ++itr) {
    if (options_.redraw_conditions && itr > 0)
      for (int c = 0; c < M; ++c) conditions[c] = mix(seeds[c] ^ mix(0xC0DEULL + itr));
    const std::vector<Sample> all = collect(envs, conditions, itr);  // step 1
    log.samples += per_iteration;
    GpsIteration it = summarise(all);
    it.samples = log.samples;
    std::vector<std::vector<const Sample*>> by_condition(M);
    std::vector<Eigen::MatrixXd> Xs, Us;
    for (const Sample& s : all)
      if (!s.failed) {
        by_condition[s.condition].push_back(&s);
        Xs.push_back(s.X);
        Us.push_back(s.U);
      }
    if (!Xs.empty()) fitter.update_prior(Xs, Us);
    if (itr == 0) fit_policy(by_condition, controllers_);  // the policy catches up first
    int updated = 0;
    for (int c = 0; c < M; ++c) {
      const auto step = improve(state[c], by_condition[c], fitter, J);
      if (!step) continue;
      controllers_[c] = step->controller;
      it.mean_kl += step->kl / T;
      it.mean_step_mult += state[c].step_mult;
      ++updated;
    }
    if (updated > 0) {
      it.mean_kl /= updated;
      it.mean_step_mult /= updated;
    }
    it.policy_loss = fit_policy(by_condition, controllers_);  // step 7
    it.wall_time_s = seconds_since(start);
    log.iterations.push_back(it);
    if (progress) progress(it);
  }
  log.wall_time_s = seconds_since(start);
  return log;
}

GpsIteration Gps::summarise(const std::vector<Sample>& all) {
  GpsIteration it;
  it.trajectories = static_cast<int>(all.size());
  for (const Sample& s : all) {
    if (s.failed) {
      if (it.failed++ == 0) it.first_failure = s.reason;
      continue;
    }
    it.mean_cost += s.cost_sum;
    it.mean_return += s.return_sum;
    it.success_rate += s.success ? 1.0 : 0.0;
    it.mean_min_error += s.min_error;
    it.mean_final_error += s.final_error;
  }
  if (const int valid = it.trajectories - it.failed; valid > 0) {
    it.mean_cost /= valid;
    it.mean_return /= valid;
    it.success_rate /= valid;
    it.mean_min_error /= valid;
    it.mean_final_error /= valid;
  }
  return it;
}

namespace {

QuadraticCost mean_cost(const std::vector<const Gps::Sample*>& samples) {
  QuadraticCost cost = samples.front()->cost;
  const double n = static_cast<double>(samples.size());
  for (std::size_t t = 0; t < cost.C.size(); ++t) {
    for (std::size_t i = 1; i < samples.size(); ++i) {
      cost.C[t] += samples[i]->cost.C[t];
      cost.c[t] += samples[i]->cost.c[t];
      cost.c0[t] += samples[i]->cost.c0[t];
    }
    cost.C[t] /= n;
    cost.c[t] /= n;
    cost.c0[t] /= n;
  }
  return cost;
}

}  // namespace

}  // namespace rodlab::solvers::learning
