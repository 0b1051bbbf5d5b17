// rodlab workspace SCENE --samples K [options]: sample the actuator inputs, solve the statics
// for each sample, collect the tip poses.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <iostream>

#include "rodlab/check.hpp"
#include "rodlab/io/result_writer.hpp"
#include "progress_line.hpp"
#include "vtk_output.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/solvers/dynamics/dynamic_workspace.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/statics/workspace.hpp"

#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"

namespace rodlab::cli {
namespace {

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};
constexpr OptionSpec kSamplesOption{
    "--samples", "K", "number of sampled input vectors, integer >= 2 (required)"};
constexpr OptionSpec kDynamicOption{
    "--dynamic", "", "the dynamic workspace (thesis 3.4.1): K input vectors held in turn in one "
                     "simulation; --scheme is then a dynamics scheme"};
constexpr OptionSpec kHoldOption{
    "--hold", "T", "--dynamic: how long each input vector is held [s] > 0; default: the first "
                   "bending period"};
constexpr std::array<OptionSpec, 11> kOptions{kSamplesOption, kDynamicOption, kHoldOption,
                                              kSchemeOption,  kNodesOption,   kTolOption,
                                              kDtOption,      kOutFileOption, kVtkOption,
                                              kSetOption,     kQuietOption};

/// The first bending period 2 pi / omega_1 of the cantilever (Euler-Bernoulli).
double first_period(const scene::Scene& scene) {
  const auto problem = solvers::dynamics::DynamicProblem::from_scene(scene);
  const auto& K = problem.model().K_diag();
  const auto& M = problem.model().M_diag();
  const double L = problem.length();
  const double omega1 = 1.8751040687119611 * 1.8751040687119611 / (L * L) *
                        std::sqrt(std::min(K[0], K[1]) / M[3]);
  return 2.0 * std::numbers::pi / omega1;
}

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const bool dynamic = reader.flag(kDynamicOption.name);
  const SolveOptions options = read_solve_options(
      reader, dynamic ? solvers::Problem::dynamics : solvers::Problem::statics, "workspace");
  const auto samples = reader.integer(kSamplesOption.name, 2);
  if (!reader.arguments().has(kSamplesOption.name))
    reader.problem("--samples: required (the number of samples per actuator input)");
  const auto hold = reader.positive(kHoldOption.name);
  if (!dynamic && (hold || options.dt))
    reader.problem(std::string(hold ? "--hold" : "--dt") + ": only with --dynamic");
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  if (scene.actuators.empty())
    throw UsageError("the workspace samples actuator inputs, and " + options.scene_path +
                     " has no actuators");
  result::WorkspaceResult result;
  ProgressLine progress("workspace", dynamic ? "steps" : "samples", !options.quiet);
  if (dynamic) {
    solvers::dynamics::DynamicWorkspaceOptions ws;
    ws.holds = static_cast<int>(*samples);
    ws.hold_time = hold.value_or(first_period(scene));
    SolveOptions timed = options;  // the run lasts holds x hold, whatever dynamics.t_end says
    timed.t_end = ws.holds * ws.hold_time;
    DynamicRun run = resolve_dynamic_run(timed, scene, "workspace");
    resolve_time_step(run, scene);
    ws.solve = run.solve;  // t_end and output_every: set by the workspace from the holds
    if (progress.active())
      ws.solve.on_step = [&](long done, long steps, double t, double) {
        progress.update(done, steps, rodlab::format("t = {:.4g} s", t));
      };
    result = solvers::dynamics::sample_dynamic_workspace(scene, ws);
  } else {
    const StaticRun run = resolve_static_run(options, scene, "workspace");
    result = solvers::statics::sample_workspace(
        scene, run.solve, static_cast<int>(*samples), 1,
        [&](int done, int total) { progress.update(done, total); });
  }
  progress.finish();
  if (options.out) io::write_result(*options.out, result);
  if (options.vtk) VtkOutput(scene, *options.vtk).write_workspace(result);
  std::cout << "scene            " << result.scene << "\n"
            << "scheme           " << result.scheme << ", " << result.nodes << " nodes\n"
            << (dynamic ? "tips recorded    " : "samples          ") << result.samples.size()
            << (dynamic ? (result.failed ? " (the run stopped early: run `rodlab dynamic` with "
                                           "the same scheme for the reason)"
                                         : " (" + std::to_string(*samples) + " held inputs)")
                        : " (" + std::to_string(result.failed) + " did not converge)")
            << ", seed " << result.seed << "\n"
            << "omega_bound      " << io::format_number(result.bounds.omega_bound) << " rad/m\n"
            << "epsilon          [" << io::format_number(result.bounds.eps_low) << ", "
            << io::format_number(result.bounds.eps_high) << "]\n"
            << "wall time        " << io::format_number(result.wall_time_s) << " s\n";
  if (options.out) std::cout << "result written to " << options.out->string() << '\n';
  if (options.vtk) std::cout << "ParaView files in " << options.vtk->string() << '\n';
  return result.failed == 0 ? kSolved : kNotConverged;
}

}  // namespace

const Command& workspace_command() {
  static const Command command{
      "workspace",
      "SCENE --samples K [options]",
      "sample the actuator inputs and map the reachable tip poses",
      "Draws K input vectors uniformly within every actuator's `limits` (fixed seed), solves the\n"
      "static equilibrium of each with the statics scheme of --scheme or solver.scheme, and fits\n"
      "the constant-curvature workspace model (thesis 2.7.3): omega_bound, eps_low, eps_high.\n"
      "--out writes the sampled tips and the bounds (rodlab.workspace-result/1, JSON or CSV).\n"
      "With --dynamic: the K input vectors are held in turn (each for --hold T, default the\n"
      "first bending period) in one simulation with the dynamics scheme, and the model is\n"
      "fitted around every recorded tip (the dynamic workspace, thesis 3.4.1).\n"
      "The options and the scene are checked before anything runs.\n"
      "\n"
      "Exit status: 0 every sample converged; 1 some did not; 2 bad input or usage (nothing is\n"
      "written).\n",
      kPositionals,
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
