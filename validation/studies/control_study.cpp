#include "studies/control_study.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "rodlab/check.hpp"
#include "rodlab/io/result_writer.hpp"
#include "rodlab/io/scene_loader.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/control/control_run.hpp"

#include "report/report.hpp"

// Data sets and figure specs are written with designated initializers; the fields left out keep
// their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace rodlab::validation::study {
namespace {

namespace fs = std::filesystem;

bool is_one_of(const std::string& name, const auto& list) {
  return std::find(std::begin(list), std::end(list), name) != std::end(list);
}

/// "0.05" for names and labels.
std::string number(double v) { return io::format_number(v); }

/// The study's scene for a column: the scene file with --set, and rod.model = kirchhoff for
/// the Kirchhoff column (thesis 4.4: "NLSQ Kirchhoff", the variational scheme on the Kirchhoff
/// rod of 3.3).
scene::Scene column_scene(const ControlStudySettings& s, const ControlColumn& c) {
  std::vector<io::Override> overrides;
  for (const auto& o : s.overrides) overrides.push_back(io::parse_override(o));
  if (c.kirchhoff) overrides.push_back(io::parse_override("rod.model=kirchhoff"));
  return io::load_scene(s.scene_path, overrides);
}

/// The plant's solver as `rodlab control` sets it (cmd_control.cpp read_plant): the scene's
/// solver tolerance and iterations and scheme options, dynamics.dt when set, the column's scheme.
solvers::dynamics::DynamicSolveOptions plant_solver(const scene::Scene& scene,
                                                    const ControlStudySettings& s,
                                                    const ControlColumn& c) {
  solvers::dynamics::DynamicSolveOptions o;
  o.scheme = c.scheme;
  o.nodes = s.nodes;
  o.tol = scene.solver.tol;
  o.max_iterations = scene.solver.max_iterations;
  solvers::dynamics::apply_scene_options(scene, o);
  if (scene.dynamics && scene.dynamics->dt) o.dt = *scene.dynamics->dt;
  o.max_wall_time = s.max_wall_time;
  return o;
}

scene::ControlTask task_of(const std::string& task) {
  return task == "reach" ? scene::ControlTask::reach
         : task == "hold" ? scene::ControlTask::hold
                          : scene::ControlTask::track;
}

/// The task settings of one run: the scene's control section (weights, trajectory) with the
/// thesis' success criterion and step limit (4.4.1) and the study's targets.
scene::Control run_control_settings(const scene::Scene& scene, const ControlStudySettings& s,
                                    const ControlColumn& c, const std::string& task, int horizon) {
  scene::Control control = scene.control.value_or(scene::Control{});
  control.task = task_of(task);
  control.horizon = std::max(1, horizon);
  control.dt_control = c.dt_control;
  control.model_scheme.reset();
  if (!c.model_scheme.empty()) control.model_scheme = c.model_scheme;
  control.threshold = kThesisThreshold;
  control.max_steps = kThesisMaxSteps;
  control.seed = s.seed;
  control.targets.clear();
  control.target_count = s.targets;
  return control;
}

std::string file_stem(const ControlColumn& c, const std::string& task, int horizon) {
  std::string stem = c.kind;
  if (c.kind == "nlsq-implicit") stem += "-dt" + number(c.dt_control);
  return stem + "_" + task + (horizon > 0 ? "_H" + std::to_string(horizon) : "");
}

/// The row of a finished run: its summary, and its status ("timed out" when the wall-time
/// guard stopped it: common/deadline.hpp's message).
void fill_from_result(ControlStudyRow& row, result::ControlResult r, double length) {
  // every target counts, also those a stopped run did not get to (track: one pass)
  const std::size_t planned = row.task == "track" ? 1 : r.targets.points.size();
  row.episodes = static_cast<int>(std::max(r.episodes.size(), planned));
  double final_sum = 0.0, min_sum = 0.0;
  int stepped = 0;  // episodes with a control step (one that could not start has no error)
  for (const auto& e : r.episodes) {
    row.successes += e.success ? 1 : 0;
    if (e.steps == 0) continue;
    final_sum += e.final_error;
    min_sum += e.min_error;
    ++stepped;
  }
  if (stepped > 0) {
    row.final_error_pct_L = 100.0 * final_sum / stepped / length;
    row.min_error_pct_L = 100.0 * min_sum / stepped / length;
  }
  row.mean_error_pct_L = r.series.error.empty() ? kNotMeasured : r.summary.mean_error_pct_L;
  row.real_time_ratio_mean = r.series.error.empty() ? kNotMeasured : r.summary.real_time_ratio_mean;
  row.real_time_ratio_max = r.series.error.empty() ? kNotMeasured : r.summary.real_time_ratio_max;
  row.wall_time_s = r.summary.wall_time_s;
  row.converged = r.converged;
  row.reason = r.reason.value_or("");
  const bool timed_out = !r.converged && row.reason.find("wall-time limit") != std::string::npos;
  row.status = timed_out ? "timed out" : r.converged ? "done" : "failed";
  row.result = std::move(r);
}

/// One run of the study. The wall-time limit also covers drawing the targets (run_control
/// draws dynamic-workspace targets before its own guard starts), so a run takes at most about
/// twice the limit.
ControlStudyRow run_one(const scene::Scene& scene, const ControlStudySettings& s,
                        const ControlColumn& c, const std::string& task, int horizon) {
  ControlStudyRow row{.column = c, .task = task, .horizon = horizon};
  solvers::control::ControlRunOptions options;
  options.controller = c.controller;
  options.control = run_control_settings(scene, s, c, task, horizon);
  options.solver = plant_solver(scene, s, c);
  try {
    const solvers::DeadlineScope deadline(s.max_wall_time);
    fill_from_result(row, solvers::control::run_control(scene, options), scene.rod.length);
    row.run_file = "runs/" + file_stem(c, task, horizon) + ".json";
  } catch (const solvers::WallTimeExceeded& e) {  // while drawing the targets
    row.status = "timed out";
    row.reason = std::string(e.what()) + " (drawing the targets)";
  } catch (const std::exception& e) {  // a run that cannot start: reported, the study goes on
    row.status = "failed";
    row.reason = e.what();
  }
  return row;
}

}  // namespace

