#define BOOST_TEST_MODULE trajectory
#include <boost/test/unit_test.hpp>

// The control trajectory helper (rodlab/scene/trajectory.hpp). Reference: the closed form
// p(t) = c + r (cos phi e1 + sin phi e2), phi = 2 pi t / T, with the axes defined in the header;
// tolerances are a few ulps of the coordinates (1e-15 absolute on values of order 0.1).

#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "rodlab/scene/trajectory.hpp"

using namespace rodlab::scene;

namespace {

constexpr double kTol = 1e-15;

CircleTrajectory circle(const Vector3& normal, double laps = 1.0) {
  return {Vector3(0.01, -0.02, 0.09), 0.01, 4.0, laps, normal.normalized()};
}

}  // namespace

BOOST_AUTO_TEST_CASE(phase_zero_is_plus_x_and_the_tip_turns_towards_plus_y) {
  const CircleTrajectory c = circle(Vector3::UnitZ());
  BOOST_TEST((position(c, 0.0) - Vector3(0.02, -0.02, 0.09)).norm() <= kTol);
  BOOST_TEST((position(c, 1.0) - Vector3(0.01, -0.01, 0.09)).norm() <= kTol);  // T/4
  BOOST_TEST((position(c, 2.0) - Vector3(0.0, -0.02, 0.09)).norm() <= kTol);   // T/2
  BOOST_TEST((position(c, 4.0) - position(c, 0.0)).norm() <= kTol);
  BOOST_TEST(duration(c) == 4.0);
}

BOOST_AUTO_TEST_CASE(before_the_start_and_after_the_end_it_waits) {
  const CircleTrajectory c = circle(Vector3::UnitZ(), 0.25);
  BOOST_TEST(duration(c) == 1.0);
  BOOST_TEST((position(c, -3.0) - position(c, 0.0)).norm() == 0.0);
  BOOST_TEST((position(c, 7.0) - position(c, 1.0)).norm() == 0.0);
  BOOST_TEST((position(c, 7.0) - Vector3(0.01, -0.01, 0.09)).norm() <= kTol);
  const Trajectory t{circle(Vector3::UnitZ(), 2.5)};
  BOOST_TEST(duration(t) == 10.0);
  BOOST_TEST((position(t, 10.0) - position(t.circle, 2.0)).norm() <= kTol);
}

BOOST_AUTO_TEST_CASE(axes_are_right_handed_in_the_plane_for_every_normal) {
  // including normals along x (e1 from the y axis instead) and just either side of the switch
  const double s = std::numbers::sqrt2 / 2.0;
  const std::vector<Vector3> normals{Vector3::UnitZ(),          Vector3::UnitX(),
                                     Vector3(-1, 0, 0),         Vector3::UnitY(),
                                     Vector3(1, 1, 1),          Vector3(s + 1e-9, s, 0),
                                     Vector3(s - 1e-9, s, 0),   Vector3(0.3, -0.2, -0.9)};
  for (const Vector3& n : normals) {
    const Vector3 u = n.normalized();
    const auto [e1, e2] = circle_axes(u);
    BOOST_TEST(std::abs(e1.norm() - 1.0) <= 1e-15);
    BOOST_TEST(std::abs(e2.norm() - 1.0) <= 1e-15);
    BOOST_TEST(std::abs(e1.dot(u)) <= 1e-15);
    BOOST_TEST((e1.cross(e2) - u).norm() <= 1e-15);
    const CircleTrajectory c = circle(u);
    for (double t : {0.0, 0.3, 1.7, 3.9}) {
      const Vector3 d = position(c, t) - c.center;
      BOOST_TEST(std::abs(d.norm() - c.radius) <= kTol);
      BOOST_TEST(std::abs(d.dot(u)) <= kTol);
    }
  }
}

BOOST_AUTO_TEST_CASE(e1_is_the_projected_x_axis_or_y_near_x) {
  auto [e1, e2] = circle_axes(Vector3::UnitY());
  BOOST_TEST((e1 - Vector3::UnitX()).norm() <= kTol);
  BOOST_TEST((e2 - Vector3(0, 0, -1)).norm() <= kTol);  // y x x = -z
  std::tie(e1, e2) = circle_axes(Vector3::UnitX());
  BOOST_TEST((e1 - Vector3::UnitY()).norm() <= kTol);
  BOOST_TEST((e2 - Vector3::UnitZ()).norm() <= kTol);
  std::tie(e1, e2) = circle_axes(Vector3(0, 1, 1).normalized());
  BOOST_TEST((e1 - Vector3::UnitX()).norm() <= kTol);
}
