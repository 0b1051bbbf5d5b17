// rodlab control SCENE --controller NAME --task TASK [options]: a controller on a task
// (interface spec "Control and learning", docs/control.md).
#include <array>
#include <fstream>
#include <iostream>
#include <sstream>

#include "rodlab/check.hpp"
#include "rodlab/io/result_writer.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/io/text_table.hpp"
#include "rodlab/solvers/control/control_run.hpp"

#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "vtk_output.hpp"

namespace rodlab::cli {
namespace {

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};
constexpr std::array<std::string_view, 5> kControllers{"quasi-static", "nlsq-mpc", "lqr", "ilqr",
                                                       "policy"};
constexpr std::array<std::string_view, 3> kTasks{"reach", "hold", "track"};

constexpr OptionSpec kControllerOption{
    "--controller", "NAME",
    "quasi-static | nlsq-mpc | lqr | ilqr | policy (a trained policy, --policy); default: "
    "nlsq-mpc"};
constexpr OptionSpec kPolicyOption{"--policy", "FILE",
                                   "the policy file of `rodlab train` (rodlab.policy/1), for "
                                   "--controller policy"};
constexpr OptionSpec kTaskOption{"--task", "reach|hold|track", "the task; default: control.task"};
constexpr OptionSpec kHorizonOption{"--horizon", "H",
                                    "control steps predicted, integer >= 1; default: control.horizon"};
constexpr OptionSpec kIterationsOption{
    "--iterations", "K",
    "solver iterations per control step (nlsq-mpc, ilqr), integer >= 1; 1: the real-time "
    "iteration; default: control.iterations, else the controller's"};
constexpr OptionSpec kModelSchemeOption{
    "--model-scheme", "NAME",
    "the scheme the controller predicts with, taking over the plant's state every control step: "
    "implicit-midpoint | implicit-midpoint-collocation | variational; default: "
    "control.model_scheme, else the plant's (--scheme)"};
constexpr OptionSpec kDtControlOption{"--dt-control", "X",
                                      "control step [s] > 0; default: control.dt_control"};
constexpr OptionSpec kSeedOption{"--seed", "K", "seed of drawn targets, integer >= 0; default: control.seed"};
constexpr OptionSpec kTargetsOption{
    "--targets", "K", "draw K targets from the static workspace, integer >= 1 (instead of control.targets)"};

/// The task settings: the scene's control section (or its defaults) with the options over it.
scene::Control read_control(OptionReader& reader, const scene::Scene& scene) {
  scene::Control c = scene.control.value_or(scene::Control{});
  if (const auto task = reader.choice(kTaskOption.name, kTasks))
    c.task = *task == "reach" ? scene::ControlTask::reach
             : *task == "hold" ? scene::ControlTask::hold
                               : scene::ControlTask::track;
  if (const auto h = reader.integer(kHorizonOption.name, 1)) c.horizon = *h;
  if (const auto k = reader.integer(kIterationsOption.name, 1)) c.iterations = *k;
  if (const auto m = reader.choice(kModelSchemeOption.name, scene::kModelSchemes))
    c.model_scheme = *m;
  if (const auto dt = reader.positive(kDtControlOption.name)) c.dt_control = *dt;
  if (const auto seed = reader.integer(kSeedOption.name, 0)) c.seed = static_cast<unsigned>(*seed);
  if (const auto k = reader.integer(kTargetsOption.name, 1)) {
    c.target_count = *k;
    c.targets.clear();
  }
  if (c.task == scene::ControlTask::track && !c.trajectory)
    reader.problem("--task track: the scene has no control.trajectory to track");
  return c;
}

std::string summarize(const result::ControlResult& r) {
  io::TextTable t;
  t.add_row({"scene", r.scene});
  t.add_row({"controller", r.controller + " on " + r.task + ", " + r.scheme + " N = " +
                               std::to_string(r.nodes) + ", dt_control " +
                               io::format_number(r.dt_control) + " s, horizon " +
                               std::to_string(r.horizon)});
  if (r.model_scheme) t.add_row({"model", "predicts with " + *r.model_scheme});
  t.add_row({"status", r.converged ? std::string("converged") : "NOT converged: " + r.reason.value_or("")});
  int ok = 0;
  for (const auto& e : r.episodes) ok += e.success ? 1 : 0;
  t.add_row({"episodes", std::to_string(ok) + " of " + std::to_string(r.episodes.size()) +
                             " successful"});
  t.add_row({"mean error", io::format_number(r.summary.mean_error_pct_L) + " % of L"});
  t.add_row({"real-time ratio", io::format_number(r.summary.real_time_ratio_mean) + " mean, " +
                                    io::format_number(r.summary.real_time_ratio_max) + " max"});
  t.add_row({"wall time", io::format_number(r.summary.wall_time_s) + " s"});
  if (r.reason && r.converged) t.add_row({"note", *r.reason});
  return t.render();
}

/// --policy FILE: read and parsed (a missing or bad file is bad input, exit 2).
solvers::learning::Policy read_policy(OptionReader& reader) {
  const auto path = reader.text(kPolicyOption.name);
  if (!path) throw UsageError("--controller policy needs --policy FILE (from `rodlab train`)");
  std::ifstream in(*path, std::ios::binary);
  if (!in) throw UsageError("--policy: cannot read " + *path);
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return solvers::learning::policy_from_json(text.str());
  } catch (const std::invalid_argument& e) {
    throw UsageError("--policy: " + *path + ": " + e.what());
  }
}

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const SolveOptions options = read_solve_options(reader, solvers::Problem::dynamics, "control");
  const auto controller = reader.choice(kControllerOption.name, kControllers);
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  solvers::control::ControlRunOptions run;
  run.controller = controller.value_or("nlsq-mpc");
  run.control = read_control(reader, scene);
  reader.finish();
  run.solver = resolve_plant_solver(options, scene, "control");
  if (run.controller == "policy") {
    run.policy = read_policy(reader);
    // a policy acts at its own step and nodes unless told otherwise
    if (!inv.args.has(kDtControlOption.name)) run.control.dt_control = run.policy->dt_control;
    if (!options.nodes) run.solver.nodes = run.policy->nodes;
  }
  std::vector<VtkOutput> vtk;  // one collection per episode: DIR/episode_<e>/rod.pvd
  if (options.vtk)
    run.on_state = [&](int episode, double t, const solvers::dynamics::Stepper& state) {
      while (static_cast<int>(vtk.size()) <= episode)
        vtk.emplace_back(scene, *options.vtk / rodlab::format("episode_{:03d}", vtk.size()));
      vtk[episode].add_state(t, state.centerline(), state.velocities());
    };
  const result::ControlResult r = solvers::control::run_control(scene, run);
  for (const auto& v : vtk) v.finish();
  if (options.out) io::write_result(*options.out, r);
  std::cout << summarize(r);
  if (options.out) std::cout << "result written to " << options.out->string() << '\n';
  if (options.vtk) std::cout << "ParaView files in " << options.vtk->string() << '\n';
  return r.converged && !r.reason ? kSolved : kNotConverged;
}

}  // namespace