std::vector<ControlColumn> control_columns(const ControlStudySettings& s) {
  std::vector<ControlColumn> out;
  for (const auto& kind : s.columns)
    RODLAB_THROW_UNLESS(is_one_of(kind, kControlColumnKinds),
                        "--controllers: unknown column '{}' (nlsq-implicit, nlsq-kirchhoff, lqr, "
                        "ilqr, nlsq-kirchhoff-variational)",
                        kind);
  // Table 4.1's order, whatever the order asked for.
  for (const std::string kind : kControlColumnKinds) {
    if (!is_one_of(kind, s.columns)) continue;
    if (kind == "nlsq-implicit") {
      for (const double dt : s.dt_controls)
        out.push_back({"nlsq-implicit dt=" + number(dt), kind, "nlsq-mpc", "implicit-midpoint",
                       "", false, dt});
      continue;
    }
    const double dt = kSingleColumnDtControl;
    if (kind == "nlsq-kirchhoff")
      out.push_back({kind, kind, "nlsq-mpc", "variational", "implicit-midpoint", true, dt});
    else if (kind == "nlsq-kirchhoff-variational")
      out.push_back({kind, kind, "nlsq-mpc", "variational", "", true, dt});
    else
      out.push_back({kind, kind, kind, "implicit-midpoint", "", false, dt});
  }
  return out;
}

ControlStudy run_control_study(const ControlStudySettings& s, const ControlProgress& progress) {
  ControlStudy study{.settings = s};
  long total = 0;  // LQR has no horizon: one run per task (0 in the table's horizon column)
  for (const auto& column : control_columns(s))
    total += static_cast<long>(s.tasks.size() * (column.controller == "lqr" ? 1 : s.horizons.size()));
  for (const auto& column : control_columns(s)) {
    const scene::Scene scene = column_scene(s, column);
    study.scene_name = scene.name;
    study.rod_length = scene.rod.length;
    for (const auto& task : s.tasks) {
      // LQR has no horizon: one run per task (0 in the table's horizon column).
      const std::vector<int> horizons = column.controller == "lqr" ? std::vector<int>{0}
                                                                   : s.horizons;
      for (const int h : horizons) {
        study.rows.push_back(run_one(scene, s, column, task, h));
        if (progress) progress(study.rows.back(), static_cast<long>(study.rows.size()), total);
      }
    }
  }
  return study;
}

