#define BOOST_TEST_MODULE kinsol_actuators
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

#include "rodlab/solvers/statics/kinsol_collocation.hpp"
#include "actuator_support.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

// The kinsol collocation with actuators (docs/statics.md) against rkmk-rk4 at fine N; the closed
// forms of constant strain are in test_actuators.cpp, which runs them for every statics scheme.

using namespace rodlab;
using namespace rodlab::solvers::statics;
using namespace rodlab::testing::actuators;

namespace {

/// Observed orders of kinsol's tip error against rkmk-rk4 at N = 401 over N = 21, 41, 81.
void check_order_four(const StaticProblem& P, const char* what) {
  const lie::Vector3 ref = tip(solve(P, "rkmk-rk4", 401));
  double e[3];
  const int Ns[3] = {21, 41, 81};
  for (int k = 0; k < 3; ++k) e[k] = (tip(solve(P, "kinsol", Ns[k])) - ref).norm();
  const double o1 = std::log2(e[0] / e[1]), o2 = std::log2(e[1] / e[2]);
  BOOST_TEST_MESSAGE(what << ": kinsol tip errors " << e[0] << ", " << e[1] << ", " << e[2]
                          << " (N = 21, 41, 81), observed orders " << o1 << ", " << o2);
  // The meshes are not nested (the intervals are shared among the stretches between
  // breakpoints in proportion to their lengths), so each doubling's order scatters about 4.
  const double mean = 0.5 * std::log2(e[0] / e[2]);
  BOOST_TEST(e[0] < 1e-5 * kL, what);
  BOOST_TEST(std::abs(o1 - 4.0) < 0.7, what << " observed order " << o1);
  BOOST_TEST(std::abs(o2 - 4.0) < 0.7, what << " observed order " << o2);
  BOOST_TEST(std::abs(mean - 4.0) < 0.3, what << " mean observed order " << mean);
}

}  // namespace

// Reference: rkmk-rk4 at N = 401 for a fluidic chamber over part of the rod (both span ends
// inside) under gravity (the straight chamber's closed form is in test_actuators.cpp).
BOOST_AUTO_TEST_CASE(fluidic_chamber_on_part_of_the_rod) {
  const auto m = table21();
  const double e = 0.003, Ac = std::numbers::pi * 1e-6, P_in = 2e4;
  StaticProblem Q(m, lie::SE3::identity());
  Q.set_gravity(loads::Gravity(m, lie::Vector3(-9.81, 0, 0)));
  auto b = straight(ActuatorKind::fluidic, 0.0, e, 0.0213, 0.0771);
  b.chamber_area = Ac;
  b.input = P_in;
  Q.add_actuator(b);
  check_order_four(Q, "fluidic chamber on [0.0213, 0.0771] under gravity");
}

// Reference: rkmk-rk4 at N = 401. A cable on [s0, L] enters the rod at s0 = 0.0437 (pulled from
// outside: Lambda jumps by T c(xi) there), under gravity. With a node at s0 the collocation keeps
// its order 4.
BOOST_AUTO_TEST_CASE(cable_entering_inside_keeps_order_four) {
  const auto m = table21();
  StaticProblem P(m, lie::SE3::identity());
  P.set_gravity(loads::Gravity(m, lie::Vector3(-9.81, 0, 0)));
  auto a = straight(ActuatorKind::cable, 0.004, 0.002, 0.0437, kL);
  a.input = 1.0;
  P.add_actuator(a);
  check_order_four(P, "cable entering at s0 = 0.0437");
}

// Reference: rkmk-rk4 at N = 401. Three cables with different spans (entries, ends) and a
// routed one (knot at 0.05), under gravity.
BOOST_AUTO_TEST_CASE(several_cables_together) {
  const auto m = table21();
  StaticProblem P(m, lie::SE3::identity());
  P.set_gravity(loads::Gravity(m, lie::Vector3(-9.81, 0, 0)));
  auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.0, 0.0613);
  a.input = 0.6;
  auto b = straight(ActuatorKind::cable, 0.0, 0.004, 0.0287, kL);
  b.input = 0.4;
  ActuatorTerm c{ActuatorKind::cable, loads::TendonPath({{0.0, Eigen::Vector2d(-0.004, 0)},
                                                        {0.05, Eigen::Vector2d(0.0, -0.004)},
                                                        {0.1, Eigen::Vector2d(0.004, 0)}},
                                                       0.0, kL)};
  c.input = 0.3;
  P.add_actuator(a);
  P.add_actuator(b);
  check_order_four(P, "two straight cables");
  StaticProblem Q(m, lie::SE3::identity());
  Q.set_gravity(loads::Gravity(m, lie::Vector3(-9.81, 0, 0)));
  Q.add_actuator(c);
  check_order_four(Q, "routed cable only");
  P.add_actuator(c);
  check_order_four(P, "three cables");
}

// Reference: rkmk-rk4 at N = 401. A large tension takes the tip past 90 degrees under gravity.
BOOST_AUTO_TEST_CASE(large_tension_past_ninety_degrees) {
  const auto m = table21();
  StaticProblem P(m, lie::SE3::identity());
  P.set_gravity(loads::Gravity(m, lie::Vector3(-9.81, 0, 0)));
  auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.0213, kL);
  a.input = 4.0;
  P.add_actuator(a);
  const auto ref = solve(P, "rkmk-rk4", 401);
  const auto r = solve(P, "kinsol", 41);
  const lie::Vector3 z_tip = r.centerline.back().pose.rotation_matrix().col(2);
  BOOST_TEST(z_tip.z() < 0.0, "tip tangent " << z_tip.transpose());  // past 90 degrees
  const double err = (tip(r) - tip(ref)).norm();
  const auto r2 = solve(P, "kinsol", 81);
  const double err2 = (tip(r2) - tip(ref)).norm();
  BOOST_TEST_MESSAGE("tension 4 N: kinsol tip errors " << err << ", " << err2 << " m (N = 41, 81), "
                     << r.iterations << ", " << r2.iterations << " iterations");
  BOOST_TEST(err < 5e-6 * kL);
  BOOST_TEST(std::log2(err / err2) > 3.3);
}

// Reference: rkmk-rk4 at N = 401 for a volume-controlled chamber on part of the rod and a muscle,
// under gravity (extra unknowns: the chamber's pressure and the muscle's length).
BOOST_AUTO_TEST_CASE(volume_control_and_muscle) {
  const auto m = table21();
  StaticProblem P(m, lie::SE3::identity());
  P.set_gravity(loads::Gravity(m, lie::Vector3(-9.81, 0, 0)));
  add_chamber_and_muscle(P);  // 2 % over the chamber's rest volume
  check_order_four(P, "volume control and muscle");
}

BOOST_AUTO_TEST_CASE(too_few_nodes_for_the_breakpoints) {
  StaticProblem P(table21(), lie::SE3::identity());
  auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.03, 0.07);
  a.input = 0.5;
  P.add_actuator(a);
  BOOST_CHECK_THROW(solve_static(P, {"kinsol", 3, 1e-12, 50}), std::invalid_argument);
  BOOST_TEST(solve_static(P, {"kinsol", 4, 1e-12, 50}).converged);
}
