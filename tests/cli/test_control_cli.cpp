// `rodlab control` from the command line (interface spec "Control and learning"): the example
// scene tracked by NLSQ-MPC below the 1 % of L with every tension inside its limits, an
// out-of-reach target answered with its closest tip (exit 1, reason), bad input refused (exit 2,
// nothing written).
#define BOOST_TEST_MODULE cli_control
#include <boost/test/unit_test.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

using namespace rodlab::testing::cli;

namespace {
const std::string kScene = quote(std::string(RODLAB_SOURCE_DIR) + "/scenes/control-cable.yaml");
const std::string kCables = quote(std::string(RODLAB_SOURCE_DIR) + "/scenes/cable-driven.yaml");

/// `rodlab control SCENE ARGS --out result.json` in the sandbox: the exit status must be
/// `status`; the result file, parsed.
nlohmann::json control(const Sandbox& box, const std::string& scene, const std::string& args,
                       int status = 0) {
  const Run r = box.run("control " + scene + " " + args + " --out result.json");
  BOOST_TEST_REQUIRE(r.status == status, r.err);
  return nlohmann::json::parse(read(box.work / "result.json"));
}

/// Every input of the series inside the control robot's [0, 0.5] N.
void inputs_within_limits(const nlohmann::json& j) {
  for (const auto& u : j["series"]["u"])
    for (double v : u) BOOST_TEST((v >= 0.0 && v <= 0.5));
}
}  // namespace

// The middle circle (r = 1 cm, 4 s) at dt_c = 0.1 s, H = 2 on the implicit midpoint (N = 20,
// staggered grid): 40 control steps, mean error below 1 % of L (issue #14; the thesis' NLSQ on
// its implicit scheme: 3.45 % at dt 0.01 s, 6.90 % at 0.1 s), tensions within [0, 0.5] N.
BOOST_AUTO_TEST_CASE(nlsq_mpc_tracks_the_middle_circle) {
  Sandbox box;
  const auto j = control(box, kScene, "--controller nlsq-mpc --task track --horizon 2 "
                                      "--dt-control 0.1");
  BOOST_TEST(j["schema"] == "rodlab.control-result/1");
  BOOST_TEST(j["controller"] == "nlsq-mpc");
  BOOST_TEST(j["scheme"] == "implicit-midpoint");
  BOOST_TEST(j["series"]["t"].size() == 40u);
  inputs_within_limits(j);
  const double mean = j["summary"]["mean_error_pct_L"];
  BOOST_TEST_MESSAGE("mean tracking error " << mean << " % of L");
  BOOST_TEST(mean < 1.0);
  BOOST_TEST(j["episodes"][0]["success"] == true);
}

// Dynamic reach (thesis 4.4.1): NLSQ-MPC with H = 5 on targets drawn from the dynamic workspace
// (seed 1; none within the 5 % threshold of the rest tip), all reached within max_steps (the
// thesis: 10 of 10 for NLSQ on its implicit scheme; measured 10 of 10 here too).
BOOST_AUTO_TEST_CASE(nlsq_mpc_reaches_dynamic_workspace_targets) {
  Sandbox box;
  const auto j = control(box, kScene, "--controller nlsq-mpc --task reach --targets 5 --horizon 5");
  BOOST_TEST(j["targets"]["drawn_from"] == "dynamic-workspace");
  BOOST_TEST(j["targets"]["points"].size() == 5u);
  for (const auto& p : j["targets"]["points"]) {
    const double dx = p[0], dy = p[1], dz = double(p[2]) - 0.1;
    BOOST_TEST(std::sqrt(dx * dx + dy * dy + dz * dz) > 0.005);
  }
  BOOST_TEST(j["summary"]["success_rate"] == 1.0);
}