const Command& control_command() {
  static const std::array<OptionSpec, 17> options{
      kControllerOption, kTaskOption,    kHorizonOption,     kIterationsOption, kDtControlOption,
      kSchemeOption,     kModelSchemeOption, kNodesOption,   kTolOption,        kGridOption,
      kSeedOption,       kTargetsOption, kOutFileOption,     kVtkOption,        kSetOption,
      kMaxWallTimeOption, kPolicyOption};
  static const Command command{
      "control",
      "SCENE [--controller NAME] [--task reach|hold|track] [options]",
      "drive the rod's tip with a controller (inverse statics, NLSQ-MPC, LQR, iLQR)",
      "Runs a controller on a task of the scene's control section (docs/control.md):\n"
      "reach (each target until the tip is within control.threshold * L, at most\n"
      "control.max_steps control steps; all of them with control.stop_at_success: false), hold (within the threshold for control.hold_steps\n"
      "steps in a row) or track (control.trajectory). Targets are control.targets, else\n"
      "--targets K (or control.target_count) drawn with --seed from the static workspace.\n"
      "nlsq-mpc plans --horizon steps of --dt-control on a dynamics scheme (--scheme, else\n"
      "dynamics.scheme, else implicit-midpoint), or with --model-scheme on a model that takes\n"
      "over the plant's state every control step; ilqr plans the same horizon by iterative\n"
      "LQR with input limits; lqr (reach, hold) regulates about the\n"
      "equilibrium of the inverse statics' inputs for each target; quasi-static solves the\n"
      "inverse statics (chebyshev). The result (rodlab.control-result/1) is printed as a summary and, with\n"
      "--out, written atomically as JSON or CSV (one row per control step).\n"
      "\n"
      "Exit status: 0 done; 1 a solver failed or a target is out of reach (the result is still\n"
      "written, with the reason); 2 bad input or usage (nothing is written).\n",
      kPositionals,
      options,
      &run};
  return command;
}

}  // namespace rodlab::cli
