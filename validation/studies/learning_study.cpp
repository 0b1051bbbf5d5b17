#include "studies/learning_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "rodlab/check.hpp"
#include "rodlab/io/scene_loader.hpp"
#include "rodlab/io/text_format.hpp"
#include "report/report.hpp"
#include "studies/child_process.hpp"
#include "studies/settings.hpp"

// Figure specs are written with designated initializers; the fields left out keep their
// defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace rodlab::validation::study {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

/// The hard limit of a child without --max-wall-time [s] (a training that hangs is a finding).
constexpr double kNoLimit = 3600.0;

std::string number(double v) { return io::format_number(v); }

std::string stem(const std::string& algorithm, const std::string& task, int seed, long samples) {
  return algorithm + "-" + task + "-seed" + std::to_string(seed) + "-" + std::to_string(samples);
}

/// The child's failure as a reason: time-out, signal, or the first line of its stderr (the
/// message; the progress lines of a training go to stdout's table only at the end).
std::string failure_of(const ChildOutcome& c) {
  if (c.timed_out) return "timed out after " + number(c.wall_time_s) + " s";
  if (c.signal != 0) return "killed by signal " + std::to_string(c.signal);
  std::istringstream lines(c.stderr_text);
  std::string line, first;
  while (std::getline(lines, line))
    if (line.rfind("samples ", 0) != 0 && !line.empty()) {
      first = line;
      break;
    }
  return "exit " + std::to_string(c.exit_code) + ": " + first;
}

std::string program_of(const LearningStudySettings& s) {
  return (s.program.empty() ? own_executable() : s.program).string();
}

std::vector<std::string> train_argv(const LearningStudySettings& s, const LearningStudyRow& r,
                                    const fs::path& policy) {
  std::vector<std::string> a{program_of(s), "train", s.scene_path, "--algorithm",
                             r.algorithm, "--task", r.task, "--samples", std::to_string(r.samples),
                             "--seed", std::to_string(r.seed), "--jobs", std::to_string(s.jobs),
                             "--out", policy.string()};
  for (const auto& o : s.overrides) a.insert(a.end(), {"--set", o});
  if (s.max_wall_time > 0.0) a.insert(a.end(), {"--max-wall-time", number(s.max_wall_time)});
  return a;
}

/// The evaluation runs a reach episode as the policy was trained: DDPG's end at the first step
/// within the threshold (terminal in its training), GPS's run its T steps (fixed-length
/// trajectories; a GPS policy's actions beyond them are not defined by its training), so that
/// its best error is the closest approach over the episode (the thesis' "best tip error",
/// 4.4.3; training.episode_steps in the policy file).
std::vector<std::string> control_argv(const LearningStudySettings& s, const LearningStudyRow& r,
                                      const fs::path& policy, const fs::path& result) {
  std::vector<std::string> a{program_of(s), "control", s.scene_path, "--controller",
                             "policy", "--policy", policy.string(), "--task",
                             r.task == "track" ? "track" : "reach", "--out", result.string()};
  if (r.task == "reach-any")
    a.insert(a.end(), {"--targets", std::to_string(s.targets), "--seed",
                       std::to_string(s.target_seed)});
  if (r.algorithm == "gps" && r.task != "track") {
    const Json p = Json::parse(std::ifstream(policy));
    const int steps = p["training"]["episode_steps"].get<int>();
    a.insert(a.end(), {"--set", "control.stop_at_success=false", "--set",
                       "control.max_steps=" + std::to_string(steps)});
  }
  // the user's overrides last: they win
  for (const auto& o : s.overrides) a.insert(a.end(), {"--set", o});
  return a;
}

/// Fills the row's numbers from the policy file and the control result.
void read_outcome(LearningStudyRow& r, const fs::path& policy, const fs::path& result,
                  double length) {
  const Json p = Json::parse(std::ifstream(policy));
  r.train_wall_time_s = p["training"]["wall_time_s"].get<double>();
  r.samples_per_s = r.samples / std::max(r.train_wall_time_s, 1e-9);
  const Json c = Json::parse(std::ifstream(result));
  const auto& episodes = c["episodes"];
  double successes = 0.0, best = 0.0;
  for (const auto& e : episodes) {
    successes += e["success"].get<bool>() ? 1.0 : 0.0;
    best += e["min_error"].get<double>();
  }
  const double n = std::max<double>(1.0, episodes.size());
  r.success_pct = 100.0 * successes / n;
  r.best_error_pct_L = 100.0 * best / n / length;
  r.mean_error_pct_L = c["summary"]["mean_error_pct_L"].get<double>();
  r.real_time_ratio_max = c["summary"]["real_time_ratio_max"].get<double>();
  if (!c["converged"].get<bool>()) {
    r.status = "failed";
    r.reason = c["reason"].is_string() ? c["reason"].get<std::string>() : "not converged";
  }
}

