#define BOOST_TEST_MODULE chebyshev_tracker
#include <boost/test/unit_test.hpp>

#include <iostream>
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/statics/chebyshev_tracker.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"
#include "rodlab/solvers/statics/workspace.hpp"

using namespace rodlab;
using namespace rodlab::solvers::statics;

namespace {

scene::Scene cable_driven(bool gravity) {
  auto scene = io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/cable-driven.yaml");
  if (gravity) scene.loads.gravity = lie::Vector3(-9.81, 0, 0);
  return scene;
}

/// The tip of a cold solve_static (chebyshev N = 24, tol 1e-12) with the tensions u.
lie::Vector3 cold_tip(scene::Scene scene, const Eigen::Vector4d& u) {
  for (int k = 0; k < 4; ++k) std::get<scene::Cable>(scene.actuators[k]).tension = scene::ScalarSchedule(u[k]);
  const auto r = solve_static(scene, {"chebyshev", 24, 1e-12, 50});
  BOOST_TEST_REQUIRE(r.converged, r.reason);
  return r.centerline.back().pose.translation();
}

}  // namespace

// References: solve_chebyshev from scratch (the warm solve must find the same equilibrium, to the
// solve tolerance: 1e-11 m) and central differences of such cold solves with a step of 1e-4 N
// (truncation ~1e-8 relative) for the implicit-function-theorem Jacobian dp/du (agreement to
// 1e-6 relative to |J|). On scenes/cable-driven.yaml without and with gravity (the loads then
// depend on the rotation: the theta columns of the Newton matrix matter).
BOOST_AUTO_TEST_CASE(warm_solves_and_tip_jacobian) {
  for (bool gravity : {false, true}) {
    const scene::Scene scene = cable_driven(gravity);
    ChebyshevTracker tracker(StaticProblem::from_scene(scene), {24, 1e-12, 50, 0});
    const Eigen::Vector4d u0(0.2, 0.05, 0.1, 0.4), u1(0.25, 0.0, 0.15, 0.35);
    BOOST_TEST_REQUIRE(tracker.solve(std::span<const double>(u0.data(), 4)), tracker.reason());
    BOOST_TEST(!tracker.warm());
    BOOST_TEST((tracker.tip_position() - cold_tip(scene, u0)).norm() <= 1e-11);
    ChebyshevTracker::TipJacobian J;
    const double steps[4] = {5e-7, 5e-7, 5e-7, 5e-7};
    BOOST_TEST_REQUIRE(tracker.tip_jacobian(steps, J));
    Eigen::Matrix<double, 3, 4> fd;
    for (int k = 0; k < 4; ++k) {
      const double h = 1e-4;
      Eigen::Vector4d up = u0, um = u0;
      up[k] += h;
      um[k] -= h;
      fd.col(k) = (cold_tip(scene, up) - cold_tip(scene, um)) / (2 * h);
    }
    const double err = (J - fd).norm() / fd.norm();
    std::cout << "gravity " << gravity << ": |J - J_fd| / |J_fd| = " << err << "\nJ =\n" << J << "\nJ_fd =\n" << fd << "\n";
    BOOST_TEST(err <= 1e-6);
    BOOST_TEST_REQUIRE(tracker.solve(std::span<const double>(u1.data(), 4)), tracker.reason());
    BOOST_TEST(tracker.warm());
    std::cout << "warm solve: " << tracker.iterations() << " Newton iterations\n";
    BOOST_TEST((tracker.tip_position() - cold_tip(scene, u1)).norm() <= 1e-11);
  }
}

namespace {

/// tests/data/scenes/good/mixed-actuators.yaml: every kind of input, under gravity; three elements.
scene::Scene mixed_actuators() {
  return io::load_scene(std::string(RODLAB_TEST_DATA) + "/scenes/good/mixed-actuators.yaml");
}

/// The tip of a cold solve_static (chebyshev N = 24, tol 1e-12) with the inputs u.
lie::Vector3 cold_tip_inputs(scene::Scene scene, const Eigen::Vector4d& u) {
  const auto inputs = workspace_inputs(scene);
  for (int k = 0; k < 4; ++k) *inputs[k].value = scene::ScalarSchedule(u[k]);
  const auto r = solve_static(scene, {"chebyshev", 24, 1e-12, 50});
  BOOST_TEST_REQUIRE(r.converged, r.reason);
  return r.centerline.back().pose.translation();
}

}  // namespace

// The same references with every kind of input: a cable's displacement and a muscle's q (both
// with an extra unknown of the BVP, bordering the Newton matrix), a chamber's pressure and the
// tension of a cable entering the rod, under gravity. Central differences of cold solves with steps 1e-4 of each input's range; agreement to
// 1e-6 relative per column (the columns differ by orders of magnitude: m per m, per Pa, per unit q).
BOOST_AUTO_TEST_CASE(tip_jacobian_with_every_input_kind) {
  const scene::Scene scene = mixed_actuators();
  ChebyshevTracker tracker(StaticProblem::from_scene(scene), {24, 1e-12, 50, 0});
  const Eigen::Vector4d u0(0.0005, 2.0e4, 1.0, 0.3), range(0.001, 5.0e4, 2.0, 0.5);
  BOOST_TEST_REQUIRE(tracker.solve(std::span<const double>(u0.data(), 4)), tracker.reason());
  BOOST_TEST((tracker.tip_position() - cold_tip_inputs(scene, u0)).norm() <= 1e-11);
  ChebyshevTracker::TipJacobian J;
  const double steps[4] = {1e-6 * range[0], 1e-6 * range[1], 1e-6 * range[2], 1e-6 * range[3]};
  BOOST_TEST_REQUIRE(tracker.tip_jacobian(steps, J));
  for (int k = 0; k < 4; ++k) {
    const double h = 1e-4 * range[k];
    Eigen::Vector4d up = u0, um = u0;
    up[k] += h;
    um[k] -= h;
    const lie::Vector3 fd = (cold_tip_inputs(scene, up) - cold_tip_inputs(scene, um)) / (2 * h);
    const double err = (J.col(k) - fd).norm() / fd.norm();
    std::cout << "input " << k << ": J " << J.col(k).transpose() << ", |J - J_fd| / |J_fd| = " << err << "\n";
    BOOST_TEST(err <= 1e-6);
  }
  const Eigen::Vector4d u1(0.0006, 2.5e4, 1.2, 0.35);
  BOOST_TEST_REQUIRE(tracker.solve(std::span<const double>(u1.data(), 4)), tracker.reason());
  BOOST_TEST(tracker.warm());
  BOOST_TEST((tracker.tip_position() - cold_tip_inputs(scene, u1)).norm() <= 1e-11);
}
