#include "common_options.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "rodlab/check.hpp"
#include "rodlab/io/result_writer.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

#include "errors.hpp"

namespace rodlab::cli {
namespace fs = std::filesystem;
using solvers::Problem;

namespace {
const solvers::dynamics::DynamicSolveOptions kDefaults;
const std::string kRtolHelp =
    "ida: relative tolerance of the time integration > 0; default: " + io::format_number(kDefaults.rtol);
const std::string kAtolHelp =
    "ida: absolute tolerance > 0 (scaled per component); default: " + io::format_number(kDefaults.atol);
const std::string kAlphaHelp =
    "bdf-alpha: alpha in [-0.5, 0] (0 BDF2, -0.5 trapezoidal); default: solver.alpha, else " +
    io::format_number(kDefaults.alpha);
const std::string kGridHelp =
    "the spatial grid: for implicit-midpoint and bdf-alpha euler (explicit Euler RKMK on the "
    "nodes, the thesis) or staggered (the grid of variational and ida, second order); for "
    "every dynamics scheme staggered or corrected (the staggered grid with its bending and tip "
    "corrections, about 15x smaller errors on bending modes; Cosserat rods without actuators); "
    "default: solver.grid, else " +
    std::string(solvers::dynamics::shooting_grid_name(kDefaults.grid));
const std::string kVariationalStepHelp =
    "variational: its time rule, verlet (Stormer-Verlet, second order) or symplectic-euler (the "
    "thesis, first order); default: solver.variational_step, else " +
    std::string(solvers::dynamics::variational_step_name(kDefaults.variational_step));
}  // namespace

// Defined after their help lines (same translation unit: initialised in this order); other
// files use them only from functions, after static initialisation.
const OptionSpec kRtolOption{"--rtol", "X", kRtolHelp};
const OptionSpec kAtolOption{"--atol", "X", kAtolHelp};
const OptionSpec kAlphaOption{"--alpha", "X", kAlphaHelp};
const OptionSpec kGridOption{"--grid", "euler|staggered|corrected", kGridHelp};
const OptionSpec kVariationalStepOption{"--variational-step", "verlet|symplectic-euler",
                                        kVariationalStepHelp};


std::optional<solvers::SchemeInfo> fitting_scheme(std::string_view name, Problem problem,
                                                  std::string_view command, std::string& why) {
  const auto takes = "`rodlab " + std::string(command) + "` takes a " +
                     std::string(solvers::to_string(problem)) +
                     " scheme: " + solvers::scheme_names(problem);
  const auto scheme = solvers::find_scheme(name);
  if (!scheme) {
    why = "unknown scheme '" + std::string(name) + "'; " + takes;
    return std::nullopt;
  }
  if (scheme->problem != problem) {
    why = std::string("'") + std::string(name) + "' is a " +
          std::string(solvers::to_string(scheme->problem)) + " scheme; " + takes;
    return std::nullopt;
  }
  return scheme;
}

std::vector<io::Override> read_overrides(OptionReader& reader) {
  std::vector<io::Override> out;
  for (const auto& text : reader.arguments().values(kSetOption.name)) {
    try {
      out.push_back(io::parse_override(text));
    } catch (const io::SceneError& e) {
      for (const auto& d : e.diagnostics())
        reader.problem("--set " + text + ": " + (d.field.empty() ? "" : d.field + ": ") +
                       d.message);
    }
  }
  return out;
}

std::optional<fs::path> read_out_file(OptionReader& reader) {
  const auto text = reader.text(kOutFileOption.name);
  if (!text) return std::nullopt;
  const fs::path path(*text);
  bool ok = true;
  try {
    io::result_format(path);
  } catch (const std::invalid_argument&) {
    reader.problem("--out: the result file must end in .json or .csv (got " + *text + ")");
    ok = false;
  }
  ok = check_out_file_place(reader, path) && ok;
  return ok ? std::optional(path) : std::nullopt;
}

bool check_out_file_place(OptionReader& reader, const fs::path& path, std::string_view option) {
  std::error_code ec;
  const fs::path dir = path.parent_path();
  if (!dir.empty() && !fs::is_directory(dir, ec)) {
    reader.problem(std::string(option) + ": directory " + dir.string() + " does not exist (for " +
                   path.string() + ")");
    return false;
  }
  if (fs::is_directory(path, ec)) {
    reader.problem(std::string(option) + ": " + path.string() +
                   " is a directory; give a file name");
    return false;
  }
  return true;
}

std::optional<fs::path> read_out_dir(OptionReader& reader, std::string_view option) {
  const auto text = reader.text(option);
  if (!text) return std::nullopt;
  std::error_code ec;
  if (fs::exists(*text, ec) && !fs::is_directory(*text, ec)) {
    reader.problem(std::string(option) + ": " + *text + " exists and is not a directory");
    return std::nullopt;
  }
  return fs::path(*text);
}

SolveOptions read_solve_options(OptionReader& reader, Problem problem, std::string_view command) {
  SolveOptions o;
  if (!reader.arguments().positionals().empty())
    o.scene_path = reader.arguments().positionals().back();
  o.overrides = read_overrides(reader);
  if (const auto name = reader.text(kSchemeOption.name)) {
    std::string why;
    o.scheme = fitting_scheme(*name, problem, command, why);
    if (!o.scheme) reader.problem("--scheme: " + why);
  }
  o.nodes = reader.integer(kNodesOption.name, solvers::min_nodes(problem));
  o.tol = reader.positive(kTolOption.name);
  o.out = read_out_file(reader);
  o.vtk = read_out_dir(reader, kVtkOption.name);
  o.quiet = reader.flag(kQuietOption.name);
  if (const auto dt = reader.text(kDtOption.name)) {
    if (*dt == "auto") {
      o.dt = TimeStep{};
    } else if (const auto v = to_double(*dt); v && *v > 0.0) {
      o.dt = TimeStep{false, *v};
    } else {
      reader.problem("--dt: must be a number > 0 or auto (got " + *dt + ")");
    }
  }
  o.t_end = reader.positive(kTEndOption.name);
  if (const auto time = reader.text(kTimeOption.name)) {
    if (const auto v = to_double(*time); v && *v >= 0.0 && std::isfinite(*v))
      o.time = *v;
    else
      reader.problem("--time: must be a number >= 0 (got " + *time + ")");
  }
  o.output_every = reader.integer(kOutputEveryOption.name, 1);
  o.rtol = reader.positive(kRtolOption.name);
  o.atol = reader.positive(kAtolOption.name);
  o.max_wall_time = reader.positive(kMaxWallTimeOption.name);
  if (const auto alpha = reader.text(kAlphaOption.name)) {
    if (const auto v = to_double(*alpha); v && *v >= -0.5 && *v <= 0.0)
      o.alpha = *v;
    else
      reader.problem("--alpha: must be a number in [-0.5, 0] (got " + *alpha + ")");
  }
  if (const auto grid = reader.text(kGridOption.name)) {
    if (solvers::dynamics::shooting_grid_from_name(*grid))
      o.grid = *grid;
    else
      reader.problem("--grid: must be euler, staggered or corrected (got " + *grid + ")");
  }
  if (const auto step = reader.text(kVariationalStepOption.name)) {
    if (solvers::dynamics::variational_step_from_name(*step))
      o.variational_step = *step;
    else
      reader.problem("--variational-step: must be verlet or symplectic-euler (got " + *step + ")");
  }
  return o;
}

scene::Scene load_checked_scene(const SolveOptions& options) {
  return io::load_scene(options.scene_path, options.overrides);
}

namespace {

/// The scheme --scheme named, or the one the scene names in `field` (checked to fit).
solvers::SchemeInfo chosen_scheme(const SolveOptions& options, const scene::Scene& scene,
                                  std::string_view from_scene, std::string_view field,
                                  Problem problem, std::string_view command) {
  if (options.scheme) return *options.scheme;
  std::string why;
  if (auto scheme = fitting_scheme(from_scene, problem, command, why)) return *scheme;
  io::SceneDiagnostic d;
  d.source = scene.source_path.empty() ? options.scene_path : scene.source_path;
  d.field = std::string(field);
  d.message = why + " (or choose one with --scheme)";
  throw io::SceneError({d});
}

}  // namespace

StaticRun resolve_static_run(const SolveOptions& options, const scene::Scene& scene,
                             std::string_view command) {
  StaticRun run{chosen_scheme(options, scene, scene.solver.scheme, "solver.scheme",
                              Problem::statics, command),
                {}};
  run.solve.scheme = std::string(run.scheme.name);
  run.solve.nodes = options.nodes.value_or(scene.solver.nodes);
  run.solve.tol = options.tol.value_or(scene.solver.tol);
  run.solve.max_iterations = scene.solver.max_iterations;
  run.solve.time = options.time.value_or(0.0);
  run.solve.max_wall_time = options.max_wall_time.value_or(0.0);
  return run;
}

std::string scene_dynamics_scheme(const scene::Scene& scene) {
  if (scene.dynamics && scene.dynamics->scheme) return *scene.dynamics->scheme;
  const auto solver_scheme = solvers::find_scheme(scene.solver.scheme);
  if (solver_scheme && solver_scheme->problem == Problem::dynamics) return scene.solver.scheme;
  return solvers::dynamics::DynamicSolveOptions{}.scheme;
}

namespace {

/// Rest-strain spans (issue #18): every dynamics scheme solves them when every span begins on a
/// node; otherwise a scene error at rod.rest_strain.spans, before anything runs.
void check_rest_spans(const SolveOptions& options, const scene::Scene& scene,
                      const DynamicRun& run) {
  if (scene.rod.rest_spans.empty()) return;
  try {
    scene.rod.to_model().require_spans_on_grid(run.solve.nodes, run.scheme.name);
  } catch (const std::invalid_argument& e) {
    io::SceneDiagnostic d;
    d.source = scene.source_path.empty() ? options.scene_path : scene.source_path;
    d.line = scene.rod.rest_spans_line;
    d.column = scene.rod.rest_spans_column;
    d.field = "rod.rest_strain.spans";
    const std::string what = e.what(), prefix = "rod.rest_strain.spans: ";
    d.message = what.rfind(prefix, 0) == 0 ? what.substr(prefix.size()) : what;
    throw io::SceneError({d});
  }
}

}  // namespace

DynamicRun resolve_dynamic_solver(const SolveOptions& options, const scene::Scene& scene,
                                  std::string_view scene_scheme, std::string_view command) {
  DynamicRun run{chosen_scheme(options, scene, scene_scheme, "dynamics.scheme", Problem::dynamics,
                               command),
                 true,
                 {}};
  auto& solve = run.solve;
  solve.scheme = std::string(run.scheme.name);
  solve.nodes = options.nodes.value_or(scene.solver.nodes);
  if (solve.nodes < solvers::min_nodes(Problem::dynamics))
    throw UsageError(rodlab::format("{}: the dynamics schemes need N >= {} (got {})",
                                    options.nodes ? "--nodes" : "solver.nodes",
                                    solvers::min_nodes(Problem::dynamics), solve.nodes));
  solve.tol = options.tol.value_or(scene.solver.tol);
  solve.max_iterations = scene.solver.max_iterations;
  solve.rtol = options.rtol.value_or(solve.rtol);
  solve.atol = options.atol.value_or(solve.atol);
  solvers::dynamics::apply_scene_options(scene, solve);  // then the command line over the scene
  if (options.alpha) solve.alpha = *options.alpha;
  if (options.grid) solve.grid = *solvers::dynamics::shooting_grid_from_name(*options.grid);
  if (options.variational_step)
    solve.variational_step =
        *solvers::dynamics::variational_step_from_name(*options.variational_step);
  solve.max_wall_time = options.max_wall_time.value_or(0.0);
  check_rest_spans(options, scene, run);
  return run;
}

DynamicRun resolve_dynamic_run(const SolveOptions& options, const scene::Scene& scene,
                               std::string_view command) {
  DynamicRun run = resolve_dynamic_solver(options, scene, scene_dynamics_scheme(scene), command);
  auto& solve = run.solve;
  const scene::Dynamics dynamics = scene.dynamics.value_or(scene::Dynamics{});
  const auto t_end = options.t_end ? options.t_end : dynamics.t_end;
  if (!t_end)
    throw UsageError("--t-end: no end time; give --t-end T or set dynamics.t_end in " +
                     options.scene_path);
  solve.t_end = *t_end;
  const TimeStep dt = options.dt ? *options.dt : dynamics.dt ? TimeStep{false, *dynamics.dt} : TimeStep{};
  run.automatic_dt = dt.automatic;
  solve.dt = dt.value;
  if (!dt.automatic && dt.value > solve.t_end)
    throw UsageError("--dt: the time step " + io::format_number(dt.value) +
                     " s exceeds the end time " + io::format_number(solve.t_end) + " s");
  solve.output_every = options.output_every.value_or(dynamics.output_every);
  return run;
}

void resolve_time_step(DynamicRun& run, const scene::Scene& scene) {
  if (!run.automatic_dt) return;
  // on the run's grid: the corrected grid's softer shear allows a longer step
  const auto problem = solvers::dynamics::problem_on_grid(
      solvers::dynamics::DynamicProblem::from_scene(scene), run.solve);
  run.solve.dt = solvers::dynamics::auto_time_step(problem, run.solve.scheme, run.solve.nodes);
  run.automatic_dt = false;
}

solvers::dynamics::DynamicSolveOptions resolve_plant_solver(const SolveOptions& o,
                                                            const scene::Scene& scene,
                                                            std::string_view command) {
  const std::string scheme = scene.dynamics && scene.dynamics->scheme ? *scene.dynamics->scheme
                                                                       : "implicit-midpoint";
  solvers::dynamics::DynamicSolveOptions s = resolve_dynamic_solver(o, scene, scheme, command).solve;
  if (scene.dynamics && scene.dynamics->dt) s.dt = *scene.dynamics->dt;
  return s;
}

}  // namespace rodlab::cli
