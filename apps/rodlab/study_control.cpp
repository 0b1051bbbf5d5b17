#include "study_control.hpp"

#include <algorithm>
#include <iostream>
#include <string>

#include "rodlab/io/text_format.hpp"

#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "progress_line.hpp"
#include "study_support.hpp"
#include "studies/control_study.hpp"

namespace rodlab::cli {

namespace study = validation::study;

namespace {

/// The settings from the command line (problems recorded in `reader`).
study::ControlStudySettings read_settings(OptionReader& reader) {
  study::ControlStudySettings s;
  for (const auto name : kOptionsNotForControl)
    if (reader.arguments().has(name))
      reader.problem(std::string(name) + ": not an option of `rodlab study control`");
  check_names(reader, "--controllers", study::kControlColumnKinds);
  check_names(reader, "--tasks", study::kControlStudyTasks);
  if (const auto v = reader.names("--controllers")) s.columns = *v;
  if (const auto v = reader.names("--tasks")) s.tasks = *v;
  if (const auto v = reader.integers("--horizons", 1)) s.horizons = *v;
  if (const auto v = reader.positives("--dt-control")) {
    s.dt_controls = *v;
    if (std::find(s.columns.begin(), s.columns.end(), "nlsq-implicit") == s.columns.end())
      reader.problem("--dt-control: only the nlsq-implicit columns take a list of control steps "
                     "(add nlsq-implicit to --controllers)");
  }
  if (const auto v = reader.integer("--targets", 1)) s.targets = *v;
  if (const auto v = reader.integer("--seed", 0)) s.seed = static_cast<unsigned>(*v);
  if (const auto v = reader.positive("--max-wall-time")) s.max_wall_time = *v;
  const int min_nodes = solvers::min_nodes(solvers::Problem::dynamics);
  if (const auto v = reader.integers("--nodes", min_nodes)) {
    if (v->size() != 1)
      reader.problem("--nodes: `study control` takes one node count (got " +
                     std::to_string(v->size()) + ")");
    else
      s.nodes = v->front();
  }
  return s;
}

void print_row(const study::ControlStudyRow& r) {
  std::cout << "  " << r.column.name << ", " << r.task
            << (r.horizon > 0 ? ", H = " + std::to_string(r.horizon) : std::string()) << ": "
            << r.status << ", " << r.successes << "/" << r.episodes << " successful, mean error "
            << io::format_number(r.mean_error_pct_L) << " % of L, real-time ratio "
            << io::format_number(r.real_time_ratio_mean) << " mean, "
            << io::format_number(r.wall_time_s) << " s";
  if (r.status != "done" && !r.reason.empty()) std::cout << " (" << r.reason << ")";
  std::cout << '\n' << std::flush;
}

}  // namespace

int run_control_study_kind(const Invocation& inv) {
  OptionReader reader(inv.args);
  SolveOptions options;
  options.scene_path = inv.args.positionals().back();
  options.overrides = read_overrides(reader);
  study::ControlStudySettings s = read_settings(reader);
  const auto out_dir = read_out_dir(reader);
  const bool quiet = reader.flag(kQuietOption.name);
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  if (std::find(s.tasks.begin(), s.tasks.end(), "track") != s.tasks.end() &&
      !(scene.control && scene.control->trajectory))
    throw UsageError("--tasks: track needs control.trajectory in " + options.scene_path +
                     " (or --tasks reach,hold)");
  if (scene.actuators.empty())
    throw UsageError("SCENE: " + options.scene_path + " has no actuators to control");
  s.scene_path = options.scene_path;
  for (const auto& text : inv.args.values(kSetOption.name)) s.overrides.push_back(text);
  s.command_line = inv.command_line;
  const std::string dir = out_dir ? out_dir->string() : "out/study-control";

  std::cout << "Table 4.1 study: " << study::control_columns(s).size() << " columns, "
            << s.tasks.size() << " tasks, " << s.horizons.size() << " horizons, N = " << s.nodes
            << '\n';
  ProgressLine progress("study control", "runs", !quiet);
  const study::ControlStudy result = study::run_control_study(
      s, [&](const auto& row, long done, long total) {
        progress.finish();  // the row goes where the line was
        print_row(row);
        progress.update(done, total);
      });
  study::write_control_study(result, dir);
  std::cout << '\n' << study::control_table_markdown(result) << "\nwritten: " << dir << '\n';
  if (!inv.args.has("--no-figures")) draw_study_figures(study::control_study_data(result), dir);
  const bool all_done = std::all_of(result.rows.begin(), result.rows.end(), [](const auto& r) {
    return r.status == "done";
  });
  return all_done ? kSolved : kNotConverged;
}

}  // namespace rodlab::cli
