// rodlab dynamic SCENE [options]: time simulation.
#include <array>
#include <optional>

#include "rodlab/check.hpp"

#include "command.hpp"
#include "common_options.hpp"
#include "progress_line.hpp"
#include "result_output.hpp"
#include "vtk_output.hpp"

namespace rodlab::cli {
namespace {

constexpr std::array<std::string_view, 1> kPositionals{"SCENE"};

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const SolveOptions options = read_solve_options(reader, solvers::Problem::dynamics, "dynamic");
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  DynamicRun run = resolve_dynamic_run(options, scene, "dynamic");
  resolve_time_step(run, scene);
  std::optional<VtkOutput> vtk;
  if (options.vtk) {
    vtk.emplace(scene, *options.vtk);
    run.solve.on_output = [&](double t, const solvers::dynamics::Stepper& state) {
      vtk->add_state(t, state.centerline(), state.velocities());
    };
  }
  ProgressLine progress("dynamic", "steps", !options.quiet);
  if (progress.active())
    run.solve.on_step = [&](long done, long steps, double t, double dt) {
      progress.update(done, steps, rodlab::format("t = {:.4g} s, dt = {:.3g} s", t, dt));
    };
  const result::DynamicResult result = solvers::dynamics::solve_dynamic(scene, run.solve);
  progress.finish();
  if (vtk) vtk->finish();
  return deliver(result, options.out, options.vtk);
}

}  // namespace

const Command& dynamic_command() {
  // A local static: the scheme options' help lines are made at start-up in another file.
  static const std::array<OptionSpec, 16> options{
      kSchemeOption, kNodesOption, kTolOption,  kDtOption,   kTEndOption,  kOutputEveryOption,
      kOutFileOption, kVtkOption,  kSetOption,  kRtolOption, kAtolOption,  kAlphaOption,
      kGridOption,   kVariationalStepOption, kMaxWallTimeOption, kQuietOption};
  static const Command command{
      "dynamic",
      "SCENE [options]",
      "time simulation of the rod in SCENE",
      "Simulates the scene from t = 0 to the end time (--t-end or dynamics.t_end). The scheme\n"
      "is --scheme, else dynamics.scheme, else solver.scheme if it names a dynamics scheme,\n"
      "else variational (`rodlab schemes` lists them). --dt auto (the default when neither\n"
      "--dt nor dynamics.dt is given) is 0.9 times the measured stability limit of\n"
      "variational, or 1/10 of the first bending period for the implicit schemes (for ida\n"
      "the output interval; its own steps follow --rtol and --atol). The\n"
      "options and the scene are checked before anything runs. The result\n"
      "(rodlab.dynamic-result/1) is printed as a summary and, with --out, written atomically\n"
      "as JSON or as CSV (one row per output time).\n"
      "\n"
      "Exit status: 0 finished; 1 a step did not converge or the run went unstable (the result\n"
      "file is still written, with \"converged\": false and the reason); 2 bad input or usage\n"
      "(nothing is written).\n",
      kPositionals,
      options,
      &run};
  return command;
}

}  // namespace rodlab::cli
