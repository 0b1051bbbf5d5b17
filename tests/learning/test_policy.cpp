// The policy file (solvers/learning/policy.hpp, rodlab.policy/1): a round trip keeps every
// field and the network bit for bit; a wrong schema, a missing field and sizes that do not match
// the network are refused with the field named.
#define BOOST_TEST_MODULE learning_policy
#include <boost/test/unit_test.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "rodlab/solvers/learning/policy.hpp"

namespace l = rodlab::solvers::learning;

namespace {

l::Policy sample_policy() {
  l::Policy p;
  p.algorithm = "ddpg";
  p.task = "track";
  p.scene = "control-cable";
  p.scheme = "implicit-midpoint";
  p.nodes = 20;
  p.dt_control = 0.05;
  p.layout = {.goal_velocity = true, .state_nodes = 2};
  p.length = 0.1;
  p.period = 0.2260419823497288;
  p.lower = Eigen::VectorXd::Zero(4);
  p.upper = Eigen::VectorXd::Constant(4, 0.5);
  p.training = {1234, 56, 7, 8.5, 20};
  p.network = l::Mlp<double>(l::MlpConfig{{12 + 2 * 12, 8, 4}, l::Activation::relu,
                                          l::Activation::tanh, 3, 3e-3});
  return p;
}

/// `text` with the JSON field at `pointer` replaced by `value`.
std::string with(const std::string& text, const std::string& pointer, nlohmann::json value) {
  auto j = nlohmann::ordered_json::parse(text);
  j[nlohmann::ordered_json::json_pointer(pointer)] = value;
  return j.dump();
}

void refused(const std::string& text, const std::string& part) {
  BOOST_CHECK_EXCEPTION(l::policy_from_json(text), std::invalid_argument,
                        [&](const std::invalid_argument& e) {
                          BOOST_TEST_MESSAGE(e.what());
                          return std::string(e.what()).find(part) != std::string::npos;
                        });
}

}  // namespace

BOOST_AUTO_TEST_CASE(round_trip_keeps_every_field) {
  l::Policy p = sample_policy();
  for (const bool goal : {false, true}) {
    if (goal) p.goal = rodlab::lie::Vector3(0.0295, 0.0155, 0.0925);
    const l::Policy q = l::policy_from_json(l::to_json(p));
    BOOST_TEST(q.algorithm == p.algorithm);
    BOOST_TEST(q.task == p.task);
    BOOST_TEST(q.scene == p.scene);
    BOOST_TEST(q.scheme == p.scheme);
    BOOST_TEST(q.nodes == p.nodes);
    BOOST_TEST(q.dt_control == p.dt_control);
    BOOST_TEST(q.layout.goal_velocity == p.layout.goal_velocity);
    BOOST_TEST(q.layout.state_nodes == p.layout.state_nodes);
    BOOST_TEST(q.length == p.length);
    BOOST_TEST(q.period == p.period);  // shortest round-trip decimal: bit for bit
    BOOST_TEST(q.lower == p.lower);
    BOOST_TEST(q.upper == p.upper);
    BOOST_TEST(q.training.samples == 1234);
    BOOST_TEST(q.training.episodes == 56);
    BOOST_TEST(q.training.seed == 7u);
    BOOST_TEST(q.training.wall_time_s == 8.5);
    BOOST_TEST(q.training.episode_steps == 20);
    BOOST_TEST(q.goal.has_value() == goal);
    if (goal) BOOST_TEST((*q.goal - *p.goal).norm() == 0.0);
    BOOST_TEST((q.network.parameters() - p.network.parameters()).norm() == 0.0);
    BOOST_TEST(q.network.sizes() == p.network.sizes());
  }
}

BOOST_AUTO_TEST_CASE(bad_files_name_the_field) {
  const std::string good = l::to_json(sample_policy());
  refused("not json", "not JSON");
  refused(with(good, "/schema", "rodlab.mlp/1"), "schema");
  refused(with(good, "/nodes", "twenty"), "nodes");
  refused(with(good, "/observation/size", 9), "observation.size");
  refused(with(good, "/action/lower", nlohmann::json::array({0, 0, 0})), "action.lower");
  refused(with(good, "/goal", nlohmann::json::array({0, 0})), "goal");
  auto j = nlohmann::ordered_json::parse(good);
  j.erase("training");
  refused(j.dump(), "training is missing");
}

// The policy file read by Python (scripts/policy_python.py): its plain-Python evaluation (json
// and math only) equals the network's infer() to 1e-13 relative on 20 observations; where
// PyTorch is installed (python3-torch), torch's float64 evaluation too, and the file written
// back from torch's state_dict loads into the same network bit for bit. Skipped (with a
// message) without python3.
BOOST_AUTO_TEST_CASE(python_and_torch_read_the_policy_file) {
  namespace fs = std::filesystem;
  if (std::system("python3 -c 'import json' > /dev/null 2>&1") != 0) {
    BOOST_TEST_MESSAGE("python3 not found: skipped");
    return;
  }
  l::Policy p = sample_policy();
  p.network = l::Mlp<double>(l::MlpConfig{{12 + 2 * 12, 16, 16, 4}, l::Activation::relu,
                                          l::Activation::tanh, 5});
  const fs::path dir = fs::temp_directory_path() / ("rodlab-policy-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "p.json") << l::to_json(p);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  nlohmann::json inputs = nlohmann::json::array();
  std::vector<Eigen::VectorXd> xs;
  for (int i = 0; i < 20; ++i) {
    Eigen::VectorXd x(p.network.input_size());
    for (auto& v : x) v = u(rng);
    xs.push_back(x);
    inputs.push_back(std::vector<double>(x.data(), x.data() + x.size()));
  }
  std::ofstream(dir / "in.json") << inputs.dump();
  const std::string cmd = "python3 " + std::string(RODLAB_SOURCE_DIR) + "/scripts/policy_python.py " +
                          (dir / "p.json").string() + " " + (dir / "in.json").string() + " " +
                          (dir / "out.json").string() + " --torch-resave " +
                          (dir / "torch.json").string();
  BOOST_TEST_REQUIRE(std::system(cmd.c_str()) == 0, cmd);
  const auto out = nlohmann::json::parse(std::ifstream(dir / "out.json"));
  Eigen::VectorXd y(4);
  for (int i = 0; i < 20; ++i) {
    p.network.infer(xs[i], y);
    for (int k = 0; k < 4; ++k) {
      BOOST_TEST(out["python"][i][k].get<double>() == y[k], boost::test_tools::tolerance(1e-13));
      if (!out["torch"].is_null())
        BOOST_TEST(out["torch"][i][k].get<double>() == y[k], boost::test_tools::tolerance(1e-13));
    }
  }
  if (out["torch"].is_null()) {
    BOOST_TEST_MESSAGE("torch not installed: the plain-Python evaluation only");
  } else {
    BOOST_TEST_MESSAGE("torch: evaluated, and its state_dict written back");
    std::stringstream text;
    text << std::ifstream(dir / "torch.json").rdbuf();
    const l::Policy q = l::policy_from_json(text.str());
    BOOST_TEST((q.network.parameters().array() == p.network.parameters().array()).all());
  }
  fs::remove_all(dir);
}
