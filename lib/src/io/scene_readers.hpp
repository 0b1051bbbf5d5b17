#pragma once
// Readers for the parts of a scene (schema rodlab.scene/1, docs/scene-reference.md); private to
// rodlab::io. Each reports every problem it finds to the Checker. Leaf readers return nullopt
// for an absent or bad field; the part readers return the part with whatever could be read
// (the scene is discarded anyway once anything has been reported).
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "rodlab/lie/se3.hpp"
#include "rodlab/scene/scene.hpp"
#include "yaml_checker.hpp"

namespace rodlab::io::detail {

// rod_reader.cpp
std::optional<rod::Section> read_section(Checker& c, const Field& f);
std::optional<rod::Material> read_material(Checker& c, const Field& f);
scene::Rod read_rod(Checker& c, const Field& f);

// boundary_reader.cpp
/// `identity` or {position: [3], rotation: identity | 3x3 matrix | {axis: [3], angle: rad}}.
std::optional<lie::SE3> read_pose(Checker& c, const Field& f);
scene::Base read_base(Checker& c, const Field& f);
std::optional<scene::Tip> read_tip(Checker& c, const Field& f);

/// {moment, force, frame}; the fields of both the tip wrench and loads.distributed.
struct WrenchFields {
  scene::VectorSchedule moment{scene::Vector3::Zero()};
  scene::VectorSchedule force{scene::Vector3::Zero()};
  scene::Frame frame = scene::Frame::body;
};
WrenchFields read_wrench(Checker& c, const Field& f, scene::Frame default_frame);

// loads_reader.cpp
scene::Loads read_loads(Checker& c, const Field& f);

// actuator_reader.cpp
/// rod_length is nullopt when rod.length itself is missing or bad (spans and routings are
/// then checked without their upper bound).
std::vector<scene::Actuator> read_actuators(Checker& c, const Field& f,
                                            std::optional<double> rod_length);

// run_reader.cpp
scene::Dynamics read_dynamics(Checker& c, const Field& f);
scene::Solver read_solver(Checker& c, const Field& f);

// learning_reader.cpp
/// The learning section (`rodlab train`'s settings).
scene::Learning read_learning(Checker& c, const Field& f);

// control_reader.cpp
/// The control section; `actuators` is the scene's actuators field and `read` what was read of
/// it: control needs every actuator to have limits (the controller's bounds and input scale).
scene::Control read_control(Checker& c, const Field& f, const Field& actuators,
                            const std::vector<scene::Actuator>& read);

/// A scalar input: a number in `range` or a schedule of them.
inline std::optional<scene::ScalarSchedule> read_scalar_input(Checker& c, const Field& f,
                                                              const Range& range) {
  return c.schedule<double>(f, [&](const Field& v) { return c.number(v, range); });
}

/// A 3-vector input: [x, y, z] or a schedule of them.
inline std::optional<scene::VectorSchedule> read_vector_input(Checker& c, const Field& f) {
  return c.schedule<scene::Vector3>(f, [&](const Field& v) { return c.vector<3>(v); });
}

}  // namespace rodlab::io::detail
