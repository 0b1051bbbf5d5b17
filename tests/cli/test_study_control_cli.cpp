// `rodlab study control` from the command line (interface spec "Control and learning"): a tiny
// Table 4.1 (one column, one horizon, the middle circle at N = 10) writes its table, study.json
// and run; bad options exit 2 naming the option, with nothing written.
#define BOOST_TEST_MODULE cli_study_control
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

using namespace rodlab::testing::cli;

namespace {
const std::string kScene = quote(std::string(RODLAB_SOURCE_DIR) + "/scenes/control-cable.yaml");
const std::string kCables = quote(std::string(RODLAB_SOURCE_DIR) + "/scenes/cable-driven.yaml");
}  // namespace

// NLSQ-MPC at dt_c = 0.1 s, H = 1, N = 10 on the middle circle: the files of the study, one row,
// below the thesis' 6.90 % of L for that column (Table 4.1).
BOOST_AUTO_TEST_CASE(tiny_study_writes_its_table) {
  Sandbox box;
  const Run r = box.run("study control " + kScene +
                        " --controllers nlsq-implicit --dt-control 0.1 --horizons 1 --tasks track "
                        "--nodes 10 --no-figures --out st");
  BOOST_TEST_REQUIRE(r.status == 0, r.err << r.out);
  for (const char* f : {"st/table.csv", "st/table.md", "st/study.json", "st/figures.json",
                        "st/runs/nlsq-implicit-dt0.1_track_H1.json"})
    BOOST_TEST(fs::is_regular_file(box.work / f), f);
  const auto j = nlohmann::json::parse(read(box.work / "st/study.json"));
  BOOST_TEST_REQUIRE(j["rows"].size() == 1u);
  BOOST_TEST(j["rows"][0]["status"] == "done");
  BOOST_TEST(double(j["rows"][0]["mean_error_pct_L"]) < 6.90);
  const auto run = nlohmann::json::parse(read(box.work / "st/runs/nlsq-implicit-dt0.1_track_H1.json"));
  BOOST_TEST(run["schema"] == "rodlab.control-result/1");
  BOOST_TEST(double(run["summary"]["mean_error_pct_L"]) ==
             double(j["rows"][0]["mean_error_pct_L"]));
  BOOST_TEST(contains(read(box.work / "st/table.md"), "(thesis 6.90 %)"));
}

BOOST_AUTO_TEST_CASE(bad_input_is_refused) {
  Sandbox box;
  const std::string study = "study control " + kScene + " --out st ";
  expect_bad_input(box, study + "--controllers nlsq,lqr", {"--controllers", "nlsq"});
  expect_bad_input(box, study + "--horizons 0,5", {"--horizons"});
  expect_bad_input(box, study + "--horizons x", {"--horizons"});
  expect_bad_input(box, study + "--dt-control 0.05,-1", {"--dt-control"});
  expect_bad_input(box, study + "--controllers lqr --dt-control 0.05", {"--dt-control"});
  expect_bad_input(box, study + "--tasks reach,fly", {"--tasks", "fly"});
  expect_bad_input(box, study + "--targets 0", {"--targets"});
  expect_bad_input(box, study + "--seed -1", {"--seed"});
  expect_bad_input(box, study + "--nodes 10,20", {"--nodes"});
  expect_bad_input(box, study + "--nodes 1", {"--nodes"});
  expect_bad_input(box, study + "--max-wall-time 0", {"--max-wall-time"});
  expect_bad_input(box, study + "--schemes variational", {"--schemes"});
  expect_bad_input(box, study + "--jobs 2", {"--jobs"});
  expect_bad_input(box, "study control " + kCables + " --out st", {"--tasks", "trajectory"});
  expect_bad_input(box, "study convergence " + kScene + " --horizons 1 --out st", {"--horizons"});
  box.write("file", "x");
  expect_bad_input(box, "study control " + kScene + " --out file", {"--out"});
}
