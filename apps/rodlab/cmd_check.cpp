// rodlab check SCENE [--nodes N] [--set KEY=VALUE] [--json]: check a scene and print what to
// know before running it.
#include <array>
#include <iostream>

#include "rodlab/rod/characteristics.hpp"

#include "check_report.hpp"
#include "command.hpp"
#include "common_options.hpp"
#include "exit_status.hpp"

namespace rodlab::cli {
namespace {

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};
constexpr std::array<OptionSpec, 3> kOptions{
    kNodesOption, kSetOption,
    OptionSpec{"--json", "", "print the same report as one JSON object (schema rodlab.check/1)"}};

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const SolveOptions options = read_solve_options(reader, solvers::Problem::statics, "check");
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);

  const int nodes = options.nodes.value_or(scene.solver.nodes);
  const auto tip = scene.tip_clamped() ? rod::TipSupport::clamped : rod::TipSupport::free;
  const rod::Characteristics c = rod::characteristics(scene.rod.to_model(), nodes, tip);
  const Report report = check_report(scene, c, options.nodes ? "--nodes" : "solver.nodes");
  std::cout << (reader.flag("--json") ? render_json(report) : render_text(report));
  return kSolved;
}

}  // namespace

const Command& check_command() {
  static const Command command{
      "check",
      "SCENE [options]",
      "check a scene; print derived quantities, time steps and the model verdict",
      "Reads and checks SCENE (every problem is reported as file:line:col: field: message,\n"
      "exit status 2), then prints what to know before running it: the section properties,\n"
      "the diagonals of K, M (and V for a viscous rod), the wave speeds, the node spacing, the\n"
      "CFL bound and the explicit time step (3.44) for N nodes, the first bending and axial\n"
      "frequencies, the stiffness ratios with the Kirchhoff error estimate and its verdict,\n"
      "the loads, actuators and solver settings. Nothing is written.\n"
      "\n"
      "Exit status: 0 the scene is valid; 2 bad input or usage.\n",
      kPositionals,
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