// Quasi-static reach of ten targets drawn from the static workspace (seed 3): all reached to the
// threshold (5 % of L), inputs within limits; the targets and their source are in the result.
BOOST_AUTO_TEST_CASE(quasi_static_reaches_drawn_targets) {
  Sandbox box;
  const auto j = control(box, kCables, "--controller quasi-static --task reach --targets 10 "
                                       "--seed 3");
  BOOST_TEST(j["targets"]["drawn_from"] == "static-workspace");
  BOOST_TEST(j["targets"]["points"].size() == 10u);
  BOOST_TEST(j["seed"] == 3);
  BOOST_TEST(j["summary"]["success_rate"] == 1.0);
  for (const auto& e : j["episodes"]) BOOST_TEST(double(e["final_error"]) < 0.005);
}

// Reach and hold by LQR about each target's equilibrium (two targets drawn from the static
// workspace, implicit midpoint N = 10): both held within 5 % of L for hold_steps steps, every
// tension inside its limits.
BOOST_AUTO_TEST_CASE(lqr_holds_drawn_targets) {
  Sandbox box;
  const auto j = control(box, kScene, "--controller lqr --task hold --targets 2 --nodes 10");
  BOOST_TEST(j["controller"] == "lqr");
  BOOST_TEST(j["summary"]["success_rate"] == 1.0);
  inputs_within_limits(j);
}

// iLQR tracks a quarter of the middle circle (N = 6, H = 2, dt_c = 0.1 s: 10 control steps) below
// 1 % of L with every tension inside its limits (docs/control.md "iLQR").
BOOST_AUTO_TEST_CASE(ilqr_tracks_a_quarter_circle) {
  Sandbox box;
  const auto j = control(box, kScene, "--controller ilqr --task track --horizon 2 --nodes 6 "
                                      "--dt-control 0.1 "
                                      "--set control.trajectory.circle.laps=0.25");
  BOOST_TEST(j["controller"] == "ilqr");
  BOOST_TEST(j["series"]["t"].size() == 10u);
  BOOST_TEST(double(j["summary"]["mean_error_pct_L"]) < 1.0);
  inputs_within_limits(j);
}

// LQR tracks the middle circle's first quarter (N = 10, dt_c = 0.05 s: 20 control steps) along its
// quasi-static equilibria (one inverse-statics solve per step, the gain of the first target)
// below the thesis' LQR (Table 4.1: 2.03 % of L), every tension inside its limits.
BOOST_AUTO_TEST_CASE(lqr_tracks_a_quarter_circle) {
  Sandbox box;
  const auto j = control(box, kScene, "--controller lqr --task track --nodes 10 "
                                      "--set control.trajectory.circle.laps=0.25");
  BOOST_TEST(j["series"]["t"].size() == 20u);
  BOOST_TEST(double(j["summary"]["mean_error_pct_L"]) < 2.03);
  inputs_within_limits(j);
}

// The real-time iteration (--iterations 1): one iLQR iteration per control step, warm-started
// from the shifted plan; on the quarter circle as above it tracks to the same bound (measured:
// the full middle circle at N = 10, H = 10 to 0.037 % of L against 0.029 % converged).
BOOST_AUTO_TEST_CASE(ilqr_real_time_iteration_tracks_a_quarter_circle) {
  Sandbox box;
  const auto j = control(box, kScene, "--controller ilqr --task track --horizon 2 --nodes 6 "
                                      "--dt-control 0.1 --iterations 1 "
                                      "--set control.trajectory.circle.laps=0.25");
  BOOST_TEST(double(j["summary"]["mean_error_pct_L"]) < 1.0);
  for (const auto& k : j["series"]["iterations"]) BOOST_TEST(int(k) <= 1);
  inputs_within_limits(j);
}

