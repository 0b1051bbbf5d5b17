#define BOOST_TEST_MODULE scene_loader
#include <boost/test/unit_test.hpp>

// Good scene input: every field reaches the Scene struct with its value, defaults are filled,
// rotations are exact, and --set overrides create and replace fields.
// Reference values are the numbers written in the YAML (tests/data/scenes/good/).

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <variant>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/lie/se3.hpp"
#include "rodlab/lie/so3.hpp"

namespace fs = std::filesystem;
using namespace rodlab;
using io::load_scene;
using io::load_scene_from_string;
using io::Override;
using scene::Vector2;
using scene::Vector3;

namespace {

const fs::path kGoodDir = fs::path(RODLAB_TEST_DATA) / "scenes" / "good";

const std::string kMinimal = R"(schema: rodlab.scene/1
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000}
tip: {free: {}}
)";

scene::Scene with(const std::string& extra, std::initializer_list<const char*> sets = {}) {
  std::vector<Override> overrides;
  for (const char* s : sets) overrides.push_back(io::parse_override(s));
  return load_scene_from_string(kMinimal + extra, "minimal.yaml", overrides);
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

template <class T, class V>
const T& as(const V& v) {
  BOOST_TEST_REQUIRE(std::holds_alternative<T>(v));
  return std::get<T>(v);
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_field_round_trips) {
  const std::string path = (kGoodDir / "full.yaml").string();
  const scene::Scene s = load_scene(path);
  BOOST_TEST(s.schema == "rodlab.scene/1");
  BOOST_TEST(s.name == "full-scene");
  BOOST_TEST(s.source_path == path);

  // rod
  BOOST_TEST((s.rod.model == rod::ModelKind::kirchhoff));
  BOOST_TEST(s.rod.length == 0.2);
  const auto& tube = as<rod::Tube>(s.rod.section);
  BOOST_TEST(tube.outer_diameter == 0.012);
  BOOST_TEST(tube.inner_diameter == 0.004);
  BOOST_TEST(s.rod.material.E == 2.0e6);
  BOOST_TEST(s.rod.material.G == 2.0e6 / (2.0 * 1.25), boost::test_tools::tolerance(1e-15));
  BOOST_TEST(s.rod.material.rho == 1100.0);
  BOOST_TEST(s.rod.material.viscosity == 300.0);
  BOOST_TEST((s.rod.reference_twist == (scene::Vector6() << 0.5, 0, 0, 0, 0, 1).finished()));

  // base: axis [0, 0, 2] is normalised
  BOOST_TEST((s.base.pose.translation() == Vector3(0.1, 0.2, 0.3)));
  BOOST_TEST(max_abs(s.base.pose.rotation_matrix() - lie::SO3::exp(Vector3(0, 0, 0.5)).matrix()) <=
             1e-15);

  // tip
  const auto& tip = as<scene::FreeTip>(s.tip);
  BOOST_TEST(!s.tip_clamped());
  BOOST_TEST(tip.wrench.moment.is_constant());
  BOOST_TEST((tip.wrench.moment.at(0.0) == Vector3(0.01, 0.02, 0.03)));
  BOOST_TEST((tip.wrench.force.kind() == scene::VectorSchedule::Kind::ramp));
  BOOST_TEST(tip.wrench.force.points().size() == 2u);
  BOOST_TEST((tip.wrench.force.at(0.5) == Vector3(0.05, 0, 0)));
  BOOST_TEST((tip.wrench.frame == scene::Frame::world));

  // loads
  BOOST_TEST_REQUIRE(s.loads.gravity.has_value());
  BOOST_TEST((*s.loads.gravity == Vector3(0, 0, -9.81)));
  BOOST_TEST_REQUIRE(s.loads.drag.has_value());
  BOOST_TEST(s.loads.drag->fluid_density == 1000.0);
  BOOST_TEST((s.loads.drag->laminar == (scene::Vector6() << 0, 0, 0, 1, 2, 3).finished()));
  BOOST_TEST((s.loads.drag->turbulent == (scene::Vector6() << 0, 0, 0, 0.5, 0.5, 0.25).finished()));
  BOOST_TEST_REQUIRE(s.loads.buoyancy.has_value());
  BOOST_TEST(s.loads.buoyancy->fluid_density == 1000.0);
  BOOST_TEST_REQUIRE(s.loads.distributed.has_value());
  BOOST_TEST((s.loads.distributed->moment.at(0) == Vector3(0, 0, 0.001)));
  BOOST_TEST((s.loads.distributed->force.at(0) == Vector3(0.1, 0, 0)));
  BOOST_TEST((s.loads.distributed->frame == scene::Frame::body));

  BOOST_TEST_REQUIRE(s.actuators.size() == 5u);
  {
    const auto& c = as<scene::Cable>(s.actuators[0]);
    BOOST_TEST(c.offset.points.size() == 1u);
    BOOST_TEST((c.offset.at(0.05) == Vector2(0.004, 0)));
    BOOST_TEST_REQUIRE(c.tension.has_value());
    BOOST_TEST(c.tension->is_constant());
    BOOST_TEST(c.tension->at(3.0) == 0.5);
    BOOST_TEST(!c.displacement.has_value());
    BOOST_TEST_REQUIRE(c.span.has_value());
    BOOST_TEST(c.span->s0 == 0.0);
    BOOST_TEST(c.span->s1 == 0.1);
    BOOST_TEST_REQUIRE(c.limits.has_value());
    BOOST_TEST(c.limits->first == 0.0);
    BOOST_TEST(c.limits->second == 1.0);
  }
  {
    const auto& c = as<scene::Cable>(s.actuators[1]);
    BOOST_TEST_REQUIRE(c.offset.points.size() == 2u);
    BOOST_TEST(c.offset.points[1].first == 0.2);
    BOOST_TEST((c.offset.points[1].second == Vector2(0.002, 0.001)));
    BOOST_TEST(!c.tension.has_value());
    BOOST_TEST_REQUIRE(c.displacement.has_value());
    BOOST_TEST((c.displacement->kind() == scene::ScalarSchedule::Kind::steps));
    BOOST_TEST(c.displacement->at(1.5) == 0.001);
    BOOST_TEST(!c.span.has_value());
    BOOST_TEST_REQUIRE(c.limits.has_value());
    BOOST_TEST(c.limits->second == 0.003);
  }
  {
    const auto& f = as<scene::Fluidic>(s.actuators[2]);
    BOOST_TEST((f.offset.at(0) == Vector2(0, 0.003)));
    BOOST_TEST(f.chamber_radius == 0.001);
    BOOST_TEST_REQUIRE(f.pressure.has_value());
    BOOST_TEST((f.pressure->kind() == scene::ScalarSchedule::Kind::ramp));
    BOOST_TEST(f.pressure->at(0.25) == 5000.0);
    BOOST_TEST(!f.volume.has_value());
    BOOST_TEST_REQUIRE(f.limits.has_value());
    BOOST_TEST(f.limits->second == 5.0e4);
  }
  {
    const auto& f = as<scene::Fluidic>(s.actuators[3]);
    BOOST_TEST((f.offset.at(0) == Vector2(0, -0.003)));
    BOOST_TEST(f.chamber_radius == 0.0015);
    BOOST_TEST(!f.pressure.has_value());
    BOOST_TEST_REQUIRE(f.volume.has_value());
    BOOST_TEST(f.volume->at(0) == 1.0e-7);
    BOOST_TEST_REQUIRE(f.span.has_value());
    BOOST_TEST(f.span->s0 == 0.05);
    BOOST_TEST(f.span->s1 == 0.2);
    BOOST_TEST_REQUIRE(f.limits.has_value());
    BOOST_TEST(f.limits->second == 2.0e-7);
  }
  {
    const auto& m = as<scene::Muscle>(s.actuators[4]);
    BOOST_TEST((m.offset.at(0) == Vector2(-0.003, 0)));
    BOOST_TEST(as<rod::Circle>(m.section).diameter == 0.001);
    BOOST_TEST(m.material.E == 5.0e7);
    BOOST_TEST(m.material.G == 2.0e7);
    BOOST_TEST(m.material.rho == 1500.0);
    BOOST_TEST(m.material.viscosity == 0.0);
    BOOST_TEST((m.input.kind() == scene::ScalarSchedule::Kind::steps));
    BOOST_TEST(m.input.at(0.25) == 0.0);
    BOOST_TEST(m.input.at(0.5) == 1.0);
    BOOST_TEST(m.law.type == "linear");
    BOOST_TEST(m.law.gain == 0.2);
    BOOST_TEST(m.law.stiffness == 3.0);
    BOOST_TEST_REQUIRE(m.span.has_value());
    BOOST_TEST(m.span->s1 == 0.15);
    BOOST_TEST_REQUIRE(m.limits.has_value());
    BOOST_TEST(m.limits->second == 2.0);
  }

  BOOST_TEST_REQUIRE(s.dynamics.has_value());
  BOOST_TEST(*s.dynamics->t_end == 2.5);
  BOOST_TEST(*s.dynamics->dt == 1.0e-4);
  BOOST_TEST((s.dynamics->initial == scene::Initial::static_equilibrium));
  BOOST_TEST(s.dynamics->output_every == 10);
  BOOST_TEST(*s.dynamics->scheme == "implicit-midpoint");

  BOOST_TEST(s.solver.scheme == "rkmk-rk4");
  BOOST_TEST(s.solver.nodes == 40);
  BOOST_TEST(s.solver.tol == 1.0e-8);
  BOOST_TEST(s.solver.max_iterations == 30);

  BOOST_TEST_REQUIRE(s.control.has_value());
  const scene::Control& c = *s.control;
  BOOST_TEST((c.task == scene::ControlTask::track));
  BOOST_TEST(c.targets.empty());
  BOOST_TEST_REQUIRE(c.trajectory.has_value());
  const scene::CircleTrajectory& circle = c.trajectory->circle;
  BOOST_TEST((circle.center == Vector3(0.1, 0.2, 0.49)));
  BOOST_TEST(circle.radius == 0.02);
  BOOST_TEST(circle.period == 3.0);
  BOOST_TEST(circle.laps == 2.5);
  BOOST_TEST((circle.normal == Vector3(0, 1, 0)));  // [0, 2, 0] normalised
  BOOST_TEST(c.horizon == 5);
  BOOST_TEST(c.dt_control == 0.02);
  BOOST_TEST(c.threshold == 0.03);
  BOOST_TEST(c.max_steps == 50);
  BOOST_TEST(c.hold_steps == 5);
  BOOST_TEST(c.weights.input_rate == 0.01);
  BOOST_TEST(c.weights.input == 0.001);
  BOOST_TEST(c.weights.terminal == 10.0);
  BOOST_TEST(c.seed == 7u);
}

BOOST_AUTO_TEST_CASE(clamped_tip_rectangle_and_auto_dt) {
  const scene::Scene s = load_scene((kGoodDir / "clamped.yaml").string());
  BOOST_TEST(s.name == "clamped");  // the file name without extension
  const auto& r = as<rod::Rectangle>(s.rod.section);
  BOOST_TEST(r.width == 0.01);
  BOOST_TEST(r.height == 0.005);
  BOOST_TEST(max_abs(s.base.pose.matrix() - Eigen::Matrix4d::Identity()) == 0.0);
  BOOST_TEST(s.tip_clamped());
  const auto& tip = as<scene::ClampedTip>(s.tip);
  BOOST_TEST((tip.pose.translation() == Vector3(0.01, 0, 0.1)));
  Eigen::Matrix3d R;
  R << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  BOOST_TEST(max_abs(tip.pose.rotation_matrix() - R) <= 1e-15);
  BOOST_TEST_REQUIRE(s.dynamics.has_value());
  BOOST_TEST(*s.dynamics->t_end == 1.0);
  BOOST_TEST(!s.dynamics->dt.has_value());  // auto
  BOOST_TEST((s.dynamics->initial == scene::Initial::straight));
  BOOST_TEST(s.dynamics->output_every == 1);
  BOOST_TEST(!s.dynamics->scheme.has_value());
}

BOOST_AUTO_TEST_CASE(defaults) {
  const scene::Scene s = with("");
  BOOST_TEST(s.name == "minimal");
  BOOST_TEST(s.source_path == "minimal.yaml");
  BOOST_TEST((s.rod.model == rod::ModelKind::cosserat));
  BOOST_TEST((s.rod.reference_twist == rod::RodModel::straight_twist()));
  BOOST_TEST(s.rod.material.viscosity == 0.0);
  BOOST_TEST(max_abs(s.base.pose.matrix() - Eigen::Matrix4d::Identity()) == 0.0);
  const auto& tip = as<scene::FreeTip>(s.tip);
  BOOST_TEST((tip.wrench.moment.at(0) == Vector3::Zero()));
  BOOST_TEST((tip.wrench.force.at(0) == Vector3::Zero()));
  BOOST_TEST((tip.wrench.frame == scene::Frame::body));
  BOOST_TEST(!s.loads.gravity.has_value());
  BOOST_TEST(!s.loads.drag.has_value());
  BOOST_TEST(!s.loads.buoyancy.has_value());
  BOOST_TEST(!s.loads.distributed.has_value());
  BOOST_TEST(s.actuators.empty());
  BOOST_TEST(!s.dynamics.has_value());
  BOOST_TEST(s.solver.scheme == "chebyshev");
  BOOST_TEST(s.solver.nodes == 24);
  BOOST_TEST(s.solver.tol == 1e-10);
  BOOST_TEST(s.solver.max_iterations == 50);
  BOOST_TEST(!s.control.has_value());
}

BOOST_AUTO_TEST_CASE(defaults_inside_optional_sections) {
  const scene::Scene s = with(
      "loads:\n  drag: {fluid_density: 1000, laminar: [0, 0, 0, 1, 1, 1]}\n"
      "  distributed: {force: [0, 1, 0]}\n"
      "actuators:\n  - muscle: {offset: [0, 0], section: {shape: circle, diameter: 0.001},\n"
      "      material: {E: 1.0e7, poisson: 0.5, rho: 1000}, input: 2, law: {gain: 0.1}}\n"
      "dynamics: {}\n");
  BOOST_TEST((s.loads.drag->turbulent == scene::Vector6::Zero()));
  BOOST_TEST((s.loads.distributed->frame == scene::Frame::world));
  BOOST_TEST((s.loads.distributed->moment.at(0) == Vector3::Zero()));
  const auto& m = as<scene::Muscle>(s.actuators.at(0));
  BOOST_TEST(m.law.type == "linear");
  BOOST_TEST(m.law.stiffness == 0.0);
  BOOST_TEST(m.input.at(0) == 2.0);
  BOOST_TEST(m.material.G == 1.0e7 / 3.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(!m.span.has_value());
  BOOST_TEST(!m.limits.has_value());
  BOOST_TEST_REQUIRE(s.dynamics.has_value());
  BOOST_TEST(!s.dynamics->t_end.has_value());
  BOOST_TEST(!s.dynamics->dt.has_value());
  BOOST_TEST(s.dynamics->output_every == 1);
}

BOOST_AUTO_TEST_CASE(empty_values_read_as_empty_sections) {
  const scene::Scene s = load_scene_from_string(
      "schema: rodlab.scene/1\nrod: {length: 0.1, section: {shape: circle, diameter: 0.01},\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000}}\ntip:\n  free:\nbase:\nloads:\nactuators:\n",
      "s.yaml");
  BOOST_TEST(!s.tip_clamped());
  BOOST_TEST(s.actuators.empty());
  BOOST_TEST(!s.loads.gravity.has_value());
}

// ---- control

const std::string kControlled =
    "actuators:\n  - cable: {offset: [0.004, 0], tension: 0, limits: [0, 0.5]}\n"
    "  - muscle: {offset: [0, 0], section: {shape: circle, diameter: 0.001},\n"
    "      material: {E: 1.0e7, poisson: 0.5, rho: 1000}, input: 0, law: {gain: 0.1},"
    " limits: [-1, 2]}\n";

BOOST_AUTO_TEST_CASE(control_defaults) {
  // an empty section: every default of scene::Control (docs/scene-reference.md "control")
  const scene::Scene s = with(kControlled + "control:\n");
  BOOST_TEST_REQUIRE(s.control.has_value());
  const scene::Control& c = *s.control;
  BOOST_TEST((c.task == scene::ControlTask::reach));
  BOOST_TEST(c.targets.empty());
  BOOST_TEST(!c.trajectory.has_value());
  BOOST_TEST(c.horizon == 10);
  BOOST_TEST(c.dt_control == 0.05);
  BOOST_TEST(c.threshold == 0.05);
  BOOST_TEST(c.max_steps == 100);
  BOOST_TEST(c.hold_steps == 10);
  BOOST_TEST(c.weights.input_rate == 1e-3);
  BOOST_TEST(c.weights.input == 0.0);
  BOOST_TEST(c.weights.terminal == 1.0);
  BOOST_TEST(c.seed == 1u);
  BOOST_TEST(c.target_count == 10);

  // a trajectory without a task is tracked; a circle's laps and normal have defaults
  const scene::Scene t = with(kControlled +
      "control: {trajectory: {circle: {center: [0, 0, 0.09], radius: 0.01, period: 4}}}\n");
  BOOST_TEST((t.control->task == scene::ControlTask::track));
  BOOST_TEST(t.control->trajectory->circle.laps == 1.0);
  BOOST_TEST((t.control->trajectory->circle.normal == Vector3::UnitZ()));
}

BOOST_AUTO_TEST_CASE(control_targets_and_drawn_targets) {
  scene::Scene s = with(kControlled +
      "control:\n  task: hold\n  targets: [[0.02, 0.0, 0.09], [0.0, -0.015, 0.095]]\n");
  BOOST_TEST((s.control->task == scene::ControlTask::hold));
  BOOST_TEST_REQUIRE(s.control->targets.size() == 2u);
  BOOST_TEST((s.control->targets[0] == Vector3(0.02, 0.0, 0.09)));
  BOOST_TEST((s.control->targets[1] == Vector3(0.0, -0.015, 0.095)));
  BOOST_TEST(!s.control->trajectory.has_value());

  s = with(kControlled + "control: {task: reach, target_count: 25, seed: 0}\n");
  BOOST_TEST(s.control->targets.empty());
  BOOST_TEST(s.control->target_count == 25);
  BOOST_TEST(s.control->seed == 0u);
}

BOOST_AUTO_TEST_CASE(overrides_reach_the_control_fields) {
  // the section is created by the overrides when the file has none
  const scene::Scene s =
      with(kControlled, {"control.horizon=5", "control.dt_control=0.1", "control.task=hold",
                         "control.weights.input_rate=0", "control.targets=[[0.01, 0, 0.099]]",
                         "control.hold_steps=100"});
  BOOST_TEST_REQUIRE(s.control.has_value());
  BOOST_TEST(s.control->horizon == 5);
  BOOST_TEST(s.control->dt_control == 0.1);
  BOOST_TEST((s.control->task == scene::ControlTask::hold));
  BOOST_TEST(s.control->weights.input_rate == 0.0);
  BOOST_TEST(s.control->weights.terminal == 1.0);
  BOOST_TEST_REQUIRE(s.control->targets.size() == 1u);
  BOOST_TEST((s.control->targets[0] == Vector3(0.01, 0, 0.099)));
  BOOST_TEST(s.control->hold_steps == 100);

  // the full scene's circle, changed field by field
  std::vector<Override> o{io::parse_override("control.trajectory.circle.radius=0.005"),
                          io::parse_override("control.trajectory.circle.normal=[1, 0, 0]")};
  const scene::Scene f = load_scene((kGoodDir / "full.yaml").string(), o);
  BOOST_TEST(f.control->trajectory->circle.radius == 0.005);
  BOOST_TEST((f.control->trajectory->circle.normal == Vector3::UnitX()));
  BOOST_TEST(f.control->trajectory->circle.period == 3.0);
}

BOOST_AUTO_TEST_CASE(rotation_from_axis_angle_is_the_exponential) {
  const Vector3 axis(0.6, 0.0, 0.8);
  const double angle = 2.5;
  const scene::Scene s = with("base:\n  pose:\n    rotation: {axis: [0.6, 0, 0.8], angle: 2.5}\n");
  BOOST_TEST(max_abs(s.base.pose.rotation_matrix() - lie::SO3::exp(axis * angle).matrix()) <=
             1e-15);
  BOOST_TEST((s.base.pose.translation() == Vector3::Zero()));
}

BOOST_AUTO_TEST_CASE(nearly_orthonormal_rotation_is_projected_onto_SO3) {
  const scene::Scene s =
      with("base:\n  pose:\n    rotation: [[1, 2.0e-7, 0], [0, 1, 0], [0, 0, 1]]\n");
  const Eigen::Matrix3d R = s.base.pose.rotation_matrix();
  BOOST_TEST(max_abs(R.transpose() * R - Eigen::Matrix3d::Identity()) <= 1e-15);
  BOOST_TEST(std::abs(R.determinant() - 1.0) <= 1e-15);
  // the polar factor of I + e E12 is exp(e/2 (E12 - E21)) to O(e^2)
  BOOST_TEST(std::abs(R(0, 1) - 1.0e-7) <= 1e-13);
  BOOST_TEST(std::abs(R(1, 0) + 1.0e-7) <= 1e-13);
}

BOOST_AUTO_TEST_CASE(overrides_create_missing_fields) {
  const scene::Scene s = with("", {"rod.material.viscosity=300", "loads.gravity=[0, 0, -9.81]",
                                   "dynamics.dt=auto", "tip.free.wrench.frame=world"});
  BOOST_TEST(s.rod.material.viscosity == 300.0);
  BOOST_TEST_REQUIRE(s.loads.gravity.has_value());
  BOOST_TEST((*s.loads.gravity == Vector3(0, 0, -9.81)));
  BOOST_TEST_REQUIRE(s.dynamics.has_value());
  BOOST_TEST(!s.dynamics->dt.has_value());
  BOOST_TEST((as<scene::FreeTip>(s.tip).wrench.frame == scene::Frame::world));
}

BOOST_AUTO_TEST_CASE(overrides_replace_values_lists_and_maps) {
  const std::string cable = "actuators:\n  - cable: {offset: [0.004, 0], tension: 0.5}\n";
  scene::Scene s = with(cable, {"rod.material.E=2e6", "actuators.0.cable.tension=0.3", "name=other",
                                "solver={scheme: kinsol, nodes: 32}"});
  BOOST_TEST(s.rod.material.E == 2e6);
  BOOST_TEST(as<scene::Cable>(s.actuators[0]).tension->at(0) == 0.3);
  BOOST_TEST(s.name == "other");
  BOOST_TEST(s.solver.scheme == "kinsol");
  BOOST_TEST(s.solver.nodes == 32);
  BOOST_TEST(s.solver.tol == 1e-10);  // the replaced map had no tol: default again

  s = with(cable, {"actuators.00.cable.tension={steps: [[0, 0], [1, 0.3]]}"});
  const auto& tension = *as<scene::Cable>(s.actuators[0]).tension;
  BOOST_TEST((tension.kind() == scene::ScalarSchedule::Kind::steps));
  BOOST_TEST(tension.at(0.5) == 0.0);
  BOOST_TEST(tension.at(1.0) == 0.3);

  s = with(cable,
           {"tip={clamped: {position: [0, 0.01, 0.1]}}", "actuators.0.cable.offset.1=0.001"});
  BOOST_TEST((as<scene::ClampedTip>(s.tip).pose.translation() == Vector3(0, 0.01, 0.1)));
  BOOST_TEST((as<scene::Cable>(s.actuators[0]).offset.at(0) == Vector2(0.004, 0.001)));
}

BOOST_AUTO_TEST_CASE(later_override_wins_and_overrides_fix_file_values) {
  std::string yaml = kMinimal;
  yaml.replace(yaml.find("E: 1.0e6"), 8, "E: -1");
  std::vector<Override> o{io::parse_override("rod.material.E=3e6"),
                          io::parse_override("rod.length=0.2"),
                          io::parse_override("rod.length=0.3")};
  const scene::Scene s = load_scene_from_string(yaml, "x.yaml", o);
  BOOST_TEST(s.rod.material.E == 3e6);
  BOOST_TEST(s.rod.length == 0.3);
}

BOOST_AUTO_TEST_CASE(overrides_apply_to_files_too) {
  std::vector<Override> o{io::parse_override("rod.model=kirchhoff")};
  const scene::Scene s = load_scene((kGoodDir / "clamped.yaml").string(), o);
  BOOST_TEST((s.rod.model == rod::ModelKind::kirchhoff));
}

BOOST_AUTO_TEST_CASE(numbers_in_yaml_forms) {
  const scene::Scene s = with("", {"rod.length=+1.5e-1", "solver.nodes=1e2", "solver.tol=.5"});
  BOOST_TEST(s.rod.length == 0.15);
  BOOST_TEST(s.solver.nodes == 100);
  BOOST_TEST(s.solver.tol == 0.5);
}

BOOST_AUTO_TEST_CASE(reference_doc_examples_are_the_tested_scenes) {
  // docs/scene-reference.md shows full.yaml (without its comment line) and the minimal scene.
  std::ifstream doc(fs::path(RODLAB_SOURCE_DIR) / "docs" / "scene-reference.md");
  const std::string text((std::istreambuf_iterator<char>(doc)), std::istreambuf_iterator<char>());
  const auto yaml_block = [&](std::size_t from) {
    const std::size_t start = text.find("```yaml\n", from) + 8;
    return text.substr(start, text.find("```", start) - start);
  };
  const std::size_t example = text.find("## Complete example");
  BOOST_TEST_REQUIRE(example != std::string::npos);
  std::ifstream full(kGoodDir / "full.yaml");
  std::string file((std::istreambuf_iterator<char>(full)), std::istreambuf_iterator<char>());
  file.erase(0, file.find('\n') + 1);
  BOOST_TEST(yaml_block(example) == file);
  BOOST_TEST(yaml_block(text.find("A minimal scene")) == kMinimal);
}

BOOST_AUTO_TEST_CASE(rest_strain_forms) {
  // rod.rest_strain (issue #18): six numbers, an arc by radius or by total angle, or a helix by
  // radius and pitch, each read into the constant xi* (reference_twist). Reference for the
  // helix: the inverse relations of a circular helix with curvature kappa and torsion tau,
  // radius = kappa / (kappa^2 + tau^2), pitch = 2 pi tau / (kappa^2 + tau^2), and the geometry
  // itself: exp(T xi*) after one turn, T = 2 pi / |omega*|, moves the section by the pitch.
  auto twist_of = [](const std::string& rest) {
    return load_scene_from_string(
               "schema: rodlab.scene/1\nrod:\n  length: 0.1\n"
               "  section: {shape: circle, diameter: 0.01}\n"
               "  material: {E: 1.0e6, G: 0.33e6, rho: 1000}\n  rest_strain: " + rest +
                   "\ntip: {free: {}}\n",
               "rest.yaml")
        .rod.reference_twist;
  };
  using V6 = scene::Vector6;
  BOOST_TEST((twist_of("[10, 0, 2, 0, 0, 1]") == (V6() << 10, 0, 2, 0, 0, 1).finished()));
  BOOST_TEST((twist_of("{arc: {radius: 0.05}}") == (V6() << 20, 0, 0, 0, 0, 1).finished()));
  const V6 by_angle = twist_of("{arc: {angle: 1.5}}");  // 1.5 rad over L = 0.1 m
  BOOST_TEST(std::abs(by_angle[0] - 15.0) <= 1e-14);
  BOOST_TEST((by_angle.tail<5>() == (V6() << 0, 0, 0, 0, 0, 1).finished().tail<5>()));
  for (const double pitch : {0.05, -0.03}) {
    const V6 xi = twist_of("{helix: {radius: 0.02, pitch: " + std::to_string(pitch) + "}}");
    const double k = xi[0], tau = xi[2], w2 = k * k + tau * tau;
    BOOST_TEST(xi[1] == 0.0);
    BOOST_TEST((xi.tail<3>() == Vector3(0, 0, 1)));
    BOOST_TEST(std::abs(k / w2 - 0.02) <= 1e-15);
    BOOST_TEST(std::abs(2.0 * M_PI * tau / w2 - pitch) <= 1e-15);
    const double turn = 2.0 * M_PI / std::sqrt(w2);
    const double rise = lie::SE3::exp(turn * xi).translation().norm();
    BOOST_TEST(std::abs(rise - std::abs(pitch)) <= 1e-14, "rise per turn " << rise);
  }
}

BOOST_AUTO_TEST_CASE(rest_strain_spans) {
  // rod.rest_strain.spans (issue #18): spans of six numbers, an arc (its angle is the span's own
  // bend) and a helix, begun where the previous one ends; the model's xi*(s) and its rest pose
  // (the product of the spans' exponentials, docs/scene-reference.md).
  const auto scene = load_scene_from_string(
      "schema: rodlab.scene/1\nrod:\n  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000}\n"
      "  rest_strain:\n    spans:\n"
      "      - {length: 0.02, strain: [0, 0, 0, 0, 0, 1]}\n"
      "      - {length: 0.05, arc: {angle: 0.5}}\n"
      "      - {length: 0.03, helix: {radius: 0.02, pitch: 0.05}}\n"
      "tip: {free: {}}\n",
      "spans.yaml");
  const auto& spans = scene.rod.rest_spans;
  BOOST_REQUIRE(spans.size() == 3u);
  BOOST_TEST(spans[0].begin == 0.0);
  BOOST_TEST(std::abs(spans[1].begin - 0.02) <= 1e-15);
  BOOST_TEST(std::abs(spans[2].begin - 0.07) <= 1e-15);
  BOOST_TEST(std::abs(spans[1].xi_star[0] - 10.0) <= 1e-13);  // 0.5 rad over 0.05 m
  const rod::RodModel model = scene.rod.to_model();
  BOOST_TEST(model.has_rest_spans());
  BOOST_TEST((model.xi_star(0.01) == spans[0].xi_star));
  BOOST_TEST((model.xi_star(spans[1].begin) == spans[1].xi_star));  // a begin is its span's
  BOOST_TEST((model.xi_star(0.1) == spans[2].xi_star));
  BOOST_TEST((model.rest_breaks() == std::vector<double>{spans[1].begin, spans[2].begin}));
  const lie::SE3 expected = lie::SE3::exp(0.02 * spans[0].xi_star) *
                            lie::SE3::exp(0.05 * spans[1].xi_star) *
                            lie::SE3::exp(0.03 * spans[2].xi_star);
  const lie::SE3 tip = model.rest_pose(0.1);
  BOOST_TEST((tip.translation() - expected.translation()).norm() <= 1e-16);
  BOOST_TEST((tip.rotation_matrix() - expected.rotation_matrix()).norm() <= 1e-15);
  // A uniform rod keeps one span: its xi* everywhere and exp(s xi*).
  const rod::RodModel uniform = load_scene_from_string(
      "schema: rodlab.scene/1\nrod:\n  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000}\n  rest_strain: {arc: {radius: 0.05}}\n"
      "tip: {free: {}}\n",
      "arc.yaml").rod.to_model();
  BOOST_TEST(!uniform.has_rest_spans());
  BOOST_TEST((uniform.rest_pose(0.07).translation() ==
              lie::SE3::exp(0.07 * uniform.xi_star()).translation()));
}
