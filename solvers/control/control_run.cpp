#include "rodlab/solvers/control/control_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>

#include "rodlab/check.hpp"
#include "rodlab/scene/trajectory.hpp"
#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/control/dynamic_targets.hpp"
#include "rodlab/solvers/control/ilqr.hpp"
#include "rodlab/solvers/control/inverse_statics.hpp"
#include "rodlab/solvers/control/lqr_hold.hpp"
#include "rodlab/solvers/control/nlsq_mpc.hpp"
#include "rodlab/solvers/control/plant.hpp"
#include "rodlab/solvers/control/plant_ilqr.hpp"
#include "rodlab/solvers/control/static_targets.hpp"
#include "rodlab/solvers/learning/action_map.hpp"
#include "rodlab/solvers/learning/observer.hpp"

namespace rodlab::solvers::control {
namespace {

using Clock = std::chrono::steady_clock;
/// At least this many holds in a dynamic-workspace run for targets.
constexpr int kDynamicHolds = 10;
using result::ControlEpisode;
using result::ControlResult;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

const char* task_name(scene::ControlTask t) {
  switch (t) {
    case scene::ControlTask::reach: return "reach";
    case scene::ControlTask::hold: return "hold";
    case scene::ControlTask::track: return "track";
  }
  return "?";
}

/// The inverse statics of the quasi-static controller and of LQR's equilibria: reached within
/// the success threshold, on the plant's number of nodes.
InverseStaticsOptions inverse_statics_options(const scene::Control& c, const scene::Scene& scene,
                                              int nodes) {
  InverseStaticsOptions io;
  io.tolerance = c.threshold * scene.rod.length;
  io.statics.nodes = nodes;
  return io;
}

/// The control steps of a track episode: the trajectory's duration in steps of dt_control.
int track_steps(const scene::Control& c) {
  return std::max(1, static_cast<int>(std::ceil(scene::duration(*c.trajectory) / c.dt_control -
                                                1e-9)));
}

/// `count` targets from the dynamic workspace (dynamic_targets.hpp, thesis 3.4.1) on the plant's
/// scheme, none within the success threshold of the rest tip.
std::vector<Vector3> dynamic_targets(const scene::Scene& scene, const ControlRunOptions& o) {
  const scene::Control& c = o.control;
  DynamicTargetOptions d;
  d.solver = o.solver;
  d.dt_control = c.dt_control;
  d.holds = std::max(kDynamicHolds, c.target_count);
  d.exclude_radius = c.threshold * scene.rod.length;
  d.seed = c.seed;
  return draw_dynamic_targets(scene, d, c.target_count);
}

/// The targets of reach and hold: listed, else drawn: from the dynamic workspace for a dynamic
/// controller's reach (the thesis' dynamic reach), from the static workspace otherwise.
void choose_targets(const scene::Scene& scene, const ControlRunOptions& o, ControlResult& out) {
  const scene::Control& c = o.control;
  out.seed = c.seed;
  if (!c.targets.empty()) {
    out.targets.drawn_from = result::TargetSource::scene;
    out.targets.points = c.targets;
    return;
  }
  if (c.task == scene::ControlTask::reach && o.policy && o.policy->goal) {
    out.targets.drawn_from = result::TargetSource::policy;
    out.targets.points = {*o.policy->goal};
    return;
  }
  if (c.task == scene::ControlTask::reach && o.controller != "quasi-static") {
    out.targets.drawn_from = result::TargetSource::dynamic_workspace;
    out.targets.points = dynamic_targets(scene, o);
    return;
  }
  const StaticTargets drawn =
      sample_static_targets(scene, InverseStaticsOptions{}.statics, c.target_count, c.seed);
  out.targets.drawn_from = result::TargetSource::static_workspace;
  out.targets.points = drawn.tips;
}

/// One row of the series.
void record(ControlResult& out, int episode, double t, const Eigen::VectorXd& u,
            const Vector3& tip, const Vector3& target, double solve_time, int iterations) {
  auto& s = out.series;
  s.t.push_back(t);
  s.u.push_back(u);
  s.tip.push_back(tip);
  s.target.push_back(target);
  s.error.push_back((tip - target).norm());
  s.solve_time_s.push_back(solve_time);
  s.iterations.push_back(iterations);
  s.episode.push_back(episode);
}

/// The episode's error statistics over its rows.
void close_episode(ControlResult& out, ControlEpisode& e, std::size_t first_row) {
  const auto& err = out.series.error;
  e.steps = static_cast<int>(err.size() - first_row);
  if (e.steps == 0) return;
  e.final_error = err.back();
  e.min_error = *std::min_element(err.begin() + static_cast<long>(first_row), err.end());
  double sum = 0.0;
  for (std::size_t i = first_row; i < err.size(); ++i) sum += err[i];
  e.mean_error = sum / e.steps;
}

/// The episode a stopped run (--max-wall-time) was in: its rows are recorded, the episode was
/// not; closed here as unsuccessful, so that every series.episode index names an episode.
void close_interrupted_episode(ControlResult& out, const std::string& why) {
  const auto& index = out.series.episode;
  if (index.empty() || index.back() < static_cast<int>(out.episodes.size())) return;
  std::size_t first = index.size();
  while (first > 0 && index[first - 1] == index.back()) --first;
  ControlEpisode e;
  e.target = out.series.target[first];
  e.reason = why;
  close_episode(out, e, first);
  out.episodes.push_back(e);
}

/// One control decision of a controller of the dynamic plant.
struct Decision {
  std::string failure;  ///< empty: u is the input to apply
  Eigen::VectorXd u;
  int iterations = 0;
};

/// A controller of the dynamic plant (run_dynamic): nlsq-mpc, lqr.
class DynamicController {
 public:
  virtual ~DynamicController() = default;
  /// A new episode from the plant's initial state towards `target` (reach, hold; the
  /// trajectory's start for track); a non-empty return is why the episode cannot start.
  virtual std::string start(const Plant& plant, const Vector3& target) = 0;
  /// The input of the coming control step; `horizon` holds the targets at its end and after.
  virtual Decision decide(Plant& plant, std::span<const Vector3> horizon) = 0;
};

class MpcController final : public DynamicController {
 public:
  MpcController(const Plant& plant, const scene::Control& c) : mpc_(plant, options(c)) {}
  std::string start(const Plant& plant, const Vector3&) override {
    mpc_.reset(plant);
    return {};
  }
  Decision decide(Plant& plant, std::span<const Vector3> horizon) override {
    const MpcPlan plan = mpc_.plan(plant, horizon);
    return {plan.ok ? std::string() : plan.reason, plan.u, plan.iterations};
  }

