// The data sets and figure specs of `rodlab study control` (drawn by validation/make_figures.py,
// in the study's directory and in the validation report): error and real-time ratio against
// the horizon per task, as the thesis' figures 4.4-4.5 (dynamic reach), 4.7-4.8 (static reach)
// and 4.10-4.11 (trajectory), and the traced middle circle of every column.
#include <string>

#include "studies/control_study.hpp"

// Figure specs are written with designated initializers; the fields left out keep their
// defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace rodlab::validation::study {
namespace {

/// How each task's figures read (thesis 4.4.1-4.4.3): its title, the error it plots, and the
/// thesis' figure numbers for the error and the real-time ratio.
struct TaskFigures {
  const char* task;
  const char* title;
  const char* error_column;
  const char* error_label;
  const char* error_figure;
  const char* ratio_figure;
};
constexpr TaskFigures kTaskFigures[] = {
    {"reach", "dynamic reach", "min_error_pct_L",
     "lowest tip error, mean over the targets [% of L]", "4.4", "4.5"},
    {"hold", "static reach and hold", "final_error_pct_L",
     "final tip error, mean over the targets [% of L]", "4.7", "4.8"},
    {"track", "middle-circle tracking", "mean_error_pct_L", "mean tip error [% of L]", "4.10",
     "4.11"},
};

const TaskFigures& task_figures(const std::string& task) {
  for (const auto& t : kTaskFigures)
    if (task == t.task) return t;
  return kTaskFigures[2];
}

/// Rows against the horizon; LQR's single run (no horizon) repeated at every horizon, a flat line.
DataSet horizon_data(const ControlStudy& study) {
  DataSet d{.name = "control_study_horizon",
            .description = "rodlab study control: every run's successes, errors (% of L) and "
                           "real-time ratio against the horizon H (LQR, which has none, repeated "
                           "at every H)",
            .columns = {"series", "task", "column", "horizon", "successes", "episodes",
                        "mean_error_pct_L", "final_error_pct_L", "min_error_pct_L",
                        "real_time_ratio_mean",
                        "real_time_ratio_max", "wall_time_s", "status"}};
  for (const auto& r : study.rows)
    for (const int h : study.settings.horizons) {
      if (r.horizon != 0 && r.horizon != h) continue;
      d.add_row({r.task + ": " + r.column.name, r.task, r.column.name, h, r.successes, r.episodes,
                 r.mean_error_pct_L, r.final_error_pct_L, r.min_error_pct_L, r.real_time_ratio_mean,
                 r.real_time_ratio_max, r.wall_time_s, r.status});
    }
  for (const auto& task : study.settings.tasks) {
    const TaskFigures& t = task_figures(task);
    const std::string title = t.title;
    d.figures.push_back(
        {.name = "control_study_error_" + task,
         .kind = "semilogy",
         .x = "horizon",
         .y = {t.error_column},
         .series = "series",
         .title = "Error against the horizon: " + title,
         .xlabel = "horizon H [control steps]",
         .ylabel = t.error_label,
         .caption = "Tip error (" + std::string(t.error_label) + ") against the horizon, " +
                    title + ", one curve per column of Table 4.1 (as the thesis' figure " +
                    t.error_figure + ")." +
                    (task == "track" ? " Table 4.1's NLSQ Implicit: 3.45 % to 6.90 % of L."
                                     : " Success: below 5 % of L."),
         .style = "lines+markers",
         .select = task + ":"});
    d.figures.push_back({.name = "control_study_real_time_" + task,
                         .kind = "semilogy",
                         .x = "horizon",
                         .y = {"real_time_ratio_mean"},
                         .series = "series",
                         .title = "Real-time ratio against the horizon: " + title,
                         .xlabel = "horizon H [control steps]",
                         .ylabel = "controller time / dt_c (mean)",
                         .caption = "Mean real-time ratio (controller wall time per control step "
                                    "over dt_c; below 1 keeps up with real time) against the "
                                    "horizon, " + title + " (as the thesis' figure " +
                                    t.ratio_figure + "); shared machine, timings indicative.",
                         .style = "lines+markers",
                         .select = task + ":"});
  }
  return d;
}

/// The largest horizon with a finished track run (LQR's has none).
int default_trace_horizon(const ControlStudy& study) {
  int h = 0;
  for (const auto& r : study.rows)
    if (r.task == "track" && r.result && r.horizon > h) h = r.horizon;
  return h;
}

/// The tips of every column's track run at horizon h against the target circle, in mm.
DataSet circle_data(const ControlStudy& study, int h) {
  DataSet d{.name = "control_study_circle",
            .description = "rodlab study control: the tip's x-y path of every column's track run "
                           "at H = " + std::to_string(h) + ", and the target circle [mm]",
            .columns = {"series", "x_mm", "y_mm"}};
  bool target_done = false;
  for (const auto& r : study.rows) {
    if (r.task != "track" || r.horizon != h || !r.result) continue;
    const auto& s = r.result->series;
    if (!target_done)
      for (const auto& p : s.target) d.add_row({"target circle", 1e3 * p.x(), 1e3 * p.y()});
    target_done = true;
    for (const auto& p : s.tip) d.add_row({r.column.name, 1e3 * p.x(), 1e3 * p.y()});
  }
  d.figures.push_back({.name = "control_study_circle",
                       .kind = "shape",
                       .x = "x_mm",
                       .y = {"y_mm"},
                       .series = "series",
                       .title = "The traced middle circle, H = " + std::to_string(h),
                       .xlabel = "tip x [mm]",
                       .ylabel = "tip y [mm]",
                       .caption = "The tip's path seen from above (x-y) while tracking the "
                                  "middle circle (radius 1 cm) at H = " + std::to_string(h) +
                                  ", every column of Table 4.1 that tracks, against the target "
                                  "circle at the control instants.",
                       .style = "lines"});
  return d;
}

}  // namespace

std::vector<DataSet> control_study_data(const ControlStudy& study, int trace_horizon) {
  std::vector<DataSet> out{horizon_data(study)};
  const int h = trace_horizon > 0 ? trace_horizon : default_trace_horizon(study);
  if (h > 0) out.push_back(circle_data(study, h));
  return out;
}

}  // namespace rodlab::validation::study
