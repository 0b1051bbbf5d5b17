// Reach and hold by infinite-horizon LQR (solvers/control/lqr_hold.hpp) about the plant's own
// equilibrium under known tensions: the linear closed loop is stable, and from rest the tip
// settles on the equilibrium's tip with every tension inside its limits.
#define BOOST_TEST_MODULE control_lqr_hold
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "control_support.hpp"
#include "rodlab/solvers/control/lqr_hold.hpp"

namespace c = rodlab::solvers::control;
using rodlab::testing::control::cable_robot;
using rodlab::testing::control::plant_options;

// The equilibrium under (0.3, 0, 0, 0.1) N on the implicit midpoint (N = 8, dt_c = 0.05 s): the
// gain's closed loop A - B K has spectral radius < 1; from rest, straight, the controlled tip
// comes within 5 % of L of the equilibrium's tip (the thesis' success) and ends within 0.1 mm
// after 60 control steps (3 s; the open loop is damped about 100 times slower).
BOOST_AUTO_TEST_CASE(holds_the_equilibrium_of_known_tensions) {
  const c::PlantOptions po = plant_options("implicit-midpoint", 8, 0.05);
  Eigen::VectorXd u_star(4);
  u_star << 0.3, 0.0, 0.0, 0.1;
  const c::HoldGain gain = c::hold_gain(cable_robot(), po, u_star);
  BOOST_TEST_REQUIRE(gain.ok, gain.reason);
  BOOST_TEST_MESSAGE("closed-loop spectral radius " << gain.spectral_radius);
  BOOST_TEST(gain.spectral_radius < 1.0);
  BOOST_TEST(gain.tip_star.x() > 0.005);  // the +x cable bent it

  c::Plant plant(cable_robot(), po);
  double first = -1.0, error = 0.0;
  for (int k = 0; k < 60; ++k) {
    const Eigen::VectorXd u = gain.control(plant);
    BOOST_TEST((u.array() >= 0.0 && u.array() <= 0.5).all());
    plant.set_input(u);
    BOOST_REQUIRE(plant.advance().ok);
    error = (plant.tip() - gain.tip_star).norm();
    if (first < 0.0 && error < 0.05 * 0.1) first = plant.time();
  }
  BOOST_TEST_MESSAGE("within 5 % of L at t = " << first << " s; final error " << error << " m");
  BOOST_TEST(first > 0.0);
  BOOST_TEST(error < 1e-4);
}