 private:
  static MpcOptions options(const scene::Control& c) {
    MpcOptions mo;
    mo.horizon = c.horizon;
    mo.input_rate_weight = c.weights.input_rate;
    mo.input_weight = c.weights.input;
    mo.terminal_weight = c.weights.terminal;
    mo.max_iterations = c.iterations.value_or(mo.max_iterations);
    return mo;
  }
  NlsqMpc mpc_;
};

/// iLQR (ilqr.hpp) over the horizon with the plant as its model (plant_ilqr.hpp), warm-started
/// from the last plan shifted by a step; the first input is applied.
class IlqrController final : public DynamicController {
 public:
  IlqrController(Plant& plant, const scene::Control& c)
      : model_(plant, c.horizon, c.weights.input, c.weights.terminal), plan_(c.horizon) {
    options_.max_iterations = c.iterations.value_or(kIterationsPerStep);
    options_.tolerance = 1e-6;
  }
  std::string start(const Plant& plant, const Vector3&) override {
    std::fill(plan_.begin(), plan_.end(), plant.input());
    return {};
  }
  Decision decide(Plant&, std::span<const Vector3> horizon) override {
    if (plan_.size() > 1) {  // shifted by a step, the last input repeated
      std::rotate(plan_.begin(), plan_.begin() + 1, plan_.end());
      plan_.back() = plan_[plan_.size() - 2];
    }
    model_.start(horizon);
    const IlqrResult r = solve_ilqr(model_, plan_, options_);
    model_.reset();  // the plant back where it stands
    if (!r.ok) return {r.reason, {}, r.iterations};
    plan_ = r.u;
    return {{}, plan_.front(), r.iterations};
  }