// A model-plant split (--model-scheme): a Kirchhoff rod on `variational` (N = 10, its step below
// the viscous stability limit, about 7000 per second) driven along the middle circle's first
// quarter by NLSQ-MPC predicting with implicit-midpoint (one step per control step, H = 2). The
// inextensible rod cannot shorten to the circle's height: its closest feasible tips (the
// quasi-static controller, inverse statics on the same rod) are 0.6245 % of L away. After the
// start's transient (1.6 mm at the third step) the controller tracks on that floor: over the
// last five steps within 0.02 % of L of it (measured 0.001 %), and below 1 % of L on average
// over the quarter (measured 0.73 %). The result names the model.
BOOST_AUTO_TEST_CASE(nlsq_mpc_drives_a_variational_plant_predicting_with_the_implicit_midpoint) {
  Sandbox box;
  const std::string rod = " --nodes 10 --set rod.model=kirchhoff "
                          "--set control.trajectory.circle.laps=0.25";
  const auto floor = control(box, kScene, "--controller quasi-static --task track" + rod);
  const auto j = control(box, kScene, "--controller nlsq-mpc --task track --horizon 2 "
                                      "--scheme variational --model-scheme implicit-midpoint" +
                                          rod);
  BOOST_TEST(j["scheme"] == "variational");
  BOOST_TEST(j["model_scheme"] == "implicit-midpoint");
  BOOST_TEST(j["series"]["t"].size() == 20u);
  const double mean = j["summary"]["mean_error_pct_L"];
  const double closest = floor["summary"]["mean_error_pct_L"];
  const auto& error = j["series"]["error"];
  double last = 0.0;  // the last five steps' mean error, % of L
  for (std::size_t k = error.size() - 5; k < error.size(); ++k) last += double(error[k]) / 5;
  last *= 100.0 / 0.1;
  BOOST_TEST_MESSAGE("Kirchhoff quarter circle: " << mean << " % of L, the last five steps "
                                                  << last << " %, closest feasible " << closest);
  BOOST_TEST(closest > 0.3);  // the circle lies outside the Kirchhoff rod's reach
  BOOST_TEST(std::abs(last - closest) < 0.02);
  BOOST_TEST(mean < 1.0);
  inputs_within_limits(j);
  const auto same = control(box, kScene, "--controller nlsq-mpc --task track --horizon 2 "
                                         "--dt-control 0.1 --nodes 6");
  BOOST_TEST(same["model_scheme"].is_null());  // the plant's own scheme
}

// A target beyond the rod's length: the closest feasible tip, exit 1, the reason in the result.
BOOST_AUTO_TEST_CASE(unreachable_target_exits_1_with_a_reason) {
  Sandbox box;
  const auto j = control(box, kCables, "--controller quasi-static --task reach "
                                       "--set 'control.targets=[[0, 0, 0.2]]'", 1);
  BOOST_TEST(!j["reason"].is_null());
  BOOST_TEST(contains(j["reason"].get<std::string>(), "unreachable"));
  BOOST_TEST(j["episodes"][0]["success"] == false);
  BOOST_TEST(double(j["episodes"][0]["final_error"]) > 0.09);  // the rod is 0.1 m long
}

BOOST_AUTO_TEST_CASE(bad_input_is_refused) {
  Sandbox box;
  expect_bad_input(box, "control " + kScene + " --controller policy --out x.json",
                   {"--controller", "policy"});
  expect_bad_input(box, "control " + kScene + " --controller pid --out x.json", {"--controller"});
  expect_bad_input(box, "control " + kScene + " --horizon 0 --out x.json", {"--horizon"});
  expect_bad_input(box, "control " + kScene + " --iterations 0 --out x.json", {"--iterations"});
  expect_bad_input(box, "control " + kScene + " --dt-control -1 --out x.json", {"--dt-control"});
  expect_bad_input(box, "control " + kCables + " --task track --out x.json", {"trajectory"});
  expect_bad_input(box, "control " + kScene + " --set control.horizon=0 --out x.json", {"control.horizon"});
  expect_bad_input(box, "control " + kScene + " --scheme ida --out x.json", {"control"});
  expect_bad_input(box, "control " + kScene + " --model-scheme bdf-alpha --out x.json",
                   {"--model-scheme", "bdf-alpha"});
}
