#define BOOST_TEST_MODULE workspace
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/statics/workspace.hpp"

using namespace rodlab;
using namespace rodlab::solvers::statics;
using std::numbers::pi;

namespace {
constexpr double kL = 0.1;

scene::Scene four_cable_scene() {
  return io::load_scene_from_string(R"(
schema: rodlab.scene/1
name: four-cables
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000}
tip:
  free: {}
actuators:
  - cable: {offset: [0.004, 0], tension: 0, limits: [0, 0.5]}
  - cable: {offset: [0, 0.004], tension: 0, limits: [0, 0.5]}
  - cable: {offset: [-0.004, 0], tension: 0, limits: [0, 0.5]}
  - cable: {offset: [0, -0.004], tension: 0, limits: [0, 0.5]}
)", "four-cables.yaml");
}
}  // namespace

// Reference: (2.120) and its inverse (2.121)-(2.127) are inverse maps for omega L in [0, 2 pi),
// including omega L = pi where the thesis's (2.123) divides by sin(omega L) = 0, and omega = 0.
BOOST_AUTO_TEST_CASE(coordinates_round_trip) {
  for (double wL : {0.0, 1e-9, 0.3, pi / 2, pi, 4.0, 5.5})
    for (double phi : {0.0, 0.7, 2.0, -2.5})
      for (double eps : {-0.05, 0.0, 0.1}) {
        const WorkspaceCoordinates c{wL / kL, wL > 0 ? phi : 0.0, eps};
        const auto back = workspace_coordinates(workspace_tip(c, kL), kL);
        BOOST_TEST(std::abs(back.omega - c.omega) * kL <= 1e-12, "wL " << wL);
        BOOST_TEST(std::abs(back.epsilon - c.epsilon) <= 1e-12, "wL " << wL);
        if (wL > 1e-6) BOOST_TEST(std::abs(std::remainder(back.phi - c.phi, 2 * pi)) <= 1e-12);
      }
  // (2.124): the straight rod.
  const auto c = workspace_coordinates(Eigen::Vector3d(0, 0, 1.02 * kL), kL);
  BOOST_TEST(c.omega == 0.0);
  BOOST_TEST(std::abs(c.epsilon - 0.02) <= 1e-14);
}

// Reference: one cable at offset [d, 0] with tension T bends the rod into an exact circular arc
// with kappa = T d / (E I) and stretch -T / (E A) (closed form of test_actuators), so the model
// coordinates of its tip are exactly (kappa, phi, -T/EA).
BOOST_AUTO_TEST_CASE(single_cable_tip_has_the_arc_coordinates) {
  auto scene = four_cable_scene();
  scene.actuators.resize(1);
  std::get<scene::Cable>(scene.actuators[0]).tension = scene::ScalarSchedule(0.4);
  const auto r = solve_static(scene, {"rkmk-rk4", 21, 1e-12, 50});
  BOOST_TEST_REQUIRE(r.converged);
  const auto model = scene.rod.to_model();
  const auto c = workspace_coordinates(r.centerline.back().pose.translation(), kL);
  BOOST_TEST(std::abs(c.omega - 0.4 * 0.004 / model.K_diag()[1]) <= 1e-9);
  BOOST_TEST(std::abs(c.epsilon + 0.4 / model.K_diag()[5]) <= 1e-12);
}

// Sampling: every converged sample lies inside the fitted bounds (by construction), the bounds
// are those of the samples, and a point far outside is rejected.
BOOST_AUTO_TEST_CASE(sampled_tips_lie_inside_the_fitted_workspace) {
  const auto result = sample_workspace(four_cable_scene(), {"rkmk-rk4", 21, 1e-10, 50}, 20, 7);
  BOOST_TEST(result.samples.size() == 20u);
  BOOST_TEST(result.failed == 0);
  BOOST_TEST(result.bounds.omega_bound > 0.0);
  BOOST_TEST(result.bounds.eps_high <= 0.0);  // cables only compress the rod
  for (const auto& s : result.samples) {
    BOOST_TEST(s.converged);
    BOOST_TEST(workspace_contains(result.bounds, s.tip, kL, 1e-12));
    for (double u : s.inputs) BOOST_TEST((u >= 0.0 && u <= 0.5));
  }
  BOOST_TEST(!workspace_contains(result.bounds, Eigen::Vector3d(0, 0, 2 * kL), kL));
  BOOST_TEST(!workspace_contains(result.bounds, Eigen::Vector3d(0.08, 0, 0.02), kL));
  // Fixed seed: the same samples again.
  const auto again = sample_workspace(four_cable_scene(), {"rkmk-rk4", 21, 1e-10, 50}, 20, 7);
  BOOST_TEST(again.samples[5].inputs == result.samples[5].inputs);
}

BOOST_AUTO_TEST_CASE(limits_are_required) {
  auto scene = four_cable_scene();
  std::get<scene::Cable>(scene.actuators[2]).limits.reset();
  BOOST_CHECK_THROW(sample_workspace(scene, {"rkmk-rk4", 21, 1e-10, 50}, 5), std::invalid_argument);
}