 private:
  /// control.iterations' default: converged plans (1: the real-time iteration, docs/control.md)
  static constexpr int kIterationsPerStep = 10;
  PlantIlqrModel model_;
  std::vector<Eigen::VectorXd> plan_;
  IlqrOptions options_;
};

/// Infinite-horizon LQR about the equilibrium of the inverse statics' inputs for the target
/// (lqr_hold.hpp); the gain is designed at the episode's start. Tracking: the reference follows
/// the quasi-static equilibria of the coming targets (one inverse-statics solve per control
/// step, from the last inputs) with that gain.
class LqrController final : public DynamicController {
 public:
  LqrController(const scene::Scene& scene, const PlantOptions& po, const scene::Control& c)
      : scene_(scene), po_(po), statics_(scene, inverse_statics_options(c, scene, po.solver.nodes)),
        track_(c.task == scene::ControlTask::track) {
    weights_.input = std::max(c.weights.input, LqrWeights{}.input);
  }
  std::string start(const Plant&, const Vector3& target) override {
    const InverseStaticsResult equilibrium = statics_.solve(target);
    if (!equilibrium.converged || !equilibrium.reached) return equilibrium.reason;
    gain_ = hold_gain(scene_, po_, equilibrium.u, weights_);
    return gain_.ok ? std::string() : gain_.reason;
  }
  Decision decide(Plant& plant, std::span<const Vector3> horizon) override {
    if (!track_) return {{}, gain_.control(plant), 1};
    // the closest feasible equilibrium if the target is out of reach (its inputs still apply)
    const InverseStaticsResult reference = statics_.solve(horizon.front());
    if (!reference.converged) return {reference.reason, {}, reference.updates};
    return {{}, gain_.control(plant, reference.u), reference.updates};
  }

 private:
  const scene::Scene& scene_;
  PlantOptions po_;
  InverseStatics statics_;
  bool track_;
  LqrWeights weights_;
  HoldGain gain_;
};

/// A trained policy (learning/policy.hpp): one network evaluation per control step on the
/// observation of learning/observer.hpp, the goal's velocity from the horizon's first two targets.
class PolicyController final : public DynamicController {
 public:
  PolicyController(const Plant& plant, const learning::Policy& p, int nodes)
      : network_(p.network), lower_(p.lower), upper_(p.upper),
        observer_(plant, nodes, p.layout) {
    const auto near = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); };
    RODLAB_THROW_UNLESS(p.nodes == nodes, "policy: trained at N = {}, the plant has N = {} "
                        "(--nodes {})", p.nodes, nodes, p.nodes);
    RODLAB_THROW_UNLESS(near(p.dt_control, plant.dt_control()),
                        "policy: trained at dt_control = {:g} s, the plant steps {:g} s "
                        "(--dt-control {:g})",
                        p.dt_control, plant.dt_control(), p.dt_control);
    RODLAB_THROW_UNLESS(p.lower.size() == plant.input_count() &&
                            p.lower == plant.lower() && p.upper == plant.upper(),
                        "policy: trained for {} inputs with other limits than the scene's {}",
                        p.lower.size(), plant.input_count());
    RODLAB_THROW_UNLESS(near(p.length, plant.length()) && near(p.period, observer_.period()) &&
                            network_.input_size() == observer_.size(),
                        "policy: trained on a rod with L = {:g} m and T = {:g} s ({} observations), "
                        "the scene's has L = {:g} m and T = {:g} s ({})",
                        p.length, p.period, network_.input_size(), plant.length(),
                        observer_.period(), observer_.size());
    o_.resize(observer_.size());
    a_.resize(network_.output_size());
  }
  std::string start(const Plant&, const Vector3&) override {
    tip_before_.reset();
    return {};
  }
  Decision decide(Plant& plant, std::span<const Vector3> horizon) override {
    const Vector3 velocity = horizon.size() > 1
                                 ? Vector3((horizon[1] - horizon[0]) / plant.dt_control())
                                 : Vector3::Zero();
    observer_.observe(plant, tip_before_, horizon.front(), velocity,
                      std::span<double>(o_.data(), o_.size()));
    network_.infer(o_, a_);
    Decision d{{}, {}, 1};
    learning::input_of_action(std::span<const double>(a_.data(), a_.size()), lower_, upper_, d.u);
    tip_before_ = plant.tip();
    return d;
  }

 private:
  learning::Mlp<double> network_;
  Eigen::VectorXd lower_, upper_, o_, a_;
  learning::Observer observer_;
  std::optional<Vector3> tip_before_;
};

/// A solver failure ends its episode (the reason in it) and marks the run: not converged, the
/// first failure's reason. The next episode starts from the initial state again.
void fail(ControlResult& out, ControlEpisode& episode, const std::string& why) {
  out.converged = false;
  if (!out.reason) out.reason = why;
  episode.reason = why;
}

