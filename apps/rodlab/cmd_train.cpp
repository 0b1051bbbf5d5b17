// rodlab train SCENE --algorithm ddpg|gps --task reach-one|reach-any|track --samples K: trains a
// policy on the scene's rod (interface spec "Control and learning", docs/learning.md).
#include <array>
#include <chrono>
#include <deque>
#include <fstream>
#include <iostream>
#include <memory>
#include <vector>

#include "rodlab/check.hpp"
#include "rodlab/io/atomic_file.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/io/text_table.hpp"
#include "rodlab/solvers/learning/ddpg.hpp"
#include "rodlab/solvers/learning/goal_pool.hpp"
#include "rodlab/solvers/learning/gps.hpp"
#include "rodlab/solvers/learning/policy.hpp"
#include "rodlab/solvers/learning/rod_environment.hpp"

#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "progress_line.hpp"

namespace rodlab::cli {
namespace {

namespace l = solvers::learning;

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};
constexpr std::array<std::string_view, 2> kAlgorithms{"ddpg", "gps"};
constexpr std::array<std::string_view, 3> kTasks{"reach-one", "reach-any", "track"};

constexpr OptionSpec kAlgorithmOption{"--algorithm", "ddpg|gps",
                                      "the learning algorithm; required"};
constexpr OptionSpec kTaskOption{"--task", "reach-one|reach-any|track", "the task; required"};
constexpr OptionSpec kSamplesOption{"--samples", "K",
                                    "environment steps to train on, integer >= 1; required"};
constexpr OptionSpec kSeedOption{"--seed", "S",
                                 "seed of every random draw, integer >= 0; default: 1"};
constexpr OptionSpec kJobsOption{"--jobs", "J",
                                 "environments stepping in parallel (one thread each), integer "
                                 ">= 1; default: 1"};
constexpr OptionSpec kDtControlOption{"--dt-control", "X",
                                      "control step [s] > 0; default: control.dt_control, else "
                                      "0.05 (the thesis')"};
constexpr OptionSpec kPolicyOutOption{
    "--out", "POLICY", "write the policy to POLICY (.json); default: policy.json"};

/// Episodes the progress line's success rate and return average over.
constexpr std::size_t kProgressWindow = 100;

struct TrainSettings {
  std::string algorithm, task;
  long samples = 0;
  int jobs = 1;
  std::uint64_t seed = 1;
  double dt_control = 0.05;
  std::filesystem::path out = "policy.json";
  bool quiet = false;  ///< --quiet: no progress line
};

TrainSettings read_settings(OptionReader& reader, const SolveOptions& o) {
  TrainSettings t;
  const auto algorithm = reader.choice(kAlgorithmOption.name, kAlgorithms);
  const auto task = reader.choice(kTaskOption.name, kTasks);
  const auto samples = reader.integer(kSamplesOption.name, 1);
  if (!reader.text(kAlgorithmOption.name)) reader.problem("--algorithm: required (ddpg or gps)");
  if (!reader.text(kTaskOption.name))
    reader.problem("--task: required (reach-one, reach-any or track)");
  if (!reader.text(kSamplesOption.name)) reader.problem("--samples: required (an integer >= 1)");
  if (const auto jobs = reader.integer(kJobsOption.name, 1)) t.jobs = *jobs;
  if (const auto seed = reader.integer(kSeedOption.name, 0)) t.seed = static_cast<std::uint64_t>(*seed);
  if (const auto dt = reader.positive(kDtControlOption.name)) t.dt_control = *dt;
  if (o.out) {
    if (o.out->extension() != ".json")
      reader.problem("--out: a policy file is JSON (.json) (got " + o.out->string() + ")");
    t.out = *o.out;
  }
  t.algorithm = algorithm.value_or("");
  t.task = task.value_or("");
  t.samples = samples.value_or(0);
  t.quiet = o.quiet;
  return t;
}

/// The progress line (progress_line.hpp): samples, episodes, the last episodes' mean return and
/// success rate, and the sample rate.
class Progress {
 public:
  Progress(long samples, bool quiet) : samples_(samples), line_("train", "samples", !quiet) {}
  void operator()(const l::DdpgEpisode& e) {
    window_.push_back(e);
    if (window_.size() > kProgressWindow) window_.pop_front();
    ++episodes_;
    if (!line_.active()) return;
    double returns = 0.0;
    for (const auto& w : window_) returns += w.return_sum;
    const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
    line_.update(e.samples, samples_,
                 rodlab::format("episodes {}, mean return {:.4g}, success {:.3g} % (last {}), "
                                "{:.4g} samples/s",
                                episodes_, returns / window_.size(), 100.0 * success_rate(),
                                window_.size(), e.samples / std::max(seconds, 1e-9)));
  }
  /// The success rate over the last episodes.
  double success_rate() const {
    double s = 0.0;
    for (const auto& w : window_) s += w.success ? 1.0 : 0.0;
    return window_.empty() ? 0.0 : s / window_.size();
  }

