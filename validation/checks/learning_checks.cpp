// The "learning" family of `rodlab validate`: the DDPG and GPS columns of the thesis' Table 4.1
// (sections 4.4.2-4.4.3) by `rodlab study learning` (studies/learning_study.hpp) on
// scenes/control-cable.yaml, each training and evaluation a `rodlab train` / `rodlab control`
// child process.
//   --quick  reach-one, seed 1, both algorithms at their full budgets (DDPG 3000 samples, GPS
//            1200; seconds each): the policy reaches its target;
//   --full   the whole study: three tasks, five seeds, the learning curves.
// Checked against issue #15's bounds, which are the thesis' results with fewer samples:
// reach-one 100 %; reach-any at least 83.6 % (DDPG) and 94 % with a mean lowest error at most
// 2.5 % of L (GPS); middle circle at most 6.4 % (DDPG) and 10.3 % of L (GPS); every policy in
// real time, controller time per step / dt_c below the thesis' 0.01. The lowest error is the
// closest approach of an evaluation episode run as the policy was trained (GPS: its T steps;
// DDPG: until within the threshold; learning_study.cpp control_argv).
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "rodlab/io/text_format.hpp"

#include "checks/check.hpp"
#include "studies/learning_study.hpp"

namespace rodlab::validation {
namespace {

/// Table 4.1's real-time ratio of both learned policies.
constexpr double kThesisRealTime = 0.01;

std::string point_name(const study::LearningPoint& p) {
  return "Table 4.1, " + p.algorithm + ", " + p.task + ", " + std::to_string(p.samples) +
         " samples, " + std::to_string(p.done) + "/" + std::to_string(p.runs) + " seeds";
}

void point_checks(const study::LearningPoint& p, std::vector<Check>& out) {
  const bool gps = p.algorithm == "gps";
  const std::string ref = std::string("issue #15 / Table 4.1, ") + (gps ? "GPS" : "DDPG");
  const double success = p.done == p.runs ? p.success_mean : double(NAN);
  if (p.task == "reach-one") {
    out.push_back(boolean_check(point_name(p) + ": the target reached by every seed's policy",
                                p.done == p.runs && p.success_mean >= 100.0,
                                ref + ": 100 %",
                                io::format_number(p.success_mean) + " % reached"));
  } else if (p.task == "reach-any") {
    Check c = range_check(point_name(p) + ": targets reached [%]", success, gps ? 94.0 : 83.6,
                          100.0, ref + (gps ? ": 94.0 %" : ": 83.6 %"));
    c.detail = "sd " + io::format_number(p.success_sd) + " over the seeds";
    out.push_back(with_topic(std::move(c), "reference"));
    if (gps)
      out.push_back(upper_bound_check(point_name(p) + ": mean lowest tip error [% of L]",
                                      p.done == p.runs ? p.best_error_mean : double(NAN), 2.5,
                                      ref + ": 2.5 % of L"));
  } else {
    out.push_back(with_topic(
        upper_bound_check(point_name(p) + ": middle-circle error [% of L]",
                          p.done == p.runs ? p.mean_error_mean : double(NAN), gps ? 10.3 : 6.4,
                          ref + (gps ? ": 10.3 % of L" : ": 6.40 % of L")),
        "reference"));
  }
  out.push_back(upper_bound_check(point_name(p) + ": policy time per step / dt_c",
                                  p.real_time_ratio_max, kThesisRealTime,
                                  "Table 4.1: 0.01 for DDPG and GPS"));
}

}  // namespace

std::vector<Check> learning_checks(const ValidationContext& context) {
  study::LearningStudySettings s;
  s.scene_path = (context.scenes_dir / "control-cable.yaml").string();
  s.program = context.program;
  if (!context.full) {
    s.tasks = {"reach-one"};
    s.seeds = 1;
    s.fractions = {1.0};
  }
  s.command_line = "rodlab study learning " + s.scene_path +
                   (context.full ? std::string() : " --tasks reach-one --seeds 1");
  const auto dir = std::filesystem::temp_directory_path() /
                   ("rodlab-learning-" + std::to_string(::getpid()));
  const study::LearningStudy result = study::run_learning_study(s, dir.string());
  std::filesystem::remove_all(dir);
  std::vector<Check> out;
  for (const auto& p : study::learning_points(result))
    if (p.samples == study::learning_budget(p.algorithm, p.task)) point_checks(p, out);
  std::vector<DataSet> data = study::learning_study_data(result);
  data.front().table = "###" + study::learning_table_markdown(result).substr(1);
  for (auto& d : data) context.emit(std::move(d));
  return out;
}

}  // namespace rodlab::validation