/// A controller on the dynamic plant: every episode from the plant's initial state.
void run_dynamic(const scene::Scene& scene, const ControlRunOptions& o, ControlResult& out) {
  const scene::Control& c = o.control;
  PlantOptions po;
  po.solver = o.solver;
  po.solver.max_iterations = std::max(o.solver.max_iterations, PlantOptions::kShotsPerStep);
  po.dt_control = c.dt_control;
  Plant plant(scene, po);
  const PlantSnapshot initial = plant.snapshot();
  // The controller's model: the plant itself, or a plant of control.model_scheme that takes
  // over the plant's state before every decision (one scheme step per control step).
  PlantOptions mo = po;
  std::optional<Plant> own_model;
  if (c.model_scheme && *c.model_scheme != po.solver.scheme) {
    RODLAB_THROW_UNLESS(std::ranges::find(scene::kModelSchemes, *c.model_scheme) !=
                            std::end(scene::kModelSchemes),
                        "control.model_scheme: '{}' cannot take over another scheme's state (its "
                        "tangent coordinates are not its whole state); use implicit-midpoint, "
                        "implicit-midpoint-collocation or variational",
                        *c.model_scheme);
    mo.solver.scheme = *c.model_scheme;
    mo.solver.dt = 0.0;
    own_model.emplace(scene, mo);
  }
  Plant& model = own_model ? *own_model : plant;
  std::unique_ptr<DynamicController> controller;
  if (o.controller == "policy") {
    RODLAB_THROW_UNLESS(o.policy.has_value(), "--controller policy needs a policy (--policy FILE)");
    controller = std::make_unique<PolicyController>(model, *o.policy, mo.solver.nodes);
  } else if (o.controller == "lqr")
    controller = std::make_unique<LqrController>(scene, mo, c);
  else if (o.controller == "ilqr")
    controller = std::make_unique<IlqrController>(model, c);
  else
    controller = std::make_unique<MpcController>(model, c);
  const double L = plant.length(), threshold = c.threshold * L, dt = c.dt_control;
  const bool track = c.task == scene::ControlTask::track;
  const int episodes = track ? 1 : static_cast<int>(out.targets.points.size());
  const int steps = track ? track_steps(c) : c.max_steps;
  // a policy observes the goal's velocity from the first two targets
  std::vector<Vector3> horizon(std::max(o.controller == "policy" ? 2 : 1, c.horizon));
  for (int e = 0; e < episodes; ++e) {
    plant.restore(initial);
    auto target_at = [&](double t) {
      return track ? scene::position(*c.trajectory, t) : out.targets.points[e];
    };
    ControlEpisode episode;
    episode.target = target_at(0.0);
    const std::size_t first = out.series.t.size();
    int below = 0;
    bool reached = false;
    if (o.on_state) o.on_state(e, 0.0, plant.stepper());  // (not in the controller's time)
    auto t0 = Clock::now();  // the episode's set-up counts in its first step
    if (own_model) own_model->set_state_of(plant);
    if (std::string why = controller->start(model, episode.target); !why.empty()) {
      episode.reason = why;
      out.episodes.push_back(episode);
      continue;
    }
    for (int k = 0; k < steps; ++k) {
      const double t = (k + 1) * dt;  // the step ends at t
      for (std::size_t i = 0; i < horizon.size(); ++i) horizon[i] = target_at(t + i * dt);
      if (k > 0) t0 = Clock::now();
      if (own_model && k > 0) own_model->set_state_of(plant);
      const Decision d = controller->decide(model, horizon);
      const double solve_time = seconds_since(t0);
      if (!d.failure.empty()) {
        fail(out, episode, d.failure);
        break;
      }
      plant.set_input(d.u);
      const dynamics::StepStatus status = plant.advance();
      if (!status.ok) {
        fail(out, episode, "the plant's step failed: " + status.reason);
        break;
      }
      record(out, e, t, d.u, plant.tip(), target_at(t), solve_time, d.iterations);
      if (o.on_state) o.on_state(e, t, plant.stepper());
      const double error = out.series.error.back();
      below = error < threshold ? below + 1 : 0;
      reached = reached || below > 0;
      if (c.task == scene::ControlTask::reach && below > 0 && c.stop_at_success) break;
      if (c.task == scene::ControlTask::hold && below >= c.hold_steps) break;
    }
    close_episode(out, episode, first);
    episode.success = track ? episode.steps == steps && episode.mean_error < threshold
                            : (c.task == scene::ControlTask::reach ? reached : below >= c.hold_steps);
    out.episodes.push_back(episode);
  }
}