 private:
  using Clock = std::chrono::steady_clock;
  long samples_, episodes_ = 0;
  Clock::time_point start_ = Clock::now();
  std::deque<l::DdpgEpisode> window_;
  ProgressLine line_;
};

/// The scene's learning section over the solvers' defaults (each absent field keeps it).
void apply_learning(const scene::Learning& s, l::EnvironmentOptions& e, l::GoalPoolOptions& g,
                    l::DdpgOptions& d, l::GpsOptions& p) {
  const auto set = [](auto& to, const auto& from) {
    if (from) to = *from;
  };
  set(e.beta, s.beta);
  set(e.max_steps, s.max_steps);
  set(e.state_nodes, s.state_nodes);
  set(e.track_duration, s.track_duration);
  set(e.track_end_speed, s.track_end_speed);
  set(g.dynamic_holds, s.dynamic_holds);
  set(g.static_points, s.static_points);
  const scene::LearningDdpg& q = s.ddpg;
  set(d.actor_hidden, q.actor_hidden);
  set(d.critic_hidden, q.critic_hidden);
  if (q.activation) d.hidden = l::parse_activation(*q.activation);
  set(d.actor_learning_rate, q.actor_learning_rate);
  set(d.critic_learning_rate, q.critic_learning_rate);
  set(d.gamma, q.gamma);
  set(d.tau, q.tau);
  set(d.batch_size, q.batch_size);
  set(d.buffer_capacity, q.buffer_capacity);
  set(d.warmup, q.warmup);
  set(d.updates_per_step, q.updates_per_step);
  set(d.noise_theta, q.noise_theta);
  set(d.noise_sigma, q.noise_sigma);
  set(d.final_layer_scale, q.final_layer_scale);
  if (q.precision) d.precision = l::parse_precision(*q.precision);
  const scene::LearningGps& r = s.gps;
  set(p.conditions, r.conditions);
  set(p.samples_per_condition, r.samples_per_condition);
  set(p.steps, r.steps);
  set(p.policy_hidden, r.policy_hidden);
  if (r.activation) p.hidden = l::parse_activation(*r.activation);
  set(p.policy_learning_rate, r.policy_learning_rate);
  set(p.policy_epochs, r.policy_epochs);
  set(p.batch_size, r.batch_size);
  set(p.kl_step, r.kl_step);
  set(p.min_step_mult, r.min_step_mult);
  set(p.max_step_mult, r.max_step_mult);
  set(p.kl.entropy, r.entropy);
  set(p.sample_on_policy, r.sample_on_policy);
  set(p.redraw_conditions, r.redraw_conditions);
  set(p.initial_action, r.initial_action);
  set(p.initial_variance, r.initial_variance);
  set(p.noise_smoothing, r.noise_smoothing);
  set(p.dynamics.prior.max_clusters, r.prior_clusters);
  set(p.dynamics.prior_trajectories, r.prior_trajectories);
  set(e.cost.alpha, r.cost_alpha);
  set(e.cost.quadratic, r.cost_quadratic);
  set(e.cost.velocity, r.cost_velocity);
  set(e.cost.action, r.cost_action);
  set(e.cost.bound, r.cost_bound);
  set(e.cost.running, r.cost_running);
  set(e.cost.final, r.cost_final);
  set(e.cost.log, r.cost_log);
}

/// What a training run gives the policy file and the summary, whichever the algorithm.
struct Trained {
  l::Mlp<double> network{l::MlpConfig{{1, 1}}};
  long samples = 0, episodes = 0;
  double wall_time_s = 0.0, success_rate = 0.0;
  int failed = 0;
  std::string first_failure;
  std::string detail;  ///< an algorithm's own line (GPS: iterations, conditions)
};

Trained train_ddpg(std::span<l::LearningEnvironment* const> lanes, const l::DdpgOptions& d,
                   const TrainSettings& t) {
  const l::LearningEnvironment& env = *lanes.front();
  l::Ddpg ddpg(env.observation_size(), env.action_size(), d);
  Progress progress(t.samples, t.quiet);
  const l::DdpgLog log = ddpg.train(lanes, t.samples, std::ref(progress));
  Trained r;
  r.network = ddpg.actor();
  r.samples = log.samples;
  r.episodes = static_cast<long>(log.episodes.size());
  r.wall_time_s = log.wall_time_s;
  r.success_rate = progress.success_rate();
  for (const auto& e : log.episodes)
    if (e.failed && r.failed++ == 0) r.first_failure = e.reason;
  r.detail = "success over the last " + std::to_string(std::min(kProgressWindow, log.episodes.size())) +
             " episodes";
  return r;
}

/// The GPS progress line's text, after every iteration.
std::string gps_progress(const l::GpsIteration& it, double length) {
  return rodlab::format("trajectories {} ({} failed), mean return {:.4g}, mean cost {:.4g}, "
                        "success {:.3g} %, best error {:.3g} % L, KL/step {:.3g}, {:.4g} samples/s",
                        it.trajectories, it.failed, it.mean_return, it.mean_cost,
                        100.0 * it.success_rate, 100.0 * it.mean_min_error / length, it.mean_kl,
                        it.samples / std::max(it.wall_time_s, 1e-9));
}

Trained train_gps(std::span<l::RodEnvironment* const> envs, const l::GpsOptions& o,
                  const TrainSettings& t) {
  std::vector<l::TrajectoryEnvironment*> lanes(envs.begin(), envs.end());
  const l::RodEnvironment& env = *envs.front();
  std::vector<std::uint64_t> seeds;
  for (int c = 0; c < o.conditions; ++c) seeds.push_back(t.seed * 1000003ULL + c);
  l::Gps gps(env.state_size(), env.observation_size(), env.action_size(), o);
  const double L = env.length();
  ProgressLine line("train", "samples", !t.quiet);
  const l::GpsLog log = gps.train(lanes, seeds, t.samples, [&](const l::GpsIteration& it) {
    if (line.active()) line.update(it.samples, t.samples, gps_progress(it, L));
  });
  line.finish();
  Trained r;
  r.network = gps.policy();
  r.samples = log.samples;
  r.wall_time_s = log.wall_time_s;
  for (const auto& it : log.iterations) {
    r.episodes += it.trajectories;
    r.failed += it.failed;
    if (r.first_failure.empty()) r.first_failure = it.first_failure;
  }
  if (!log.iterations.empty()) r.success_rate = log.iterations.back().success_rate;
  r.detail = rodlab::format("success of the last iteration's {} trajectories ({} iterations of "
                            "{} conditions x {} trajectories x {} steps)",
                            log.iterations.empty() ? 0 : log.iterations.back().trajectories,
                            log.iterations.size(), o.conditions, o.samples_per_condition,
                            o.steps);
  return r;
}

/// GPS's task-dependent settings: one condition for reach-one's one target; for track, a
/// path's steps and fewer conditions (unless the scene sets them). Throws UsageError when the
/// budget does not hold one iteration.
void apply_gps_task(const scene::Scene& scene, const l::EnvironmentOptions& eo, long samples,
                    l::GpsOptions& g) {
  if (eo.task == l::LearningTask::reach_one) g.conditions = 1;
  if (eo.task == l::LearningTask::track) {
    const scene::LearningGps none;
    const scene::LearningGps& set = scene.learning ? scene.learning->gps : none;
    if (!set.steps)
      g.steps = static_cast<int>(std::ceil(eo.track_duration / eo.plant.dt_control - 1e-9));
    if (!set.conditions) g.conditions = l::kGpsTrackConditions;
  }
  const long iteration = static_cast<long>(g.conditions) * g.samples_per_condition * g.steps;
  if (samples < iteration)
    throw UsageError(rodlab::format(
        "--samples: GPS needs at least one iteration, {} conditions x {} trajectories x {} steps "
        "= {} samples (got {})",
        g.conditions, g.samples_per_condition, g.steps, iteration, samples));
}

/// The table printed after training.
void print_summary(const TrainSettings& t, const l::Policy& p, const l::GoalPool& pool,
                   l::LearningTask task, const Trained& trained) {
  io::TextTable table;
  table.add_row({"trained", t.algorithm + " on " + t.task + ", " + p.scheme + " N = " +
                                std::to_string(p.nodes) + ", dt_control " +
                                io::format_number(p.dt_control) + " s, seed " +
                                std::to_string(t.seed) + ", " + std::to_string(t.jobs) +
                                " environment(s) in parallel"});
  if (task == l::LearningTask::reach_one) {
    const auto& g = pool.points.front();
    table.add_row({"target", rodlab::format("[{:g}, {:g}, {:g}] m, {:g} mm from the closest "
                                            "quasi-static tip",
                                            g[0], g[1], g[2], 1e3 * pool.beyond_static)});
  } else {
    table.add_row({"goals", std::to_string(pool.points.size()) + " candidate points"});
  }
  table.add_row({"samples", std::to_string(trained.samples) + " in " +
                                std::to_string(trained.episodes) + " episodes (" +
                                std::to_string(trained.failed) + " ended by a failed step)"});
  if (trained.failed > 0) table.add_row({"first failure", trained.first_failure});
  table.add_row({"success", io::format_number(100.0 * trained.success_rate) + " %, " +
                                trained.detail});
  table.add_row({"wall time",
                 io::format_number(trained.wall_time_s) + " s (" +
                     io::format_number(trained.samples / std::max(trained.wall_time_s, 1e-9)) +
                     " samples/s)"});
  std::cout << table.render() << "policy written to " << t.out.string() << '\n';
}

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const SolveOptions options = read_solve_options(reader, solvers::Problem::dynamics, "train");
  TrainSettings t = read_settings(reader, options);
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  if (!inv.args.has(kDtControlOption.name) && scene.control) t.dt_control = scene.control->dt_control;

