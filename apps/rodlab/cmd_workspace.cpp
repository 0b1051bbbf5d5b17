// rodlab workspace SCENE --samples K [options]: sample the actuator inputs, solve the statics
// for each sample, collect the tip poses.
#include <array>
#include <stdexcept>
#include <string>

#include <iostream>

#include "rodlab/io/result_writer.hpp"
#include "rodlab/solvers/statics/workspace.hpp"

#include "availability.hpp"
#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "format.hpp"

namespace rodlab::cli {
namespace {

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};
constexpr OptionSpec kSamplesOption{
    "--samples", "K", "number of sampled input vectors, integer >= 2 (required)"};
constexpr std::array<OptionSpec, 6> kOptions{kSamplesOption, kSchemeOption,  kNodesOption,
                                             kTolOption,     kOutFileOption, kSetOption};

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const SolveOptions options = read_solve_options(reader, solvers::Problem::statics, "workspace");
  const auto samples = reader.integer(kSamplesOption.name, 2);
  if (!reader.arguments().has(kSamplesOption.name))
    reader.problem("--samples: required (the number of samples per actuator input)");
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  if (scene.actuators.empty())
    throw UsageError("the workspace samples actuator inputs, and " + options.scene_path +
                     " has no actuators");
  const StaticRun run = resolve_static_run(options, scene, "workspace");
  require_available(run.scheme);
  solvers::statics::StaticSolveOptions solve;
  solve.scheme = std::string(run.scheme.name);
  solve.nodes = run.nodes;
  solve.tol = run.tol;
  solve.max_iterations = run.max_iterations;
  const auto result = solvers::statics::sample_workspace(scene, solve, static_cast<int>(*samples));
  if (options.out) io::write_result(*options.out, result);
  std::cout << "scene            " << result.scene << "\n"
            << "scheme           " << result.scheme << ", " << result.nodes << " nodes\n"
            << "samples          " << result.samples.size() << " (" << result.failed
            << " did not converge), seed " << result.seed << "\n"
            << "omega_bound      " << format_number(result.bounds.omega_bound) << " rad/m\n"
            << "epsilon          [" << format_number(result.bounds.eps_low) << ", "
            << format_number(result.bounds.eps_high) << "]\n"
            << "wall time        " << format_number(result.wall_time_s) << " s\n";
  if (options.out) std::cout << "result written to " << options.out->string() << '\n';
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
