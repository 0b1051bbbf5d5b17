// `rodlab train` and `rodlab control --controller policy` from the command line (interface spec
// "Control and learning", docs/learning.md): DDPG trains a reach-one policy on the control robot
// (implicit-midpoint, N = 20, dt_c = 0.05 s, seed 1), whose target lies 10 mm outside the static
// workspace, and the trained policy reaches it (thesis 4.4.2: within 5 % of L) in real time; bad
// input is refused (exit 2, nothing written).
#define BOOST_TEST_MODULE cli_train
#include <boost/test/unit_test.hpp>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

using namespace rodlab::testing::cli;

namespace {
const std::string kScene = quote(std::string(RODLAB_SOURCE_DIR) + "/scenes/control-cable.yaml");
}  // namespace

// 1500 samples (about 3 s; measured: the deterministic policy reaches from 1000 samples on, 500
// do not), then the policy as a controller: the target of the policy file, reached within 5 % of
// L within 100 steps (measured: 2 steps, 2.3 mm), every tension inside [0, 0.5] N, one network
// evaluation per step (real-time ratio far below the thesis' 0.01).
BOOST_AUTO_TEST_CASE(ddpg_learns_to_reach_one_point) {
  Sandbox box;
  const Run t = box.run("train " + kScene +
                        " --algorithm ddpg --task reach-one --samples 1500 --seed 1 --out p.json");
  BOOST_TEST_REQUIRE(t.status == 0, t.err);
  BOOST_TEST(contains(t.out, "policy written to p.json"));
  const auto p = nlohmann::json::parse(read(box.work / "p.json"));
  BOOST_TEST(p["schema"] == "rodlab.policy/1");
  BOOST_TEST(p["algorithm"] == "ddpg");
  BOOST_TEST(p["task"] == "reach-one");
  BOOST_TEST(p["training"]["samples"] == 1500);
  BOOST_TEST(p["network"]["sizes"].front() == 9);
  BOOST_TEST(p["network"]["sizes"].back() == 4);
  BOOST_TEST(p["goal"].size() == 3u);
  const Run c = box.run("control " + kScene +
                        " --controller policy --policy p.json --task reach --out r.json");
  BOOST_TEST_REQUIRE(c.status == 0, c.err);
  const auto r = nlohmann::json::parse(read(box.work / "r.json"));
  BOOST_TEST(r["targets"]["drawn_from"] == "policy");
  BOOST_TEST(r["summary"]["samples"] == 1500);  // what the policy cost
  BOOST_TEST(r["targets"]["points"][0] == p["goal"]);
  BOOST_TEST(r["episodes"][0]["success"] == true);
  BOOST_TEST(double(r["episodes"][0]["min_error"]) < 0.005);
  BOOST_TEST(double(r["summary"]["real_time_ratio_max"]) < 0.01);
  for (const auto& u : r["series"]["u"])
    for (double v : u) BOOST_TEST((v >= 0.0 && v <= 0.5));
}