  l::EnvironmentOptions eo;
  eo.plant.solver = resolve_plant_solver(options, scene, "train");
  eo.plant.solver.max_iterations =
      std::max(eo.plant.solver.max_iterations, solvers::control::PlantOptions::kShotsPerStep);
  eo.plant.dt_control = t.dt_control;
  eo.task = l::task_from_name(t.task);
  if (scene.control) eo.threshold = scene.control->threshold;
  l::GoalPoolOptions gp;
  gp.seed = t.seed;
  l::DdpgOptions d;
  d.seed = t.seed;
  l::GpsOptions g;
  g.seed = t.seed;
  const bool gps = t.algorithm == "gps";
  if (scene.learning) apply_learning(*scene.learning, eo, gp, d, g);
  if (gps) apply_gps_task(scene, eo, t.samples, g);

  const l::GoalPool pool = l::make_goal_pool(scene, eo, gp);
  std::vector<std::unique_ptr<l::RodEnvironment>> envs;
  for (int j = 0; j < t.jobs; ++j) envs.push_back(std::make_unique<l::RodEnvironment>(scene, eo, pool));
  const l::RodEnvironment& env = *envs.front();

  Trained trained;
  if (gps) {
    std::vector<l::RodEnvironment*> lanes;
    for (auto& e : envs) lanes.push_back(e.get());
    trained = train_gps(lanes, g, t);
  } else {
    std::vector<l::LearningEnvironment*> lanes;
    for (auto& e : envs) lanes.push_back(e.get());
    trained = train_ddpg(lanes, d, t);
  }