/// quasi-static: inverse statics per target (reach, hold) or per control step (track).
void run_quasi_static(const scene::Scene& scene, const ControlRunOptions& o, ControlResult& out) {
  const scene::Control& c = o.control;
  InverseStatics solver(scene, inverse_statics_options(c, scene, o.solver.nodes));
  const bool track = c.task == scene::ControlTask::track;
  const int episodes = track ? 1 : static_cast<int>(out.targets.points.size());
  const int steps = track ? track_steps(c) : 1;
  for (int e = 0; e < episodes; ++e) {
    ControlEpisode episode;
    const std::size_t first = out.series.t.size();
    for (int k = 0; k < steps; ++k) {
      const double t = track ? (k + 1) * c.dt_control : 0.0;
      const Vector3 target = track ? scene::position(*c.trajectory, t) : out.targets.points[e];
      if (k == 0) episode.target = target;
      const InverseStaticsResult r = solver.solve(target);
      record(out, e, t, r.u, r.tip, target, r.wall_time_s, r.updates);
      if (!r.reached && !track) episode.reason = r.reason;
      if (!r.converged) {
        out.converged = false;
        out.reason = episode.reason = r.reason;
        break;
      }
    }
    close_episode(out, episode, first);
    if (!track) episode.steps = out.series.iterations.back();  // updates, as the spec counts
    const double threshold = c.threshold * scene.rod.length;
    episode.success = track ? episode.mean_error < threshold : episode.final_error < threshold;
    out.episodes.push_back(episode);
    if (!out.converged) break;
  }
}

void summarise(const ControlResult& in, double L, double dt_control, result::ControlSummary& s) {
  int successes = 0;
  for (const auto& e : in.episodes) successes += e.success ? 1 : 0;
  s.success_rate = in.episodes.empty() ? 0.0 : static_cast<double>(successes) / in.episodes.size();
  const auto& err = in.series.error;
  double sum = 0.0, ratio_sum = 0.0, ratio_max = 0.0;
  for (double v : err) sum += v;
  for (double t : in.series.solve_time_s) {
    ratio_sum += t / dt_control;
    ratio_max = std::max(ratio_max, t / dt_control);
  }
  const double n = std::max<std::size_t>(1, err.size());
  s.mean_error_pct_L = 100.0 * sum / n / L;
  s.real_time_ratio_mean = ratio_sum / n;
  s.real_time_ratio_max = ratio_max;
}

}  // namespace

result::ControlResult run_control(const scene::Scene& scene, const ControlRunOptions& options) {
  const scene::Control& c = options.control;
  const bool mpc = options.controller == "nlsq-mpc";
  const bool dynamic = mpc || options.controller == "lqr" || options.controller == "ilqr" ||
                       options.controller == "policy";
  RODLAB_THROW_UNLESS(dynamic || options.controller == "quasi-static",
                      "--controller: '{}' is not available (quasi-static, nlsq-mpc, lqr, ilqr, "
                      "policy)",
                      options.controller);
  RODLAB_THROW_UNLESS(c.task != scene::ControlTask::track || c.trajectory.has_value(),
                      "control.task track needs control.trajectory");
  RODLAB_THROW_UNLESS(c.horizon >= 1 && c.dt_control > 0.0 && c.threshold > 0.0 &&
                          c.max_steps >= 1 && c.hold_steps >= 1,
                      "control: horizon, dt_control, threshold, max_steps and hold_steps must be "
                      "positive");
  const auto start = Clock::now();
  ControlResult out;
  out.scene = scene.name;
  out.controller = options.controller;
  out.task = task_name(c.task);
  out.scheme = dynamic ? options.solver.scheme : InverseStaticsOptions{}.statics.scheme;
  if (dynamic && c.model_scheme && *c.model_scheme != options.solver.scheme)
    out.model_scheme = c.model_scheme;
  out.nodes = options.solver.nodes;
  out.dt_control = c.dt_control;
  out.horizon = mpc || options.controller == "ilqr" ? c.horizon : 0;
  out.converged = true;
  if (c.task == scene::ControlTask::track)
    out.targets.drawn_from = result::TargetSource::trajectory, out.seed = c.seed;
  else
    choose_targets(scene, options, out);
  try {
    const DeadlineScope deadline(options.solver.max_wall_time);  // --max-wall-time
    if (dynamic)
      run_dynamic(scene, options, out);
    else
      run_quasi_static(scene, options, out);
  } catch (const WallTimeExceeded& e) {  // common/deadline.hpp: the rows so far stay
    out.converged = false;
    out.reason = e.what();
    close_interrupted_episode(out, e.what());
  }
  if (out.converged && !out.reason)
    for (const auto& e : out.episodes)
      if (e.reason) out.reason = *e.reason;  // an unreachable target
  summarise(out, scene.rod.length, c.dt_control, out.summary);
  if (options.policy) out.summary.samples = options.policy->training.samples;
  out.summary.wall_time_s = seconds_since(start);
  return out;
}

}  // namespace rodlab::solvers::control