namespace {

const char* kCsvHeader =
    "column,controller,scheme,model_scheme,kirchhoff,dt_control,task,horizon,status,successes,episodes,"
    "mean_error_pct_L,final_error_pct_L,min_error_pct_L,real_time_ratio_mean,real_time_ratio_max,wall_time_s,"
    "converged,reason,run_file\n";

}  // namespace

std::string control_table_csv(const ControlStudy& study) {
  std::string out = kCsvHeader;
  for (const auto& r : study.rows)
    out += csv_text(r.column.name) + "," + r.column.controller + "," + r.column.scheme + "," +
           r.column.model_scheme + "," + (r.column.kirchhoff ? "1" : "0") + "," + csv_number(r.column.dt_control) + "," +
           r.task + "," + std::to_string(r.horizon) + "," + csv_text(r.status) + "," +
           std::to_string(r.successes) + "," + std::to_string(r.episodes) + "," +
           csv_number(r.mean_error_pct_L) + "," + csv_number(r.final_error_pct_L) + "," + csv_number(r.min_error_pct_L) + "," +
           csv_number(r.real_time_ratio_mean) + "," + csv_number(r.real_time_ratio_max) + "," +
           csv_number(r.wall_time_s) + "," + (r.converged ? "1" : "0") + "," +
           csv_text(r.reason) + "," + r.run_file + "\n";
  return out;
}

namespace {

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

Json settings_json(const ControlStudySettings& s) {
  return {{"scene_path", s.scene_path},       {"overrides", s.overrides},
          {"columns", s.columns},             {"horizons", s.horizons},
          {"dt_control", s.dt_controls},      {"tasks", s.tasks},
          {"targets", s.targets},             {"seed", s.seed},
          {"nodes", s.nodes},                 {"max_wall_time_s", s.max_wall_time},
          {"threshold", kThesisThreshold},    {"max_steps", kThesisMaxSteps}};
}

}  // namespace

Json control_study_json(const ControlStudy& study) {
  Json rows = Json::array();
  for (const auto& r : study.rows)
    rows.push_back({{"column", r.column.name},
                    {"controller", r.column.controller},
                    {"scheme", r.column.scheme},
                    {"model_scheme", r.column.model_scheme.empty() ? Json(nullptr)
                                                                   : Json(r.column.model_scheme)},
                    {"kirchhoff", r.column.kirchhoff},
                    {"dt_control", r.column.dt_control},
                    {"task", r.task},
                    {"horizon", r.horizon == 0 ? Json(nullptr) : Json(r.horizon)},
                    {"status", r.status},
                    {"successes", r.successes},
                    {"episodes", r.episodes},
                    {"mean_error_pct_L", number_or_null(r.mean_error_pct_L)},
                    {"final_error_pct_L", number_or_null(r.final_error_pct_L)},
                    {"min_error_pct_L", number_or_null(r.min_error_pct_L)},
                    {"real_time_ratio_mean", number_or_null(r.real_time_ratio_mean)},
                    {"real_time_ratio_max", number_or_null(r.real_time_ratio_max)},
                    {"wall_time_s", r.wall_time_s},
                    {"converged", r.converged},
                    {"reason", r.reason.empty() ? Json(nullptr) : Json(r.reason)},
                    {"run_file", r.run_file.empty() ? Json(nullptr) : Json(r.run_file)}});
  return {{"schema", "rodlab.study/1"},
          {"kind", "control"},
          {"scene", study.scene_name},
          {"rod_length", study.rod_length},
          {"command_line", study.settings.command_line},
          {"settings", settings_json(study.settings)},
          {"rows", rows}};
}

void write_control_study(const ControlStudy& study, const std::string& dir) {
  for (const auto& r : study.rows)
    if (r.result && !r.run_file.empty()) {
      fs::create_directories(fs::path(dir) / "runs");
      io::write_result(fs::path(dir) / r.run_file, *r.result);
    }
  const std::vector<DataSet> data = control_study_data(study);
  for (const auto& d : data) write_output((fs::path(dir) / "data").string(), d.name + ".csv", d.to_csv());
  write_output(dir, "figures.json", figure_index_json(data) + "\n");
  write_output(dir, "table.csv", control_table_csv(study));
  write_output(dir, "table.md", control_table_markdown(study));
  write_output(dir, "study.json", control_study_json(study).dump(2) + "\n");
}

}  // namespace rodlab::validation::study
