#pragma once
// `rodlab study learning` (issue #15 item 7): the DDPG and GPS columns of the thesis' Table 4.1
// (section 4.4.2-4.4.3) and their learning curves. For every algorithm, task and seed, and for
// each fraction of the task's sample budget (the curve's points), it trains a policy from
// scratch with `rodlab train` and evaluates it with `rodlab control --controller policy`, both
// as child processes of this program (the user's own commands, files in the study directory):
//   reach-one  the policy's own target (thesis: 10/10 points reached, here one per seed);
//   reach-any  50 dynamic-workspace targets drawn with seed 7, none of the training pool's
//              (thesis: 50 random points, the share reached and the mean lowest error);
//   track      the scene's middle circle (thesis: the mean error over the circle).
// A curve point is the mean and sample standard deviation over the seeds.
#include <filesystem>
#include <iterator>
#include <functional>
#include <string>
#include <vector>

#include "checks/check.hpp"

namespace rodlab::validation::study {

inline constexpr const char* kLearningAlgorithms[] = {"ddpg", "gps"};
inline constexpr const char* kLearningTasks[] = {"reach-one", "reach-any", "track"};

/// The samples of a full training (the curve's last point): within the budgets (GPS
/// reach-any <= 25 000, DDPG <= 500 000) and below the thesis' (DDPG 500 000 per reach task and
/// 1 000 000 for track; GPS 5 000, 250 000, 500 000).
long learning_budget(const std::string& algorithm, const std::string& task);

struct LearningStudySettings {
  std::string scene_path;
  std::vector<std::string> overrides;  ///< --set KEY=VALUE texts, for every training
  std::vector<std::string> algorithms{std::begin(kLearningAlgorithms),
                                      std::end(kLearningAlgorithms)};
  std::vector<std::string> tasks{std::begin(kLearningTasks), std::end(kLearningTasks)};
  int seeds = 5;                             ///< seeds 1..K
  std::vector<double> fractions{0.25, 0.5, 1.0};  ///< of each budget: the curve's points
  double budget_scale = 1.0;                 ///< multiplies every budget (smoke runs)
  int jobs = 2;                              ///< environments per training
  int targets = 50;                          ///< reach-any evaluation targets
  unsigned target_seed = 7;
  double max_wall_time = 0.0;                ///< per training or evaluation [s]; 0: none
  std::filesystem::path program;             ///< the rodlab executable; empty: this program
  std::string command_line;
};

/// One training and its evaluation.
struct LearningStudyRow {
  std::string algorithm, task;
  int seed = 0;
  long samples = 0;
  std::string status;  ///< "done", "failed" (training or evaluation), "timed out"
  std::string reason;
  double success_pct = 0.0;            ///< evaluation episodes reaching the threshold
  double best_error_pct_L = 0.0;       ///< mean over episodes of the lowest error (reach)
  double mean_error_pct_L = 0.0;       ///< summary.mean_error_pct_L (track: the circle)
  double train_wall_time_s = 0.0, samples_per_s = 0.0;
  double real_time_ratio_max = 0.0;    ///< the policy's, in the evaluation
};

struct LearningStudy {
  LearningStudySettings settings;
  std::vector<LearningStudyRow> rows;
  double wall_time_s = 0.0;
};

/// Called after each run with its row, the runs done and their total.
using LearningProgress = std::function<void(const LearningStudyRow&, long done, long total)>;

/// Runs every training and evaluation, in the order algorithm, task, fraction, seed; `progress`
/// after each. Files go to `dir` (policies/, results/, logs/).
LearningStudy run_learning_study(const LearningStudySettings& s, const std::string& dir,
                                 const LearningProgress& progress = {});

/// Mean and sample standard deviation over the seeds of one algorithm, task and budget.
struct LearningPoint {
  std::string algorithm, task;
  long samples = 0;
  int runs = 0, done = 0;  ///< done: trained (the evaluation may still have failed)
  int failed_evaluations = 0;  ///< trained, but a plant step of the evaluation failed
  double success_mean = 0, success_sd = 0, best_error_mean = 0, best_error_sd = 0,
         mean_error_mean = 0, mean_error_sd = 0, wall_time_mean = 0, samples_per_s_mean = 0,
         real_time_ratio_max = 0;
};
std::vector<LearningPoint> learning_points(const LearningStudy& study);

/// Table 4.1's learning columns at the full budgets, beside the thesis' values (Markdown).
std::string learning_table_markdown(const LearningStudy& study);
/// The curves as data sets with figures (validation/make_figures.py).
std::vector<DataSet> learning_study_data(const LearningStudy& study);
/// learning-study.json, learning-table.md and data/*.csv in dir.
void write_learning_study(const LearningStudy& study, const std::string& dir);

}  // namespace rodlab::validation::study
