#define BOOST_TEST_MODULE schedules
#include <boost/test/unit_test.hpp>

// Schedules (steps / ramp) and actuator offsets/routings as read from YAML, evaluated at,
// before, between and after their points. Reference: the definitions in
// docs/scene-reference.md (value before the first time is the first value, after the last the
// last; steps hold v_k on [t_k, t_k+1); ramps interpolate linearly, a repeated time jumps).
// The expected numbers are exact in binary floating point.

#include <string>
#include <variant>

#include "rodlab/io/scene_loader.hpp"

using namespace rodlab;
using scene::Vector2;
using scene::Vector3;

namespace {

scene::Scene with_actuator(const std::string& actuator) {
  return io::load_scene_from_string(R"(schema: rodlab.scene/1
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000}
tip: {free: {wrench: {force: {ramp: [[1, [0, 0, 0]], [3, [1, -2, 0.5]]]}}}}
actuators:
  - )" + actuator + "\n",
                                    "schedules.yaml");
}

scene::ScalarSchedule tension(const std::string& value) {
  const auto s = with_actuator("cable: {offset: [0.004, 0], tension: " + value + "}");
  return *std::get<scene::Cable>(s.actuators.at(0)).tension;
}

scene::Offset offset(const std::string& placement) {
  const auto s = with_actuator("cable: {" + placement + ", tension: 0.1}");
  return std::get<scene::Cable>(s.actuators.at(0)).offset;
}

}  // namespace

BOOST_AUTO_TEST_CASE(constant) {
  const auto c = tension("0.25");
  BOOST_TEST(c.is_constant());
  for (double t : {-1.0, 0.0, 1e9}) BOOST_TEST(c.at(t) == 0.25);
}

BOOST_AUTO_TEST_CASE(steps_are_piecewise_constant_on_half_open_intervals) {
  const auto s = tension("{steps: [[0.5, 0.1], [1, 0.2], [2, 0.4]]}");
  BOOST_TEST((s.kind() == scene::ScalarSchedule::Kind::steps));
  BOOST_TEST(s.at(-1.0) == 0.1);  // before the first time: the first value
  BOOST_TEST(s.at(0.0) == 0.1);
  BOOST_TEST(s.at(0.5) == 0.1);   // at a point
  BOOST_TEST(s.at(0.75) == 0.1);  // between
  BOOST_TEST(s.at(1.0) == 0.2);   // the step happens at t_k
  BOOST_TEST(s.at(1.999) == 0.2);
  BOOST_TEST(s.at(2.0) == 0.4);
  BOOST_TEST(s.at(100.0) == 0.4);  // after the last: the last value
}

BOOST_AUTO_TEST_CASE(ramp_is_piecewise_linear) {
  const auto r = tension("{ramp: [[1, 0], [2, 0.5], [4, 0.25]]}");
  BOOST_TEST((r.kind() == scene::ScalarSchedule::Kind::ramp));
  BOOST_TEST(r.at(0.0) == 0.0);
  BOOST_TEST(r.at(1.0) == 0.0);
  BOOST_TEST(r.at(1.5) == 0.25);
  BOOST_TEST(r.at(2.0) == 0.5);
  BOOST_TEST(r.at(3.0) == 0.375);
  BOOST_TEST(r.at(4.0) == 0.25);
  BOOST_TEST(r.at(5.0) == 0.25);
}

BOOST_AUTO_TEST_CASE(ramp_with_a_repeated_time_jumps) {
  const auto r = tension("{ramp: [[0, 0], [1, 1], [1, 3], [2, 5]]}");
  BOOST_TEST(r.at(0.5) == 0.5);
  BOOST_TEST(r.at(1.0) == 3.0);  // at the jump: the value after it
  BOOST_TEST(r.at(1.5) == 4.0);
  BOOST_TEST(r.at(2.5) == 5.0);
}

BOOST_AUTO_TEST_CASE(single_point_schedules) {
  BOOST_TEST(tension("{steps: [[1, 0.3]]}").at(0.0) == 0.3);
  BOOST_TEST(tension("{ramp: [[1, 0.3]]}").at(2.0) == 0.3);
}

BOOST_AUTO_TEST_CASE(vector_ramp) {
  const auto s = with_actuator("cable: {offset: [0.004, 0], tension: 0.1}");
  const auto& force = std::get<scene::FreeTip>(s.tip).wrench.force;
  BOOST_TEST((force.at(0.0) == Vector3(0, 0, 0)));
  BOOST_TEST((force.at(2.0) == Vector3(0.5, -1, 0.25)));
  BOOST_TEST((force.at(3.5) == Vector3(1, -2, 0.5)));
}

BOOST_AUTO_TEST_CASE(constant_offset) {
  const auto o = offset("offset: [0.004, -0.002, 0]");
  BOOST_TEST(o.points.size() == 1u);
  for (double s : {-1.0, 0.0, 0.05, 0.1}) BOOST_TEST((o.at(s) == Vector2(0.004, -0.002)));
  BOOST_TEST((offset("offset: [0.004, -0.002]").at(0) == Vector2(0.004, -0.002)));
}

BOOST_AUTO_TEST_CASE(routing_is_linear_in_s_and_clamped_at_the_ends) {
  const auto o = offset("routing: [[0.02, 0.004, 0], [0.06, 0.002, 0.001], [0.1, 0.002, 0.001]]");
  BOOST_TEST((o.at(0.0) == Vector2(0.004, 0)));  // before the first point
  BOOST_TEST((o.at(0.02) == Vector2(0.004, 0)));
  BOOST_TEST((o.at(0.04) - Vector2(0.003, 0.0005)).norm() <= 1e-18);
  BOOST_TEST((o.at(0.06) == Vector2(0.002, 0.001)));
  BOOST_TEST((o.at(0.08) == Vector2(0.002, 0.001)));
  BOOST_TEST((o.at(0.2) == Vector2(0.002, 0.001)));  // after the last point
}

BOOST_AUTO_TEST_CASE(offset_directly) {
  scene::Offset o;
  BOOST_TEST((o.at(0.3) == Vector2::Zero()));
  o.points = {{0.0, Vector2(0, 0)}, {1.0, Vector2(2, -4)}};
  BOOST_TEST((o.at(0.25) == Vector2(0.5, -1)));
  BOOST_TEST((o.at(-1) == Vector2(0, 0)));
  BOOST_TEST((o.at(2) == Vector2(2, -4)));
}
