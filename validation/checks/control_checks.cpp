// The "control" family of `rodlab validate`: the thesis' Table 4.1 (section 4.4) reproduced by
// `rodlab study control` (studies/control_study.hpp) on scenes/control-cable.yaml.
//   --quick  NLSQ-MPC on implicit-midpoint at dt_c = 0.05 s, H = 1 and 5: dynamic reach of 3
//            dynamic-workspace targets and the middle circle (one lap, 4 s);
//   --full   the whole study: every column of Table 4.1 at H = 1, 2, 5, 10, 15, 20 on the three
//            tasks with 10 targets, each run stopped after kFullRunLimit s (recorded as timed out).
// Checked against Table 4.1 for every column and horizon: every dynamic and static target
// reached (issue #14: 10/10, where the thesis' Kirchhoff, LQR and iLQR columns reached 9/10 in
// dynamic reach), the middle circle tracked below the thesis' error for that column (NLSQ
// Implicit 3.45, 4.36, 6.90 % of L at dt_c = 0.01, 0.05, 0.1 s; NLSQ Kirchhoff 1.64 %; LQR
// 2.03 %; iLQR 3.38 %). The measured table goes into the report.
#include <cmath>
#include <string>

#include "rodlab/io/text_format.hpp"

#include "checks/check.hpp"
#include "studies/control_study.hpp"

namespace rodlab::validation {
namespace {

/// --full: the wall-time limit of one run [s] (the variational and iLQR runs are slow).
constexpr double kFullRunLimit = 120.0;

std::string run_name(const study::ControlStudyRow& r) {
  return "Table 4.1, " + r.column.name + ", " + r.task +
         (r.horizon > 0 ? ", H = " + std::to_string(r.horizon) : std::string());
}

/// The checks of one run against its column of Table 4.1.
void table41_check(const study::ControlStudyRow& r, std::vector<Check>& out) {
  const std::string detail = r.status + ", " + std::to_string(r.successes) + "/" +
                             std::to_string(r.episodes) + " successful, mean error " +
                             io::format_number(r.mean_error_pct_L) + " % of L, real-time ratio " +
                             io::format_number(r.real_time_ratio_mean) + " mean" +
                             (r.reason.empty() ? "" : "; " + r.reason);
  if (r.task == "track") {
    const double bound = study::thesis_track_error(r.column);
    if (std::isnan(bound)) return;
    Check c = upper_bound_check(run_name(r) + ": mean tracking error [% of L]",
                                r.status == "done" ? r.mean_error_pct_L : double(NAN), bound,
                                "Table 4.1, " + study::thesis_column_name(r.column));
    c.detail = detail;
    out.push_back(with_topic(std::move(c), "reference"));
    return;
  }
  out.push_back(boolean_check(
      run_name(r) + ": every target reached (below 5 % of L)",
      r.status == "done" && r.episodes > 0 && r.successes == r.episodes,
      "Table 4.1, " + study::thesis_column_name(r.column) + ": " +
          (r.task == "reach" ? "Dynamic Reach (any point)" : "Static Reach") +
          ", 10/10 (issue #14)",
      detail));
}

study::ControlStudySettings quick_settings(const ValidationContext& context) {
  study::ControlStudySettings s;
  s.scene_path = (context.scenes_dir / "control-cable.yaml").string();
  s.columns = {"nlsq-implicit"};
  s.dt_controls = {0.05};
  s.horizons = {1, 5};
  s.tasks = {"reach", "track"};
  s.targets = 3;
  s.command_line = "rodlab study control " + s.scene_path +
                   " --controllers nlsq-implicit --dt-control 0.05 --horizons 1,5 --tasks "
                   "reach,track --targets 3";
  return s;
}

study::ControlStudySettings full_settings(const ValidationContext& context) {
  study::ControlStudySettings s;
  s.scene_path = (context.scenes_dir / "control-cable.yaml").string();
  s.max_wall_time = kFullRunLimit;
  s.command_line = "rodlab study control " + s.scene_path + " --max-wall-time " +
                   io::format_number(kFullRunLimit);
  return s;
}

}  // namespace

std::vector<Check> control_checks(const ValidationContext& context) {
  const study::ControlStudySettings s =
      context.full ? full_settings(context) : quick_settings(context);
  const study::ControlStudy result = study::run_control_study(s);
  std::vector<Check> out;
  for (const auto& r : result.rows) table41_check(r, out);
  std::vector<DataSet> data = study::control_study_data(result);
  data.front().table = "###" + study::control_table_markdown(result).substr(1);  // under the family
  for (auto& d : data) context.emit(std::move(d));
  return out;
}

}  // namespace rodlab::validation
