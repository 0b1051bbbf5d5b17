// The Markdown Table 4.1 of `rodlab study control`: the thesis' table (section 4.4, Table 4.1,
// quoted exactly) beside ours, one table per horizon.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "rodlab/io/text_format.hpp"

#include "studies/control_study.hpp"

namespace rodlab::validation::study {
namespace {

/// Table 4.1 of the thesis, the optimisation columns (DDPG and GPS are learning, issue #15):
/// {real-time, dynamic reach (any point), static reach, trajectory}. The column's step: NLSQ
/// Implicit at 0.01, 0.05, 0.1 s; the others have none in the table.
struct ThesisColumn {
  const char* kind;
  double dt;  ///< 0: any (the table gives none)
  const char* title;  ///< the column's heading
  const char* real_time;
  const char* dynamic_reach;
  const char* static_reach;
  const char* trajectory;
};
constexpr ThesisColumn kThesisTable41[] = {
    {"nlsq-implicit", 0.01, "NLSQ Implicit, dt = 0.01 s", "No", "10/10", "10/10", "3.45 %"},
    {"nlsq-implicit", 0.05, "NLSQ Implicit, dt = 0.05 s", "No", "10/10", "10/10", "4.36 %"},
    {"nlsq-implicit", 0.1, "NLSQ Implicit, dt = 0.1 s", "0.95", "10/10", "10/10", "6.90 %"},
    {"nlsq-kirchhoff", 0.0, "NLSQ Kirchhoff", "No", "9/10", "10/10", "1.64 %"},
    {"lqr", 0.0, "LQR", "No", "9/10", "10/10", "2.03 %"},
    {"ilqr", 0.0, "iLQR", "No", "9/10", "10/10", "3.38 %"},
};

const ThesisColumn* thesis_column(const ControlColumn& c) {
  // the thesis' Kirchhoff setup and ours (another model) answer the same column
  const std::string kind = c.kind == "nlsq-kirchhoff-variational" ? "nlsq-kirchhoff" : c.kind;
  for (const auto& t : kThesisTable41)
    if (kind == t.kind && (t.dt == 0.0 || std::abs(c.dt_control - t.dt) < 1e-12)) return &t;
  return nullptr;
}

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

/// The run of a column on a task at horizon h (LQR's single run at any h); nullptr if none.
const ControlStudyRow* find_row(const ControlStudy& study, const ControlColumn& c,
                                const std::string& task, int h) {
  for (const auto& r : study.rows)
    if (r.column.name == c.name && r.task == task && (r.horizon == h || r.horizon == 0))
      return &r;
  return nullptr;
}

/// Ours: successes/episodes (reach, hold) or the mean error in % of L (track); the status when
/// the run did not finish.
std::string our_cell(const ControlStudyRow* r) {
  if (r == nullptr) return "";
  std::string out = r->task == "track" ? fixed(r->mean_error_pct_L, 3) + " %"
                                       : std::to_string(r->successes) + "/" +
                                             std::to_string(r->episodes);
  if (r->status != "done") out += " (" + r->status + ")";
  return out;
}

std::string thesis_cell(const ThesisColumn* t, const char* ThesisColumn::*field) {
  return t == nullptr ? "" : " (thesis " + std::string(t->*field) + ")";
}

/// The real-time row: our ratio of controller time to dt_c, mean and max, over the runs of
/// the column at this horizon.
std::string real_time_cell(const ControlStudy& study, const ControlColumn& c, int h) {
  double mean = 0.0, max = 0.0;
  int n = 0;
  for (const std::string task : kControlStudyTasks) {
    const ControlStudyRow* r = find_row(study, c, task, h);
    if (r == nullptr || !std::isfinite(r->real_time_ratio_mean)) continue;
    mean += r->real_time_ratio_mean;
    max = std::max(max, r->real_time_ratio_max);
    ++n;
  }
  return n == 0 ? "-" : fixed(mean / n, 2) + " / " + fixed(max, 2);
}

std::string horizon_table(const ControlStudy& study, const std::vector<ControlColumn>& columns,
                          int h) {
  std::string out = "| H = " + std::to_string(h) + " |";
  std::string rule = "|---|";
  for (const auto& c : columns) {
    out += " " + c.name + (c.controller == "lqr" ? " (no horizon)" : "") + " |";
    rule += "---|";
  }
  out += "\n" + rule + "\n| real-time ratio, mean / max |";
  // (appended piece by piece, not " " + ...: GCC 12's -Wrestrict false positive)
  for (const auto& c : columns) {
    out += ' ';
    out += real_time_cell(study, c, h);
    out += thesis_cell(thesis_column(c), &ThesisColumn::real_time) + " |";
  }
  const struct {
    const char* task;
    const char* label;
    const char* ThesisColumn::*thesis;
  } rows[] = {{"reach", "Dynamic Reach (any point)", &ThesisColumn::dynamic_reach},
              {"hold", "Static Reach", &ThesisColumn::static_reach},
              {"track", "Trajectory (middle circle), mean error % of L", &ThesisColumn::trajectory}};
  for (const auto& row : rows) {
    bool any = false;
    for (const auto& c : columns) any = any || find_row(study, c, row.task, h) != nullptr;
    if (!any) continue;
    out += "\n| ";
    out += row.label;
    out += " |";
    for (const auto& c : columns) {
      out += ' ';
      out += our_cell(find_row(study, c, row.task, h));
      out += thesis_cell(thesis_column(c), row.thesis) + " |";
    }
  }
  return out + "\n";
}

}  // namespace

double thesis_track_error(const ControlColumn& column) {
  const ThesisColumn* t = thesis_column(column);
  return t == nullptr ? std::nan("") : std::strtod(t->trajectory, nullptr);  // "3.45 %"
}

std::string thesis_column_name(const ControlColumn& column) {
  const ThesisColumn* t = thesis_column(column);
  return t == nullptr ? column.name : t->title;
}

std::string control_table_markdown(const ControlStudy& study) {
  const auto& s = study.settings;
  const auto columns = control_columns(s);
  std::string out = "# Table 4.1 reproduction (" + study.scene_name + ")\n\n";
  out += "`" + s.command_line + "`\n\n";
  out += "N = " + std::to_string(s.nodes) + "; " + std::to_string(s.targets) +
         " targets per reach and hold run (seed " + std::to_string(s.seed) +
         "); success: tip error below " + fixed(100.0 * kThesisThreshold, 0) + " % of L within " +
         std::to_string(kThesisMaxSteps) +
         " control steps (thesis 4.4.1). Reach: targets from the dynamic workspace; Static Reach: "
         "task hold, targets from the static workspace; Trajectory: the mean tip error along the "
         "circle in % of L. The thesis' values (Table 4.1, quoted) are in brackets; the thesis "
         "reports a real-time ratio only where it is below 1 (\"No\" otherwise). Real-time ratio: "
         "the controller's wall time per control step over dt_c, mean over the tasks' runs and "
         "largest step, on this machine";
  out += s.max_wall_time > 0 ? "; every run stopped after " + io::format_number(s.max_wall_time) +
                                   " s (\"timed out\": its numbers cover the steps before)"
                             : "";
  out += ". Per-run details: table.csv, study.json, runs/.\n";
  for (const int h : s.horizons) {
    out += '\n';
    out += horizon_table(study, columns, h);
  }
  return out;
}

}  // namespace rodlab::validation::study
