#define BOOST_TEST_MODULE example_scenes
#include <boost/test/unit_test.hpp>

// Every scene in scenes/ loads, is named after its file and opens with a comment saying what it
// shows (one test case per file, scene_loads_NAME); the ones that reproduce the thesis carry
// its numbers (Table 2.1, sections 2.7, 3.5).

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <variant>
#include <vector>

#include "rodlab/io/scene_loader.hpp"

namespace fs = std::filesystem;
using namespace rodlab;

namespace examples {

const fs::path kScenes = fs::path(RODLAB_SOURCE_DIR) / "scenes";

std::vector<std::string> scene_files() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kScenes))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

scene::Scene load(const std::string& file) { return io::load_scene((kScenes / file).string()); }

/// Table 2.1: E 1 MPa, G 0.33 MPa, rho 1000 kg/m^3, D 1 cm, L 10 cm.
void check_table_2_1(const scene::Scene& s) {
  BOOST_TEST(s.rod.length == 0.1);
  BOOST_TEST(std::get<rod::Circle>(s.rod.section).diameter == 0.01);
  BOOST_TEST(s.rod.material.E == 1.0e6);
  BOOST_TEST(s.rod.material.G == 0.33e6);
  BOOST_TEST(s.rod.material.rho == 1000.0);
}

void check_scene_loads(const std::string& file) {
  const scene::Scene s = load(file);
  BOOST_TEST(s.name == fs::path(file).stem().string());
  std::ifstream in(kScenes / file);
  std::string first;
  std::getline(in, first);
  BOOST_TEST(first.starts_with("# "), file << " does not open with a comment");
}

[[maybe_unused]] const bool registered = [] {
  auto& suite = boost::unit_test::framework::master_test_suite();
  for (const std::string& file : scene_files()) {
    const std::string name = "scene_loads_" + fs::path(file).stem().string();
    suite.add(boost::unit_test::make_test_case([file] { check_scene_loads(file); }, name, __FILE__,
                                               __LINE__));
  }
  return true;
}();

}  // namespace examples

using namespace examples;

BOOST_AUTO_TEST_CASE(the_example_scenes_are_there) {
  const auto files = scene_files();
  for (const char* name :
       {"cantilever-gravity.yaml", "cantilever-gravity-kirchhoff.yaml", "fixed-ends.yaml",
        "cable-driven.yaml", "viscous-cantilever.yaml", "cable-steps.yaml", "fluidic-chamber.yaml",
        "muscle.yaml", "tip-moment-circle.yaml", "control-cable.yaml"})
    BOOST_TEST((std::find(files.begin(), files.end(), name) != files.end()), name);
}

BOOST_AUTO_TEST_CASE(cantilever_gravity_is_the_thesis_test_rod) {
  const auto s = load("cantilever-gravity.yaml");
  check_table_2_1(s);
  BOOST_TEST((s.rod.model == rod::ModelKind::cosserat));
  BOOST_TEST((*s.loads.gravity == scene::Vector3(-9.81, 0, 0)));
  BOOST_TEST(!s.tip_clamped());
  BOOST_TEST(s.solver.scheme == "chebyshev");
  BOOST_TEST(s.solver.nodes == 24);
  BOOST_TEST(s.solver.tol == 1e-10);
  const auto k = load("cantilever-gravity-kirchhoff.yaml");
  check_table_2_1(k);
  BOOST_TEST((k.rod.model == rod::ModelKind::kirchhoff));
}

BOOST_AUTO_TEST_CASE(fixed_ends_tip_is_clamped_one_centimetre_aside) {
  const auto s = load("fixed-ends.yaml");
  check_table_2_1(s);
  BOOST_TEST(!s.loads.gravity.has_value());
  const auto& tip = std::get<scene::ClampedTip>(s.tip);
  BOOST_TEST((tip.pose.translation() == scene::Vector3(0.01, 0, 0.1)));
  BOOST_TEST((tip.pose.rotation_matrix() == Eigen::Matrix3d::Identity()));
}

BOOST_AUTO_TEST_CASE(cable_driven_has_four_cables_at_four_millimetres) {
  const auto s = load("cable-driven.yaml");
  BOOST_TEST_REQUIRE(s.actuators.size() == 4u);
  double total = 0.0;
  for (const auto& a : s.actuators) {
    const auto& c = std::get<scene::Cable>(a);
    BOOST_TEST(c.offset.at(0).norm() == 0.004, boost::test_tools::tolerance(1e-15));
    total += c.tension->at(0);
  }
  BOOST_TEST(total == 0.5);
}

BOOST_AUTO_TEST_CASE(viscous_cantilever_runs_ten_seconds) {
  const auto s = load("viscous-cantilever.yaml");
  BOOST_TEST(s.rod.material.viscosity == 300.0);
  BOOST_TEST(*s.dynamics->t_end == 10.0);
  BOOST_TEST(!s.dynamics->dt.has_value());
}

BOOST_AUTO_TEST_CASE(tip_moment_closes_the_rod_into_a_circle) {
  const auto s = load("tip-moment-circle.yaml");
  const double d = std::get<rod::Circle>(s.rod.section).diameter;
  const double I = std::numbers::pi * std::pow(d, 4) / 64.0;
  const auto& w = std::get<scene::FreeTip>(s.tip).wrench;
  const double M = w.moment.at(0).x();
  BOOST_TEST(M * s.rod.length / (s.rod.material.E * I) == 2.0 * std::numbers::pi,
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST((w.frame == scene::Frame::body));
}

BOOST_AUTO_TEST_CASE(control_cable_is_the_thesis_control_robot_tracking_a_centimetre_circle) {
  // Chapter 4: the Table 2.1 rod, alpha = 300 Pa s, four cables at 4 mm within [0, 0.5] N,
  // slack at the start; N = 20, implicit-midpoint; the middle circle (radius 1 cm) of 0.5/1/1.5.
  const auto s = load("control-cable.yaml");
  check_table_2_1(s);
  BOOST_TEST(s.rod.material.viscosity == 300.0);
  BOOST_TEST(!s.loads.gravity.has_value());
  BOOST_TEST_REQUIRE(s.actuators.size() == 4u);
  for (const auto& a : s.actuators) {
    const auto& c = std::get<scene::Cable>(a);
    BOOST_TEST(c.offset.at(0).norm() == 0.004, boost::test_tools::tolerance(1e-15));
    BOOST_TEST(c.tension->at(0) == 0.0);
    BOOST_TEST((*c.limits == std::pair<double, double>(0.0, 0.5)));
  }
  BOOST_TEST(s.solver.nodes == 20);
  BOOST_TEST(*s.dynamics->scheme == "implicit-midpoint");
  BOOST_TEST_REQUIRE(s.control.has_value());
  BOOST_TEST((s.control->task == scene::ControlTask::track));
  const auto& circle = s.control->trajectory->circle;
  BOOST_TEST(circle.radius == 0.01);
  // centred on the axis, below the rest tip (0.1 m) by less than the 1.5 cm circle's drop
  BOOST_TEST((circle.center.head<2>() == Eigen::Vector2d::Zero()));
  BOOST_TEST(circle.center.z() < s.rod.length);
  BOOST_TEST(circle.center.z() > 0.098);
  BOOST_TEST((circle.normal == scene::Vector3::UnitZ()));
}
