#define BOOST_TEST_MODULE control_study
#include <boost/test/unit_test.hpp>

#include <algorithm>

// The Table 4.1 study (validation/studies/control_study.hpp) on a tiny configuration of the
// thesis' cable robot (scenes/control-cable.yaml at N = 10, H = 1, dt_c = 0.05 s, 2 targets):
// one row per column, task and horizon; each row's counts and errors are the run's own; a run
// stopped by its wall-time limit is reported as timed out; the written files hold the same
// rows.

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "studies/control_study.hpp"

namespace fs = std::filesystem;
namespace study = rodlab::validation::study;

namespace {

const std::string kScene = RODLAB_SOURCE_DIR "/scenes/control-cable.yaml";

study::ControlStudySettings tiny(std::vector<std::string> columns, std::vector<std::string> tasks) {
  study::ControlStudySettings s;
  s.scene_path = kScene;
  s.columns = std::move(columns);
  s.tasks = std::move(tasks);
  s.dt_controls = {0.05};
  s.horizons = {1};
  s.targets = 2;
  s.nodes = 10;
  s.command_line = "test_control_study";
  return s;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The run's result agrees with the row made from it.
void row_matches_its_run(const study::ControlStudyRow& r, double length) {
  BOOST_TEST_CONTEXT(r.column.name << " " << r.task) {
    BOOST_TEST_REQUIRE(r.result.has_value());
    const auto& res = *r.result;
    int ok = 0, stepped = 0;  // an episode that could not start has no error
    double final_sum = 0.0;
    for (const auto& e : res.episodes) {
      ok += e.success ? 1 : 0;
      if (e.steps > 0) final_sum += e.final_error, ++stepped;
    }
    BOOST_TEST(r.episodes == static_cast<int>(res.episodes.size()));
    BOOST_TEST(r.successes == ok);
    BOOST_TEST(r.mean_error_pct_L == res.summary.mean_error_pct_L);
    BOOST_TEST(r.final_error_pct_L == 100.0 * final_sum / stepped / length,
               boost::test_tools::tolerance(1e-12));
    BOOST_TEST(r.real_time_ratio_mean == res.summary.real_time_ratio_mean);
    BOOST_TEST(r.real_time_ratio_max >= r.real_time_ratio_mean);
    BOOST_TEST(r.horizon == res.horizon);
    BOOST_TEST(r.column.controller == res.controller);
    BOOST_TEST(r.status == (res.converged ? "done" : "failed"));
  }
}

}  // namespace

// NLSQ-MPC on implicit-midpoint (H = 1) and LQR, dynamic reach and hold of 2 targets each, and
// the middle circle: every row present, its numbers those of its run.
BOOST_AUTO_TEST_CASE(rows_are_their_runs) {
  const auto s = tiny({"nlsq-implicit", "lqr"}, {"reach", "hold", "track"});
  const study::ControlStudy st = study::run_control_study(s);
  BOOST_TEST_REQUIRE(st.rows.size() == 6u);  // 2 columns x 3 tasks x 1 horizon (LQR: none)
  BOOST_TEST(st.rod_length == 0.1);
  for (const auto& r : st.rows) {
    row_matches_its_run(r, st.rod_length);
    BOOST_TEST(r.episodes == (r.task == "track" ? 1 : 2));
  }
  // NLSQ-MPC reaches its dynamic-workspace targets (thesis Table 4.1: 10/10) and tracks the
  // circle below the thesis' 4.36 % of L at dt_c = 0.05 s; LQR tracks it below its 2.03 %.
  for (const auto& r : st.rows)
    if (r.column.kind == "nlsq-implicit" && r.task == "reach") BOOST_TEST(r.successes == 2);
    else if (r.column.kind == "nlsq-implicit" && r.task == "track")
      BOOST_TEST(r.mean_error_pct_L < 4.36);
    else if (r.column.controller == "lqr" && r.task == "track")
      BOOST_TEST(r.mean_error_pct_L < 2.03);

  const fs::path dir = fs::temp_directory_path() / ("rodlab-control-study-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  study::write_control_study(st, dir.string());
  for (const char* f : {"table.csv", "table.md", "study.json", "figures.json",
                        "data/control_study_horizon.csv", "data/control_study_circle.csv"})
    BOOST_TEST(fs::is_regular_file(dir / f), f);
  const auto j = nlohmann::json::parse(read(dir / "study.json"));
  BOOST_TEST(j["kind"] == "control");
  BOOST_TEST(j["rows"].size() == st.rows.size());
  for (std::size_t i = 0; i < st.rows.size(); ++i) {
    BOOST_TEST(j["rows"][i]["successes"] == st.rows[i].successes);
    if (!st.rows[i].run_file.empty()) BOOST_TEST(fs::is_regular_file(dir / st.rows[i].run_file));
  }
  const std::string md = read(dir / "table.md");
  BOOST_TEST(md.find("Dynamic Reach") != std::string::npos);
  BOOST_TEST(md.find("(thesis 4.36 %)") != std::string::npos);  // Table 4.1, quoted
  std::istringstream csv(read(dir / "table.csv"));
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  BOOST_TEST(lines == 1 + static_cast<int>(st.rows.size()));
  fs::remove_all(dir);
}

// A run over its wall-time limit is reported as timed out, with the steps before it, never
// hidden: the table says so. On implicit-midpoint (its Newton checks the limit) and on the
// Kirchhoff rod's variational scheme (checked between control steps), predicted by
// implicit-midpoint or by itself (the thesis' setup).
BOOST_AUTO_TEST_CASE(a_timed_out_run_is_reported) {
  auto s = tiny({"nlsq-implicit", "nlsq-kirchhoff", "nlsq-kirchhoff-variational"}, {"track"});
  s.horizons = {5};
  s.max_wall_time = 0.2;  // the whole lap takes seconds
  const study::ControlStudy st = study::run_control_study(s);
  BOOST_TEST_REQUIRE(st.rows.size() == 3u);
  for (const auto& r : st.rows) {
    BOOST_TEST_CONTEXT(r.column.name) {
      BOOST_TEST(r.status == "timed out");
      BOOST_TEST(!r.converged);
      BOOST_TEST(r.reason.find("wall-time limit") != std::string::npos, r.reason);
      BOOST_TEST(r.successes == 0);
      BOOST_TEST(r.wall_time_s < 5.0);  // the limit plus at most a control step
    }
  }
  BOOST_TEST(study::control_table_markdown(st).find("(timed out)") != std::string::npos);
  BOOST_TEST(study::control_table_csv(st).find(",timed out,") != std::string::npos);
  // the stopped pass is an episode of its result once it has rows (else its rows would name
  // none: not writable); the table counts the pass either way
  for (const auto& r : st.rows) {
    BOOST_TEST(r.episodes == 1);
    BOOST_TEST_REQUIRE(r.result.has_value());
    BOOST_TEST(r.result->episodes.size() == (r.result->series.t.empty() ? 0u : 1u));
  }
  const fs::path dir = fs::temp_directory_path() / ("rodlab-control-timeout-" + std::to_string(::getpid()));
  BOOST_CHECK_NO_THROW(study::write_control_study(st, dir.string()));
  fs::remove_all(dir);
}

// The columns in Table 4.1's order, one nlsq-implicit column per control step; unknown names
// refused.
BOOST_AUTO_TEST_CASE(columns) {
  study::ControlStudySettings s;
  s.columns = {"ilqr", "nlsq-implicit", "lqr", "nlsq-kirchhoff"};
  s.dt_controls = {0.01, 0.1};
  const auto c = study::control_columns(s);
  BOOST_TEST_REQUIRE(c.size() == 5u);
  BOOST_TEST(c[0].name == "nlsq-implicit dt=0.01");
  BOOST_TEST(c[1].name == "nlsq-implicit dt=0.1");
  BOOST_TEST(c[2].scheme == "variational");
  BOOST_TEST(c[2].model_scheme == "implicit-midpoint");  // the model-plant split
  BOOST_TEST(c[2].kirchhoff);
  BOOST_TEST(c[3].controller == "lqr");
  BOOST_TEST(c[4].controller == "ilqr");
  BOOST_TEST(c[4].dt_control == study::kSingleColumnDtControl);
  s.columns = {"nlsq-kirchhoff-variational"};  // the thesis' setup: the plant is the model
  const auto thesis = study::control_columns(s);
  BOOST_TEST_REQUIRE(thesis.size() == 1u);
  BOOST_TEST(thesis[0].scheme == "variational");
  BOOST_TEST(thesis[0].model_scheme.empty());
  BOOST_TEST(thesis[0].kirchhoff);
  const std::vector<std::string> defaults = study::ControlStudySettings{}.columns;
  BOOST_TEST(std::ranges::count(defaults, "nlsq-kirchhoff-variational") == 0);  // not by default
  s.columns = {"pid"};
  BOOST_CHECK_THROW(study::control_columns(s), std::invalid_argument);
}