  l::Policy p;
  p.algorithm = t.algorithm;
  p.task = t.task;
  p.scene = scene.name;
  p.scheme = eo.plant.solver.scheme;
  p.nodes = eo.plant.solver.nodes;
  p.dt_control = eo.plant.dt_control;
  p.layout = {.goal_velocity = eo.task == l::LearningTask::track, .state_nodes = eo.state_nodes};
  p.length = env.length();
  p.period = env.period();
  p.lower = env.plant().lower();
  p.upper = env.plant().upper();
  p.training = {trained.samples, trained.episodes, t.seed, trained.wall_time_s,
                env.episode_steps()};
  if (eo.task == l::LearningTask::reach_one) p.goal = pool.points.front();
  p.network = trained.network;
  io::write_file_atomically(t.out, l::to_json(p));

  print_summary(t, p, pool, eo.task, trained);
  return kSolved;
}

}  // namespace

const Command& train_command() {
  static const std::array<OptionSpec, 14> options{
      kAlgorithmOption, kTaskOption,  kSamplesOption,   kSeedOption, kJobsOption,
      kDtControlOption, kSchemeOption, kNodesOption,    kTolOption,  kGridOption,
      kPolicyOutOption, kSetOption,   kMaxWallTimeOption, kQuietOption};
  static const Command command{
      "train",
      "SCENE --algorithm ddpg|gps --task reach-one|reach-any|track --samples K [options]",
      "train a control policy by reinforcement learning (DDPG or GPS) on the scene's rod",
      "Trains a policy (docs/learning.md) on the scene's rod: the plant of `rodlab control`\n"
      "(--scheme, else dynamics.scheme, else implicit-midpoint; --nodes; --dt-control), the\n"
      "task's goals drawn with --seed (reach-one: one point of the dynamic workspace outside\n"
      "the static one; reach-any: any point of the dynamic workspace; track: random paths\n"
      "through the static workspace), the reward (4.40) with beta = 0.3. DDPG: deep\n"
      "deterministic policy gradient; GPS: mirror-descent guided policy search (local\n"
      "linear-Gaussian controllers, fitted dynamics, a supervised policy). Prints a progress\n"
      "line (every 10 s for DDPG, every iteration for GPS) and writes the policy\n"
      "(rodlab.policy/1, JSON) atomically;\n"
      "`rodlab control SCENE --controller policy --policy POLICY` runs it.\n"
      "\n"
      "Exit status: 0 trained (the policy is written); 2 bad input or usage (nothing is\n"
      "written).\n",
      kPositionals,
      options,
      &run};
  return command;
}

}  // namespace rodlab::cli