// GPS on the same point (thesis 4.4.3: 10/10 after 5000 samples): 1200 samples, 20 iterations
// of 3 trajectories of 20 steps (1.4 s), then the policy reaches it within 5 % of L (measured:
// 1.04 mm; seeds 1-5 all reach their targets from 1200 samples, best 1.0-3.3 % of L).
BOOST_AUTO_TEST_CASE(gps_learns_to_reach_one_point) {
  Sandbox box;
  const Run t = box.run("train " + kScene +
                        " --algorithm gps --task reach-one --samples 1200 --seed 1 --out g.json");
  BOOST_TEST_REQUIRE(t.status == 0, t.err);
  BOOST_TEST(contains(t.out, "20 iterations of 1 conditions x 3 trajectories x 20 steps"));
  const auto p = nlohmann::json::parse(read(box.work / "g.json"));
  BOOST_TEST(p["algorithm"] == "gps");
  BOOST_TEST(p["training"]["samples"] == 1200);
  BOOST_TEST(p["network"]["output_activation"] == "identity");
  const Run c = box.run("control " + kScene +
                        " --controller policy --policy g.json --task reach --out r.json");
  BOOST_TEST_REQUIRE(c.status == 0, c.err);
  const auto r = nlohmann::json::parse(read(box.work / "r.json"));
  BOOST_TEST(r["episodes"][0]["success"] == true);
  BOOST_TEST(double(r["episodes"][0]["min_error"]) < 0.005);
  BOOST_TEST(double(r["summary"]["real_time_ratio_max"]) < 0.01);
  // the study's protocol (docs/learning.md "Study"): the whole training horizon (T = 20 steps,
  // training.episode_steps) without stopping at success; the closest approach can only improve
  // on the first step within the threshold, and success stays "reached at some step"
  BOOST_TEST(p["training"]["episode_steps"] == 20);
  const Run f = box.run("control " + kScene + " --controller policy --policy g.json --task reach "
                        "--set control.stop_at_success=false --set control.max_steps=20 "
                        "--out f.json");
  BOOST_TEST_REQUIRE(f.status == 0, f.err);
  const auto w = nlohmann::json::parse(read(box.work / "f.json"));
  BOOST_TEST(w["episodes"][0]["steps"] == 20);
  BOOST_TEST(w["episodes"][0]["success"] == true);
  BOOST_TEST(int(r["episodes"][0]["steps"]) < 20);
  BOOST_TEST(double(w["episodes"][0]["min_error"]) <= double(r["episodes"][0]["min_error"]));
}

// The scene's learning section reaches the trainer: a 16-unit actor (learning.ddpg.actor_hidden)
// gives a 9-16-4 network in the policy file; the rest keeps the defaults (tanh outputs).
BOOST_AUTO_TEST_CASE(learning_section_sets_the_hyper_parameters) {
  Sandbox box;
  const Run t = box.run("train " + kScene +
                        " --algorithm ddpg --task reach-any --samples 40 --out p.json "
                        "--set 'learning.ddpg.actor_hidden=[16]' --set learning.ddpg.activation=tanh");
  BOOST_TEST_REQUIRE(t.status == 0, t.err);
  const auto p = nlohmann::json::parse(read(box.work / "p.json"));
  BOOST_TEST(p["network"]["sizes"] == nlohmann::json::array({9, 16, 4}));
  BOOST_TEST(p["network"]["hidden_activation"] == "tanh");
  BOOST_TEST(p["network"]["output_activation"] == "tanh");
  expect_bad_input(box, "train " + kScene + " --algorithm ddpg --task reach-any --samples 40 "
                                            "--set learning.ddpg.gamma=2",
                   {"learning.ddpg.gamma"});
}

BOOST_AUTO_TEST_CASE(bad_input_is_refused) {
  Sandbox box;
  expect_bad_input(box, "train " + kScene + " --algorithm ddpg --task reach-one --out p.json",
                   {"--samples", "required"});
  expect_bad_input(box, "train " + kScene + " --task reach-one --samples 10 --out p.json",
                   {"--algorithm", "required"});
  expect_bad_input(box, "train " + kScene + " --algorithm gps --task reach-one --samples 10",
                   {"--samples", "GPS", "one iteration", "= 60 samples"});
  expect_bad_input(box, "train " + kScene + " --algorithm ddpg --task reach-all --samples 10",
                   {"--task"});
  expect_bad_input(box, "train " + kScene + " --algorithm ddpg --task reach-one --samples 10 "
                                            "--jobs 0",
                   {"--jobs"});
  expect_bad_input(box, "train " + kScene + " --algorithm ddpg --task reach-one --samples 10 "
                                            "--out p.csv",
                   {"--out", ".json"});
  expect_bad_input(box, "control " + kScene + " --controller policy --task reach --out r.json",
                   {"--policy"});
  expect_bad_input(box, "control " + kScene + " --controller policy --policy none.json --out r.json",
                   {"--policy", "none.json"});
  box.write("bad.json", "{\"schema\": \"rodlab.policy/1\"}\n");
  expect_bad_input(box, "control " + kScene + " --controller policy --policy bad.json --out r.json",
                   {"--policy", "bad.json", "algorithm"});
}
