#pragma once
// `rodlab study control` (issue #14 item 8): the thesis' Table 4.1 (section 4.4) reproduced.
// Columns are controllers on plant schemes at a control step (Table 4.1: NLSQ-MPC on the
// implicit scheme at dt_c = 0.01, 0.05, 0.1 s, NLSQ-MPC on the Kirchhoff rod, LQR, iLQR), rows
// the thesis' tasks (dynamic reach of 10 dynamic-workspace targets, static reach-and-hold of 10
// static-workspace targets, tracking the middle circle), each at every horizon H (figures
// 4.4-4.11 plot error and real-time ratio against H). One `run_control` per column, task and
// horizon (LQR has no horizon: one run per task); a run over its wall-time limit is kept as
// "timed out", never left out.
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rodlab/result/control_result.hpp"
#include "rodlab/scene/scene.hpp"

#include "checks/check.hpp"
#include "studies/settings.hpp"

namespace rodlab::validation::study {

/// The column kinds (--controllers): NLSQ-MPC on implicit-midpoint (one column per dt_c),
/// NLSQ-MPC on the Kirchhoff rod (plant `variational` with rod.model = kirchhoff, predicted by
/// implicit-midpoint on the same rod: docs/control.md "Model and plant"), LQR, iLQR; and, by name
/// only, the thesis' Kirchhoff setup (`variational` also as the model: far from real time).
inline constexpr const char* kControlColumnKinds[] = {"nlsq-implicit", "nlsq-kirchhoff", "lqr",
                                                      "ilqr", "nlsq-kirchhoff-variational"};
/// The columns run when --controllers is not given: Table 4.1's.
inline constexpr const char* kDefaultControlColumns[] = {"nlsq-implicit", "nlsq-kirchhoff", "lqr",
                                                         "ilqr"};
/// The thesis' tasks in Table 4.1's row order: dynamic reach, static reach (and hold), trajectory.
inline constexpr const char* kControlStudyTasks[] = {"reach", "hold", "track"};
/// The control step of the columns Table 4.1 gives none for (Kirchhoff, LQR, iLQR) [s]: the
/// middle of the implicit columns' steps, at which NLSQ-MPC is real-time at H = 10
/// (docs/control.md "NLSQ-MPC").
inline constexpr double kSingleColumnDtControl = 0.05;
/// Thesis 4.4.1: success is a tip error below 5 % of L, within 100 control steps.
inline constexpr double kThesisThreshold = 0.05;
inline constexpr int kThesisMaxSteps = 100;

struct ControlStudySettings {
  std::string scene_path;
  std::vector<std::string> overrides;  ///< --set KEY=VALUE texts, applied to every column
  std::vector<std::string> columns{std::begin(kDefaultControlColumns),
                                   std::end(kDefaultControlColumns)};
  std::vector<int> horizons{1, 2, 5, 10, 15, 20};
  std::vector<double> dt_controls{0.01, 0.05, 0.1};  ///< the nlsq-implicit columns
  std::vector<std::string> tasks{std::begin(kControlStudyTasks), std::end(kControlStudyTasks)};
  int targets = 10;            ///< per reach and hold run
  unsigned seed = 1;           ///< of the drawn targets
  int nodes = 20;              ///< the thesis' N
  double max_wall_time = 0.0;  ///< per run [s]; 0: none
  std::string command_line;
};

/// One column of Table 4.1.
struct ControlColumn {
  std::string name;        ///< e.g. "nlsq-implicit dt=0.05"
  std::string kind;        ///< one of kControlColumnKinds
  std::string controller;  ///< nlsq-mpc | lqr | ilqr
  std::string scheme;      ///< the plant's scheme
  std::string model_scheme;  ///< the controller's model's scheme if not the plant's (control.model_scheme)
  bool kirchhoff = false;  ///< rod.model = kirchhoff
  double dt_control = 0.0;
};

/// A number the run did not produce (stopped before its first control step).
inline constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();

/// One run: a column on a task at a horizon.
struct ControlStudyRow {
  ControlColumn column;
  std::string task;
  int horizon = 0;           ///< 0: the controller has none (LQR)
  std::string status;        ///< "done", "failed" (a solver failed), "timed out"
  int successes = 0, episodes = 0;
  double mean_error_pct_L = kNotMeasured;   ///< summary.mean_error_pct_L
  double final_error_pct_L = kNotMeasured;  ///< mean over episodes of their final error, % of L
  /// Mean over episodes of their lowest error, % of L (thesis 4.4.1, dynamic reach: "we record
  /// the lowest error achieved").
  double min_error_pct_L = kNotMeasured;
  double real_time_ratio_mean = kNotMeasured, real_time_ratio_max = kNotMeasured;
  double wall_time_s = 0.0;
  bool converged = false;
  std::string reason;     ///< the run's reason
  std::string run_file;   ///< runs/NAME.json (empty when the run produced no result)
  std::optional<result::ControlResult> result;  ///< the run's result (none when it produced none)
};

struct ControlStudy {
  ControlStudySettings settings;
  std::string scene_name;
  double rod_length = 0.0;
  std::vector<ControlStudyRow> rows;
};

/// The columns of the settings, in Table 4.1's order (bad names: std::invalid_argument).
std::vector<ControlColumn> control_columns(const ControlStudySettings& settings);

/// Called after each run with its row, the runs done and their total.
using ControlProgress = std::function<void(const ControlStudyRow&, long done, long total)>;

/// Runs the study; `progress` (if set) is called after every run.
ControlStudy run_control_study(const ControlStudySettings& s,
                               const ControlProgress& progress = {});

std::string control_table_csv(const ControlStudy& study);
Json control_study_json(const ControlStudy& study);
/// Table 4.1's middle-circle error of the column [% of L]; NaN where the table has none.
double thesis_track_error(const ControlColumn& column);
/// The column's name in Table 4.1, e.g. "NLSQ Implicit, dt = 0.05 s", "NLSQ Kirchhoff", "LQR".
std::string thesis_column_name(const ControlColumn& column);
/// Table 4.1's layout, one table per horizon, each cell ours with the thesis' value beside it.
std::string control_table_markdown(const ControlStudy& study);
/// The data behind the figures: error and real-time ratio against the horizon per task
/// (figures 4.4-4.5, 4.7-4.8, 4.10-4.11), and the traced circles at `trace_horizon`
/// (the largest horizon with a track run when 0).
std::vector<DataSet> control_study_data(const ControlStudy& study, int trace_horizon = 0);

/// Writes DIR/table.csv, study.json, table.md, runs/*.json, data/*.csv and figures.json (the
/// figure specs validation/make_figures.py reads), every file atomically.
void write_control_study(const ControlStudy& study, const std::string& dir);

}  // namespace rodlab::validation::study
