// rodlab static SCENE [options]: static equilibrium.
#include <array>

#include "command.hpp"
#include "common_options.hpp"
#include "result_output.hpp"
#include "vtk_output.hpp"

namespace rodlab::cli {
namespace {

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};
constexpr std::array<OptionSpec, 8> kOptions{kSchemeOption,  kNodesOption,   kTolOption,
                                             kTimeOption,    kOutFileOption, kVtkOption,
                                             kSetOption,     kMaxWallTimeOption};

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const SolveOptions options = read_solve_options(reader, solvers::Problem::statics, "static");
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  const StaticRun run = resolve_static_run(options, scene, "static");
  const result::StaticResult result = solvers::statics::solve_static(scene, run.solve);
  if (options.vtk) VtkOutput(scene, *options.vtk).write_state(result.centerline);
  return deliver(result, options.out, options.vtk);
}

}  // namespace

const Command& static_command() {
  static const Command command{
      "static",
      "SCENE [options]",
      "static equilibrium of the rod in SCENE",
      "Solves the static equilibrium of the scene's rod under its loads and actuators at t = 0\n"
      "(or at --time T: schedules are evaluated there).\n"
      "The scheme comes from --scheme or the scene's solver.scheme and must be a statics scheme\n"
      "(`rodlab schemes` lists them). The options and the scene are checked before anything\n"
      "runs. The result (spec: rodlab.static-result/1) is printed as a summary and, with --out,\n"
      "written atomically as JSON or CSV.\n"
      "\n"
      "Exit status: 0 converged; 1 not converged (the result file is still written, with\n"
      "\"converged\": false and the reason); 2 bad input or usage (nothing is written).\n",
      kPositionals,
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
