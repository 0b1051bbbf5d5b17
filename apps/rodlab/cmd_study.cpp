// rodlab study KIND SCENE [options]: convergence, work-precision and stability studies, and
// the scheme recommendation built on them (docs/studies.md); `control` (the thesis' Table 4.1)
// is handed to study_control.cpp. This file reads and checks the
// command line and the scene (nothing runs and nothing is written until everything is
// valid), then hands over to the study functions (study_*.hpp) and writes their outputs.
#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>

#include "rodlab/check.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"

#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "progress_line.hpp"
#include "studies/convergence.hpp"
#include "studies/executor.hpp"
#include "studies/processes.hpp"
#include "studies/stability.hpp"
#include "studies/work_precision.hpp"
#include "study_control.hpp"
#include "study_learning.hpp"

namespace rodlab::cli {

namespace study = validation::study;
namespace {

using solvers::Problem;
using study::Json;

constexpr std::array<std::string_view, 2> kPositionals{"KIND", "SCENE"};
constexpr std::array<std::string_view, 6> kKinds{"convergence", "work-precision", "stability",
                                                 "recommend", "control", "learning"};
constexpr std::array<std::string_view, 3> kReferences{"kinsol", "ida", "chebyshev"};
constexpr OptionSpec kStudyTolOption{
    "--tol", "X",
    "recommend: the tip error to reach [m]; other studies: the solver tolerance "
    "(default: solver.tol)"};
constexpr std::array<std::string_view, 3> kRefinements{"time", "joint", "grid"};
constexpr std::array<OptionSpec, 15> kSweepOptions{
    OptionSpec{"--schemes", "A,B,...",
               "schemes to compare, comma-separated (one problem class); default: all of the problem class"},
    OptionSpec{"--nodes", "N1,N2,...",
               "node counts, comma-separated integers >= 2; control: one N (default 20)"},
    OptionSpec{"--dt", "X1,X2,...", "time steps > 0, comma-separated (dynamics studies)"},
    OptionSpec{"--t-end", "T", "length of the dynamics runs [s]; default: dynamics.t_end"},
    OptionSpec{"--refine", "time|joint|grid",
               "dynamics: refine dt at each N against ida at that N (time, default: the time "
               "error), N and dt together, dt ~ ds (joint), or every dt at every N (grid), "
               "both against ida at a 4x finer N (the error of space and time; recommend then "
               "compares the largest tip error over the run)"},
    OptionSpec{"--grids", "G1,G2,...",
               "dynamics (not stability): the spatial grids to sweep, each against ida on its "
               "own grid: euler (implicit-midpoint, bdf-alpha), staggered, corrected; default: "
               "solver.grid, else staggered (work-precision, recommend: staggered,corrected "
               "where the scene takes the corrected grid)"},
    OptionSpec{"--reference", "NAME", "reference solution: kinsol, ida or chebyshev"},
    kStudyTolOption,
    OptionSpec{"--budget-ms", "X", "recommend: time budget per run in milliseconds, > 0"},
    OptionSpec{"--repeats", "R", "work-precision, recommend: timed repeats per run (default 5)"},
    OptionSpec{"--moduli", "E1,E2,...", "stability: Young's moduli [Pa] (default 1e4,1e6,1e8)"},
    OptionSpec{"--jobs", "N", "runs in parallel on this machine, integer >= 1 (default 1)"},
    OptionSpec{"--out", "DIR", "directory for the study's data (default out/study-KIND)"},
    kSetOption, kQuietOption};

/// Every option of `rodlab study`: the sweep kinds', control's and learning's.
constexpr auto kOptions = [] {
  std::array<OptionSpec, kSweepOptions.size() + kStudyControlOptions.size() +
                             kStudyLearningOptions.size()>
      all{};
  std::size_t i = 0;
  for (const auto& o : kSweepOptions) all[i++] = o;
  for (const auto& o : kStudyControlOptions) all[i++] = o;
  for (const auto& o : kStudyLearningOptions) all[i++] = o;
  return all;
}();

constexpr int kDefaultRepeats = 5;

/// The problem class of the study from its schemes, its reference, or its kind; nullopt when
/// nothing decides it (then statics).
std::optional<Problem> check_problem_class(OptionReader& reader, const std::string& kind) {
  std::optional<Problem> problem;
  std::string decided_by;
  if (kind == "stability") {
    problem = Problem::dynamics;
    decided_by = "a stability study (time stepping)";
  }
  if (const auto names = reader.names("--schemes")) {
    for (const auto& name : *names) {
      const auto scheme = solvers::find_scheme(name);
      if (!scheme) {
        reader.problem("--schemes: unknown scheme '" + name +
                       "'; the statics schemes are: " + solvers::scheme_names(Problem::statics) +
                       "; the dynamics schemes are: " + solvers::scheme_names(Problem::dynamics));
        continue;
      }
      if (problem && *problem != scheme->problem) {
        reader.problem("--schemes: '" + name + "' is a " +
                       std::string(solvers::to_string(scheme->problem)) + " scheme but " +
                       decided_by + " needs " + std::string(solvers::to_string(*problem)) +
                       " schemes");
        continue;
      }
      if (!problem) {
        problem = scheme->problem;
        decided_by = "'" + name + "'";
      }
    }
  }
  if (const auto reference = reader.choice("--reference", kReferences)) {
    const Problem p = solvers::find_scheme(*reference)->problem;
    if (kind == "stability")
      reader.problem("--reference: a stability study compares no solutions");
    else if (problem && *problem != p)
      reader.problem("--reference: '" + *reference + "' is a " +
                     std::string(solvers::to_string(p)) + " reference but " + decided_by +
                     " needs a " + std::string(solvers::to_string(*problem)) + " one");
    else if (!problem) {
      problem = p;
      decided_by = "--reference " + *reference;
    }
  }
  const char* dynamics_option = nullptr;
  for (const char* option : {"--dt", "--t-end", "--refine", "--grids"})
    if (!dynamics_option && reader.arguments().has(option)) dynamics_option = option;
  if (dynamics_option && problem == Problem::statics)
    reader.problem(std::string(dynamics_option) + ": only dynamics studies step in time, and " +
                   decided_by + " makes this a statics study");
  if (!problem && dynamics_option) problem = Problem::dynamics;
  return problem;
}

/// Every option that only some kinds take.
void check_kind_options(OptionReader& reader, const std::string& kind) {
  const auto& a = reader.arguments();
  if (a.has("--budget-ms") && kind != "recommend")
    reader.problem("--budget-ms: only `rodlab study recommend` takes a time budget");
  if (a.has("--repeats") && kind != "work-precision" && kind != "recommend")
    reader.problem("--repeats: only work-precision and recommend time their runs");
  if (a.has("--refine") && kind == "stability")
    reader.problem("--refine: a stability study compares no solutions");
  if (const auto refine = reader.choice("--refine", kRefinements);
      refine && *refine != "time" && a.value("--reference") && *a.value("--reference") != "ida")
    reader.problem("--refine " + *refine + ": the reference is ida at a finer N (got --reference " +
                   *a.value("--reference") + ")");
  if (a.has("--grids") && kind == "stability")
    reader.problem("--grids: a stability study measures the scene's grid (solver.grid)");
  if (a.has("--moduli") && kind != "stability")
    reader.problem("--moduli: only `rodlab study stability` varies Young's modulus");
  for (const auto& o : kStudyControlOptions)
    if (a.has(o.name))
      reader.problem(std::string(o.name) + ": only `rodlab study control` takes it");
  for (const auto& o : kStudyLearningOptions)
    if (a.has(o.name))
      reader.problem(std::string(o.name) + ": only `rodlab study learning` takes it");
  if (kind == "recommend" && !a.has("--tol"))
    reader.problem("--tol: `rodlab study recommend` needs the tip error to reach, e.g. --tol 1e-6");
}

/// The schemes of the study: --schemes, else every scheme of the problem class.
std::vector<solvers::SchemeInfo> chosen_schemes(const OptionReader& reader, Problem problem) {
  const auto text = reader.text("--schemes");
  if (!text) return study::schemes_of(problem);
  std::vector<solvers::SchemeInfo> out;
  for (const auto& name : split_list(*text)) {
    const auto scheme = *solvers::find_scheme(name);
    bool seen = false;
    for (const auto& s : out) seen = seen || s.name == scheme.name;
    if (!seen) out.push_back(scheme);
  }
  return out;
}

std::string describe(const study::Candidate& c) {
  std::string out = c.scheme;
  if (!c.grid.empty()) out += " (" + c.grid + " grid)";
  out += ", N = " + std::to_string(c.nodes);
  if (c.dt) out += ", dt = " + io::format_number(*c.dt) + " s";
  out += ": tip error " + io::format_number(c.error) + " m, median wall time " +
         io::format_number(c.wall_time_s * 1e3) + " ms (" + std::to_string(c.repeats) +
         (c.repeats == 1 ? " run)" : " runs)");
  return out;
}

Json candidate_json(const std::optional<study::Candidate>& c) {
  if (!c) return nullptr;
  return {{"scheme", c->scheme},
          {"grid", c->grid.empty() ? Json(nullptr) : Json(c->grid)},
          {"nodes", c->nodes},
          {"dt", c->dt ? Json(*c->dt) : Json(nullptr)},
          {"error", c->error},
          {"wall_time_s", c->wall_time_s},
          {"repeats", c->repeats}};
}

/// The work-precision study.json in DIR when it was measured with the same settings.
std::optional<Json> reusable_measurements(const std::string& dir, const Json& settings) {
  const auto path = std::filesystem::path(dir) / "study.json";
  std::ifstream in(path);
  if (!in) return std::nullopt;
  try {
    const Json j = Json::parse(in);
    if (j.value("kind", "") == "work-precision" && j.value("settings", Json()) == settings)
      return j;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

/// The Pareto front of a work-precision sweep, one line per run on it.
void print_pareto(const study::Sweep& sweep, const std::vector<bool>& pareto,
                  const study::Settings& settings) {
  std::cout << study::sweep_table(sweep, true) << "\nPareto front (error against median wall time):\n";
  for (std::size_t i = 0; i < sweep.rows.size(); ++i)
    if (pareto[i])
      std::cout << "  "
                << study::scheme_label(sweep, sweep.rows[i].spec.scheme, sweep.rows[i].grid)
                << " N = " << sweep.rows[i].spec.nodes
                << (settings.problem == Problem::dynamics
                        ? " dt = " + io::format_number(sweep.rows[i].run.dt)
                        : std::string())
                << ": " << io::format_number(sweep.rows[i].error) << " m in "
                << io::format_number(sweep.rows[i].run.wall_time_s) << " s\n";
}

/// The one grid a dynamics study sweeps (the scene's solver.grid or --grids named it) when it is
/// not the corrected grid and the scene takes that (a Cosserat rod without actuators):
/// recommend's hint when nothing qualifies names both.
std::optional<std::string> grid_without_corrected(const study::Settings& settings) {
  if (settings.problem != Problem::dynamics || settings.grids.size() > 1) return std::nullopt;
  const std::string grid = settings.grids.empty() ? study::scene_grid(settings) : settings.grids[0];
  if (grid == "corrected" || solvers::dynamics::corrected_grid_refusal(
                                 solvers::dynamics::DynamicProblem::from_scene(settings.scene)))
    return std::nullopt;
  return grid;
}

/// `study recommend` on measured (or reused) work-precision rows: prints and writes
/// recommendation.json; true when a run meets the target.
bool recommend_and_write(const Json& wp, bool reused, const study::Settings& settings,
                         const std::string& dir, double target, std::optional<double> budget_ms) {
  const auto rec = study::recommend(wp["rows"], target, budget_ms,
                                    settings.refine == study::Refinement::grid
                                        ? study::ErrorMeasure::over_the_run
                                        : study::ErrorMeasure::at_end);
  const std::string budget_text =
      budget_ms ? " within " + io::format_number(*budget_ms) + " ms per run" : std::string();
  std::cout << "\nrecommendation for a tip error <= " << io::format_number(target) << " m"
            << budget_text << " (" << rec.candidates << " measured runs on this machine):\n";
  if (rec.best) {
    std::cout << "  " << describe(*rec.best) << '\n';
  } else {
    std::cout << "  nothing reaches " << io::format_number(target) << " m" << budget_text << '\n';
    if (rec.fastest_meeting_tol)
      std::cout << "  fastest that meets the tolerance: " << describe(*rec.fastest_meeting_tol)
                << '\n';
    else if (rec.most_accurate)
      std::cout << "  most accurate measured: " << describe(*rec.most_accurate) << '\n';
    const auto swept = grid_without_corrected(settings);
    std::cout << "  (refine with --nodes / --dt, or relax --tol / --budget-ms"
              << (swept ? "; or sweep the corrected grid too: --grids " + *swept + ",corrected"
                        : std::string())
              << ")\n";
  }
  const Json out{{"schema", "rodlab.study/1"},
                 {"kind", "recommend"},
                 {"scene", settings.scene.name},
                 {"command_line", settings.command_line},
                 {"tol", target},
                 {"budget_ms", budget_ms ? Json(*budget_ms) : Json(nullptr)},
                 {"measurements", reused ? "reused" : "measured"},
                 {"candidates", rec.candidates},
                 {"recommendation", candidate_json(rec.best)},
                 {"fastest_meeting_tol", candidate_json(rec.fastest_meeting_tol)},
                 {"most_accurate", candidate_json(rec.most_accurate)}};
  study::write_output(dir, "recommendation.json", out.dump(2) + "\n");
  std::cout << "written: " << dir << "/recommendation.json\n";
  return rec.best.has_value();
}

int run_sweep_kind(const std::string& kind, const study::Settings& settings,
                   const study::Executor& executor, const std::string& dir,
                   std::optional<double> target, std::optional<double> budget_ms) {
  const bool root = executor.processes->root();
  std::optional<Json> measured;
  if (kind == "recommend") measured = reusable_measurements(dir, study::settings_json(settings));
  Json wp;
  int status = kSolved;
  if (!measured) {
    if (executor.jobs > 1 && kind != "convergence" && root)
      std::cerr << "rodlab study: note: timings are measured with " << executor.jobs
                << " runs in parallel (--jobs); use --jobs 1 for uncontended timings\n";
    const auto sweep = study::run_sweep(settings, executor);
    if (!root) return kSolved;
    std::cout << "reference: " << sweep.reference.value("description", "") << "\n\n";
    if (kind == "convergence") {
      study::write_output(dir, "convergence.csv", study::convergence_csv(sweep));
      study::write_output(dir, "convergence_orders.csv", study::orders_csv(sweep));
      study::write_output(dir, "study.json",
                          study::sweep_json(sweep, settings, "convergence").dump(2) + "\n");
      std::cout << study::sweep_table(sweep, false) << '\n' << study::orders_table(sweep);
    } else {
      const auto pareto = study::pareto_front(sweep);
      wp = study::work_precision_json(sweep, pareto, settings);
      study::write_output(dir, "work_precision.csv", study::work_precision_csv(sweep, pareto));
      study::write_output(dir, "study.json", wp.dump(2) + "\n");
      if (kind == "work-precision") print_pareto(sweep, pareto, settings);
    }
    if (sweep.failed > 0) {
      std::cout << '\n' << sweep.failed << " run(s) did not converge (see the reason column)\n";
      status = kNotConverged;
    }
    std::cout << "\nwritten: " << dir << '\n';
    if (kind != "recommend") return status;
  } else {
    if (!root) return kSolved;
    wp = *measured;
    std::cout << "reusing the measurements in " << dir << "/study.json (same scene and settings)\n";
  }

  return recommend_and_write(wp, measured.has_value(), settings, dir, *target, budget_ms) ? status
                                                                                     : kNotConverged;
}

/// --nodes and --dt against the problem class and the refinement.
void check_grid_options(OptionReader& reader, std::optional<Problem> problem,
                        const std::optional<std::vector<int>>& nodes,
                        const std::optional<std::vector<double>>& dts, bool joint) {
  if (problem && nodes)
    for (const int n : *nodes)
      if (n < solvers::min_nodes(*problem)) {
        reader.problem(rodlab::format("--nodes: the {} schemes need N >= {} (got {})",
                                      solvers::to_string(*problem), solvers::min_nodes(*problem), n));
        break;
      }
  if (dts && dts->size() > 1 && joint)
    reader.problem("--dt: --refine joint starts from one step (dt at the coarsest N), got " +
                   std::to_string(dts->size()));
}

/// --grids: known grids, each taken by one of the schemes and by the scene (corrected: a
/// Cosserat rod without actuators); throws UsageError naming --grids.
std::vector<std::string> checked_grids(const std::vector<std::string>& names,
                                       const study::Settings& settings) {
  std::vector<std::string> grids;
  for (const auto& grid : names) {
    if (!solvers::dynamics::shooting_grid_from_name(grid))
      throw UsageError("--grids: unknown grid '" + grid + "'; the grids are euler, staggered, "
                       "corrected");
    if (std::find(grids.begin(), grids.end(), grid) != grids.end()) continue;
    bool taken = false;
    for (const auto& scheme : settings.schemes)
      taken = taken || study::takes_grid(scheme.name, grid);
    if (!taken)
      throw UsageError("--grids: " + grid + " is a grid of implicit-midpoint and bdf-alpha, "
                       "and no scheme of the study marches it");
    if (grid == "corrected")
      if (const auto reason = solvers::dynamics::corrected_grid_refusal(
              solvers::dynamics::DynamicProblem::from_scene(settings.scene)))
        throw UsageError("--grids: " + *reason);
    grids.push_back(grid);
  }
  return grids;
}

/// A dynamics study's run length: --t-end, else dynamics.t_end, else 1 s for stability; every
/// --dt must fit in it.
double run_length(const study::Settings& settings, const std::string& kind,
                  std::optional<double> t_end, const std::string& scene_path) {
  const auto& scene = settings.scene;
  const auto scene_t_end = scene.dynamics ? scene.dynamics->t_end : std::nullopt;
  double length = 0.0;
  if (t_end)
    length = *t_end;
  else if (scene_t_end)
    length = *scene_t_end;
  else if (kind == "stability")
    length = 1.0;
  else
    throw UsageError("--t-end: no run length; give --t-end T or set dynamics.t_end in " +
                     scene_path);
  for (const double dt : settings.dts)
    if (dt > length)
      throw UsageError("--dt: the time step " + io::format_number(dt) +
                       " s exceeds the run length " + io::format_number(length) + " s");
  return length;
}

/// `rodlab study stability`: runs, writes the two tables and study.json, prints the summary.
int run_stability_kind(const study::Settings& settings, const study::Executor& executor,
                       const std::string& dir) {
  const auto stab = study::run_stability(settings, executor);
  if (!executor.processes->root()) return kSolved;
  study::write_output(dir, "stability_explicit.csv", study::explicit_csv(stab));
  study::write_output(dir, "stability_implicit.csv", study::implicit_csv(stab));
  study::write_output(dir, "study.json", study::stability_json(stab, settings).dump(2) + "\n");
  std::cout << study::stability_table(stab) << "\nwritten: " << dir << '\n';
  return kSolved;
}

int run(const Invocation& inv) {
  const std::string kind = inv.args.positionals().front();
  if (kind == "control") return run_control_study_kind(inv);
  if (kind == "learning") return run_learning_study_kind(inv);
  OptionReader reader(inv.args);
  bool kind_ok = false;
  for (const auto k : kKinds) kind_ok = kind_ok || k == kind;
  if (!kind_ok) {
    std::vector<std::string> kinds(kKinds.begin(), kKinds.end());
    reader.problem("KIND: unknown study '" + kind + "'; the studies are: " + io::join(kinds));
  }
  SolveOptions options;
  options.scene_path = inv.args.positionals().back();
  options.overrides = read_overrides(reader);
  const auto tol = reader.positive("--tol");
  const auto nodes = reader.integers("--nodes", 2);
  const auto dts = reader.positives("--dt");
  const auto t_end = reader.positive("--t-end");
  const auto budget = reader.positive("--budget-ms");
  const auto repeats = reader.integer("--repeats", 1);
  const auto moduli = reader.positives("--moduli");
  const auto jobs = reader.integer("--jobs", 1);
  const auto out_dir = read_out_dir(reader);
  std::optional<Problem> problem;
  if (kind_ok) {
    problem = check_problem_class(reader, kind);
    check_kind_options(reader, kind);
  }
  check_grid_options(reader, problem, nodes, dts, inv.args.value("--refine") == "joint");
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);

  study::Settings settings;
  settings.scene_path = options.scene_path;
  for (const auto& text : inv.args.values(kSetOption.name)) settings.overrides.push_back(text);
  settings.scene = scene;
  settings.problem = problem.value_or(Problem::statics);
  settings.schemes = chosen_schemes(reader, settings.problem);
  settings.reference = inv.args.value("--reference");
  if (settings.schemes.empty())
    throw UsageError("--schemes: no " +
                     std::string(solvers::to_string(settings.problem)) + " scheme to study");
  if (nodes) settings.nodes = *nodes;
  if (dts) settings.dts = *dts;
  if (inv.args.value("--refine") == "joint") settings.refine = study::Refinement::joint;
  if (inv.args.value("--refine") == "grid") settings.refine = study::Refinement::grid;
  if (moduli) settings.moduli = *moduli;
  const bool recommend = kind == "recommend";
  settings.tol = (!recommend && tol) ? *tol : scene.solver.tol;
  settings.repeats = (kind == "work-precision" || recommend) ? repeats.value_or(kDefaultRepeats) : 1;
  settings.command_line = inv.command_line;
  if (settings.problem == Problem::dynamics)
    settings.t_end = run_length(settings, kind, t_end, options.scene_path);
  if (const auto grids = inv.args.value("--grids"))
    settings.grids = checked_grids(split_list(*grids), settings);
  else if (kind == "work-precision" || recommend)
    settings.grids = study::trade_grids(settings);
  const std::string dir =
      out_dir ? out_dir->string()
              : "out/study-" + std::string(recommend ? "work-precision" : kind);

  // Everything is checked: from here on the study runs (and MPI, if launched by mpirun).
  study::Processes processes;
  ProgressLine progress("study " + kind, "runs", !reader.flag(kQuietOption.name) && processes.root());
  study::Executor executor{jobs.value_or(1), &processes, {}};
  if (progress.active())
    executor.progress = [&](long done, long total) { progress.update(done, total); };
  if (kind != "stability")
    return run_sweep_kind(kind, settings, executor, dir, tol, budget);

  return run_stability_kind(settings, executor, dir);
}

}  // namespace

const Command& study_command() {
  static const Command command{
      "study",
      "KIND SCENE [options]",
      "convergence, work-precision, stability studies; scheme recommendation; Table 4.1 (control, "
      "learning)",
      "KIND is one of:\n"
      "  convergence      error against the reference as the nodes (or dt) are refined; observed\n"
      "                   order (DIR/convergence.csv, convergence_orders.csv, study.json);\n"
      "                   dynamics: dt at each N, or with --refine joint N and dt together\n"
      "  work-precision   error against median wall time for each scheme and resolution, and\n"
      "                   the Pareto front (DIR/work_precision.csv, study.json)\n"
      "  stability        largest stable time step of the explicit scheme against E and N;\n"
      "                   where the implicit schemes fail, below and above dt auto\n"
      "                   (DIR/stability_explicit.csv, stability_implicit.csv, study.json)\n"
      "  recommend        the fastest measured scheme and resolution that meets --tol (a tip\n"
      "                   error in m) within --budget-ms; reuses DIR's work-precision data when\n"
      "                   it was measured with the same settings (DIR/recommendation.json)\n"
      "  control          the thesis' Table 4.1: NLSQ-MPC on implicit-midpoint (one column per\n"
      "                   --dt-control) and on the Kirchhoff rod (variational), LQR and iLQR, on\n"
      "                   dynamic reach, static reach-and-hold and middle-circle tracking at\n"
      "                   every --horizons (DIR/table.csv, table.md, study.json, runs/*.json,\n"
      "                   figures/ with python3-matplotlib); the options marked control: are\n"
      "                   its own, --nodes takes one N (docs/control.md)\n"
      "  learning         Table 4.1's DDPG and GPS columns and learning curves: rodlab train\n"
      "                   and rodlab control --controller policy per algorithm, task (--tasks\n"
      "                   reach-one,reach-any,track), seed (--seeds K) and 1/4, 1/2, 1 of the\n"
      "                   task's sample budget (--budget-scale X); --jobs J environments per\n"
      "                   training; --targets, --seed: the reach-any evaluation targets\n"
      "                   (DIR/table.md, study.json, policies/, results/, figures/;\n"
      "                   docs/learning.md)\n"
      "A study is a statics study unless its schemes, its reference, --dt, --t-end, --refine or\n"
      "--grids make it a dynamics one (stability always is). Without --schemes, every scheme of\n"
      "the class takes part. Without --grids, a dynamics study runs on the scene's grid; where\n"
      "the scene names none, work-precision and recommend sweep the staggered grid and, for a\n"
      "Cosserat rod without actuators, the corrected grid too. The options and the scene are\n"
      "checked before anything runs.\n"
      "--jobs N runs N cases at once; under `mpirun -n K` the cases are split across the ranks\n"
      "and rank 0 writes the merged outputs (docs/studies.md).\n"
      "\n"
      "Exit status: 0 the study ran; 1 some runs failed or (control) timed out (the report says\n"
      "which), or recommend found nothing that meets --tol within the budget; 2 bad input or\n"
      "usage (nothing is written).\n",
      kPositionals,
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
