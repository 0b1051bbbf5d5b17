// rodlab workspace SCENE --samples K [options]: sample the actuator inputs, solve the statics
// for each sample, collect the tip poses.
#include <array>
#include <stdexcept>
#include <string>

#include "availability.hpp"
#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"

namespace rodlab::cli {
namespace {

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};
constexpr OptionSpec kSamplesOption{
    "--samples", "K", "samples per actuator input over its limits, integer >= 2 (required)"};
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
  require_available(kWorkspaceArrives);
  require_available(run.scheme);
  // The sweep itself arrives with kWorkspaceArrives: sample, solve_static() each, deliver.
  throw std::logic_error("the workspace sweep is marked available but not linked (" +
                         std::to_string(*samples) + " samples)");
}

}  // namespace

const Command& workspace_command() {
  static const Command command{
      "workspace",
      "SCENE --samples K [options]",
      "sample the actuator inputs and map the reachable tip poses",
      "Samples every actuator input over its limits (K samples each), solves the static\n"
      "equilibrium for each combination with the statics scheme of --scheme or solver.scheme,\n"
      "and collects the tip poses. The options and the scene are checked before anything runs.\n"
      "\n"
      "Exit status: 0 every sample converged; 1 some did not; 2 bad input or usage (nothing is\n"
      "written).\n",
      kPositionals,
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
