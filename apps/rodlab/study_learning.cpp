#include "study_learning.hpp"

#include <algorithm>
#include <iostream>
#include <string>

#include "rodlab/io/text_format.hpp"

#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "progress_line.hpp"
#include "study_support.hpp"
#include "studies/learning_study.hpp"

namespace rodlab::cli {

namespace study = validation::study;

namespace {

/// The options of the other study kinds, refused here.
constexpr std::string_view kNotForLearning[] = {
    "--schemes",  "--dt",         "--t-end",   "--refine",     "--reference", "--tol",
    "--budget-ms", "--repeats",   "--moduli",  "--controllers", "--horizons",  "--dt-control",
    "--nodes"};

study::LearningStudySettings read_settings(OptionReader& reader) {
  study::LearningStudySettings s;
  for (const auto name : kNotForLearning)
    if (reader.arguments().has(name))
      reader.problem(std::string(name) + ": not an option of `rodlab study learning`");
  check_names(reader, "--algorithms", study::kLearningAlgorithms);
  check_names(reader, "--tasks", study::kLearningTasks);
  if (const auto v = reader.names("--algorithms")) s.algorithms = *v;
  if (const auto v = reader.names("--tasks")) s.tasks = *v;
  if (const auto v = reader.integer("--seeds", 1)) s.seeds = *v;
  if (const auto v = reader.positive("--budget-scale")) s.budget_scale = *v;
  if (const auto v = reader.integer("--jobs", 1)) s.jobs = *v;
  if (const auto v = reader.integer("--targets", 1)) s.targets = *v;
  if (const auto v = reader.integer("--seed", 0)) s.target_seed = static_cast<unsigned>(*v);
  if (const auto v = reader.positive("--max-wall-time")) s.max_wall_time = *v;
  return s;
}

void print_row(const study::LearningStudyRow& r) {
  std::cout << "  " << r.algorithm << ", " << r.task << ", seed " << r.seed << ", " << r.samples
            << " samples: " << r.status;
  if (r.status == "done" || r.train_wall_time_s > 0.0)
    std::cout << ", " << io::format_number(r.success_pct) << " % reached, best error "
              << io::format_number(r.best_error_pct_L) << " % of L, mean error "
              << io::format_number(r.mean_error_pct_L) << " % of L, trained in "
              << io::format_number(r.train_wall_time_s) << " s";
  if (!r.reason.empty()) std::cout << " (" << r.reason << ")";
  std::cout << '\n' << std::flush;
}

}  // namespace

int run_learning_study_kind(const Invocation& inv) {
  OptionReader reader(inv.args);
  SolveOptions options;
  options.scene_path = inv.args.positionals().back();
  options.overrides = read_overrides(reader);
  study::LearningStudySettings s = read_settings(reader);
  const auto out_dir = read_out_dir(reader);
  const bool quiet = reader.flag(kQuietOption.name);
  reader.finish();
  const scene::Scene scene = load_checked_scene(options);
  if (scene.actuators.empty())
    throw UsageError("SCENE: " + options.scene_path + " has no actuators to learn to control");
  if (std::find(s.tasks.begin(), s.tasks.end(), "track") != s.tasks.end() &&
      !(scene.control && scene.control->trajectory))
    throw UsageError("--tasks: track is evaluated on control.trajectory, which " +
                     options.scene_path + " lacks (or --tasks reach-one,reach-any)");
  s.scene_path = options.scene_path;
  for (const auto& text : inv.args.values(kSetOption.name)) s.overrides.push_back(text);
  s.command_line = inv.command_line;
  const std::string dir = out_dir ? out_dir->string() : "out/study-learning";

  std::cout << "learning study: " << s.algorithms.size() << " algorithms, " << s.tasks.size()
            << " tasks, " << s.seeds << " seeds, " << s.fractions.size()
            << " budgets each (curve points)\n";
  ProgressLine progress("study learning", "runs", !quiet);
  const study::LearningStudy result = study::run_learning_study(
      s, dir, [&](const auto& row, long done, long total) {
        progress.finish();  // the row goes where the line was
        print_row(row);
        progress.update(done, total);
      });
  study::write_learning_study(result, dir);
  std::cout << '\n' << study::learning_table_markdown(result) << "\nwritten: " << dir << '\n';
  if (!inv.args.has("--no-figures")) draw_study_figures(study::learning_study_data(result), dir);
  const bool all_done = std::all_of(result.rows.begin(), result.rows.end(),
                                    [](const auto& r) { return r.status == "done"; });
  return all_done ? kSolved : kNotConverged;
}

}  // namespace rodlab::cli