LearningStudyRow run_one(const LearningStudySettings& s, LearningStudyRow r, const fs::path& dir,
                         double length) {
  const std::string name = stem(r.algorithm, r.task, r.seed, r.samples);
  for (const char* sub : {"policies", "results", "logs"}) fs::create_directories(dir / sub);
  const fs::path policy = dir / "policies" / (name + ".json");
  const fs::path result = dir / "results" / (name + ".json");
  const double limit = s.max_wall_time > 0.0 ? s.max_wall_time + 10.0 : kNoLimit;
  const ChildOutcome t = run_child(train_argv(s, r, policy), limit, dir / "logs" / (name + ".train"));
  if (t.exit_code != 0) {
    r.status = t.timed_out ? "timed out" : "failed";
    r.reason = "training: " + failure_of(t);
    return r;
  }
  const ChildOutcome c =
      run_child(control_argv(s, r, policy, result), limit, dir / "logs" / (name + ".control"));
  if (c.exit_code != 0 && c.exit_code != 1) {  // 1: a failed episode, still a result
    r.status = c.timed_out ? "timed out" : "failed";
    r.reason = "evaluation: " + failure_of(c);
    return r;
  }
  r.status = "done";
  read_outcome(r, policy, result, length);
  return r;
}

double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return v.empty() ? NAN : s / v.size();
}
double sd(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  const double m = mean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / (v.size() - 1));
}

}  // namespace

long learning_budget(const std::string& algorithm, const std::string& task) {
  if (algorithm == "gps") return task == "reach-one" ? 1200 : 24000;
  return task == "reach-one" ? 3000 : task == "reach-any" ? 20000 : 50000;
}

LearningStudy run_learning_study(const LearningStudySettings& s, const std::string& dir,
                                 const LearningProgress& progress) {
  const auto start = std::chrono::steady_clock::now();
  LearningStudy study;
  study.settings = s;
  std::vector<io::Override> overrides;
  for (const auto& o : s.overrides) overrides.push_back(io::parse_override(o));
  const double length = io::load_scene(s.scene_path, overrides).rod.length;  // the errors' unit
  const long total = static_cast<long>(s.algorithms.size() * s.tasks.size() *
                                       s.fractions.size()) * s.seeds;
  for (const auto& a : s.algorithms)
    for (const auto& k : s.tasks)
      for (const double f : s.fractions)
        for (int seed = 1; seed <= s.seeds; ++seed) {
          LearningStudyRow r;
          r.algorithm = a;
          r.task = k;
          r.seed = seed;
          r.samples = std::max(1L, std::lround(f * s.budget_scale * learning_budget(a, k)));
          study.rows.push_back(run_one(s, r, dir, length));
          if (progress) progress(study.rows.back(), static_cast<long>(study.rows.size()), total);
        }
  study.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return study;
}

std::vector<LearningPoint> learning_points(const LearningStudy& study) {
  std::vector<LearningPoint> out;
  for (const auto& r : study.rows) {
    auto it = std::find_if(out.begin(), out.end(), [&](const LearningPoint& p) {
      return p.algorithm == r.algorithm && p.task == r.task && p.samples == r.samples;
    });
    if (it == out.end()) {
      out.push_back({.algorithm = r.algorithm, .task = r.task, .samples = r.samples});
      it = std::prev(out.end());
    }
    ++it->runs;
  }
  for (auto& p : out) {
    std::vector<double> success, best, err, wall, rate;
    for (const auto& r : study.rows) {
      if (r.algorithm != p.algorithm || r.task != p.task || r.samples != p.samples) continue;
      // a failed evaluation still measured its episodes; a failed or timed-out training did not
      if (r.train_wall_time_s <= 0.0) continue;
      ++p.done;
      if (r.status != "done") ++p.failed_evaluations;
      success.push_back(r.success_pct);
      best.push_back(r.best_error_pct_L);
      err.push_back(r.mean_error_pct_L);
      wall.push_back(r.train_wall_time_s);
      rate.push_back(r.samples_per_s);
      p.real_time_ratio_max = std::max(p.real_time_ratio_max, r.real_time_ratio_max);
    }
    p.success_mean = mean(success);
    p.success_sd = sd(success);
    p.best_error_mean = mean(best);
    p.best_error_sd = sd(best);
    p.mean_error_mean = mean(err);
    p.mean_error_sd = sd(err);
    p.wall_time_mean = mean(wall);
    p.samples_per_s_mean = mean(rate);
  }
  return out;
}

namespace {

/// The thesis' value for a task and algorithm (Table 4.1 and 4.4.3), as text.
std::string thesis_value(const std::string& algorithm, const std::string& task) {
  const bool gps = algorithm == "gps";
  if (task == "reach-one") return gps ? "100 % (5 000 samples)" : "100 % (500 000)";
  if (task == "reach-any")
    return gps ? "94.0 %, best 2.5 % L (250 000)" : "83.6 %, best 5.2 % L (500 000)";
  return gps ? "10.3 % L (500 000)" : "6.40 % L (1 000 000)";
}

std::string pm(double m, double s) { return number(m) + " +- " + number(s); }

}  // namespace

std::string learning_table_markdown(const LearningStudy& study) {
  std::ostringstream md;
  md << "# Table 4.1, learning columns (rodlab study learning)\n\n"
     << "Mean +- sample standard deviation over " << study.settings.seeds
     << " seeds at each task's full budget; reach-any on " << study.settings.targets
     << " unseen targets (seed " << study.settings.target_seed
     << "); real time: the policy's largest controller time per step over dt_c.\n\n"
     << "| algorithm | task | samples | success [%] | best error [% L] | circle error [% L] | "
        "training [s] | samples/s | real time (max) | thesis |\n"
     << "|---|---|---|---|---|---|---|---|---|---|\n";
  const auto points = learning_points(study);
  for (const auto& a : study.settings.algorithms)
    for (const auto& k : study.settings.tasks) {
      const LearningPoint* full = nullptr;
      for (const auto& p : points)
        if (p.algorithm == a && p.task == k && (!full || p.samples > full->samples)) full = &p;
      if (!full) continue;
      md << "| " << a << " | " << k << " | " << full->samples << " | "
         << pm(full->success_mean, full->success_sd) << " | "
         << (k == "track" ? "" : pm(full->best_error_mean, full->best_error_sd)) << " | "
         << (k == "track" ? pm(full->mean_error_mean, full->mean_error_sd) : "") << " | "
         << number(full->wall_time_mean) << " | " << number(full->samples_per_s_mean) << " | "
         << number(full->real_time_ratio_max) << " | " << thesis_value(a, k) << " |"
         << (full->done < full->runs
                 ? " (" + std::to_string(full->runs - full->done) + " trainings failed)"
                 : "")
         << (full->failed_evaluations > 0
                 ? " (" + std::to_string(full->failed_evaluations) +
                       " evaluations ended in a failed plant step; their errors count)"
                 : "")
         << '\n';
    }
  return md.str();
}

std::vector<DataSet> learning_study_data(const LearningStudy& study) {
  DataSet d{.name = "learning_study_curves",
            .description = "rodlab study learning: success rate and errors against the training "
                           "samples, mean and standard deviation over the seeds",
            .columns = {"series", "algorithm", "task", "samples", "runs", "success_pct",
                        "success_sd", "best_error_pct_L", "best_error_sd", "mean_error_pct_L",
                        "mean_error_sd", "train_wall_time_s", "samples_per_s"}};
  for (const auto& p : learning_points(study))
    d.add_row({p.task + ": " + p.algorithm, p.algorithm, p.task, static_cast<double>(p.samples),
               p.done, p.success_mean, p.success_sd, p.best_error_mean, p.best_error_sd,
               p.mean_error_mean, p.mean_error_sd, p.wall_time_mean, p.samples_per_s_mean});
  for (const auto& k : study.settings.tasks) {
    const bool track = k == "track";
    d.figures.push_back(
        {.name = "learning_curve_" + k,
         .kind = "semilogx",
         .x = "samples",
         .y = {track ? "mean_error_pct_L" : "success_pct"},
         .series = "series",
         .title = "Learning curve: " + k,
         .xlabel = "training samples (environment steps)",
         .ylabel = track ? "middle-circle error [% of L], mean over seeds"
                         : "targets reached [%], mean over seeds",
         .caption = "Each point trains from scratch with that many samples and evaluates the "
                    "policy with rodlab control; mean over " +
                    std::to_string(study.settings.seeds) + " seeds (the table gives the spread). "
                    "Thesis: " + thesis_value("ddpg", k) + " for DDPG, " +
                    thesis_value("gps", k) + " for GPS.",
         .style = "lines+markers",
         .select = k + ":"});
  }
  return {d};
}

void write_learning_study(const LearningStudy& study, const std::string& dir) {
  const std::vector<DataSet> data = learning_study_data(study);
  for (const auto& d : data)
    write_output((fs::path(dir) / "data").string(), d.name + ".csv", d.to_csv());
  write_output(dir, "figures.json", figure_index_json(data) + "\n");
  write_output(dir, "table.md", learning_table_markdown(study));
  Json rows = Json::array();
  for (const auto& r : study.rows)
    rows.push_back({{"algorithm", r.algorithm}, {"task", r.task}, {"seed", r.seed},
                    {"samples", r.samples}, {"status", r.status}, {"reason", r.reason},
                    {"success_pct", r.success_pct}, {"best_error_pct_L", r.best_error_pct_L},
                    {"mean_error_pct_L", r.mean_error_pct_L},
                    {"train_wall_time_s", r.train_wall_time_s}, {"samples_per_s", r.samples_per_s},
                    {"real_time_ratio_max", r.real_time_ratio_max}});
  const auto& s = study.settings;
  write_output(dir, "study.json",
               Json{{"schema", "rodlab.study/1"},
                    {"kind", "learning"},
                    {"command_line", s.command_line},
                    {"settings",
                     {{"algorithms", s.algorithms}, {"tasks", s.tasks}, {"seeds", s.seeds},
                      {"fractions", s.fractions}, {"budget_scale", s.budget_scale},
                      {"jobs", s.jobs}, {"targets", s.targets}, {"target_seed", s.target_seed}}},
                    {"wall_time_s", study.wall_time_s},
                    {"rows", rows}}
                       .dump(2) +
                   "\n");
}

}  // namespace rodlab::validation::study
