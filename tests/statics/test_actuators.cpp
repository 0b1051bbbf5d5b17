#define BOOST_TEST_MODULE actuators
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "actuator_support.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

using namespace rodlab;
using namespace rodlab::solvers::statics;
using namespace rodlab::testing::actuators;
namespace tt = boost::test_tools;

namespace {

/// The closed forms below hold for every statics scheme (a constant twist is exact for each).
const char* const kEveryScheme[] = {"rkmk-euler-explicit",    "rkmk-euler-implicit",
                                    "rkmk-midpoint-explicit", "rkmk-midpoint-implicit",
                                    "rkmk-rk4",               "chebyshev",
                                    "kinsol"};

}  // namespace

// Reference (closed form): a straight cable at offset r = [d, 0, 0] with tension T and no other
// load. Lambda = 0 everywhere (the tendon is internal, tip free), so K (xi - xi*) = -T [r x t; t]
// with t = z: E I kappa_y = T d, E A (nu_z - 1) = -T; the rod is a circular arc (2.78).
// T = 3 N bends the tip by kappa L = 2.44 rad, past 90 degrees.
BOOST_AUTO_TEST_CASE(straight_cable_gives_constant_curvature) {
  const auto m = table21();
  const double d = 0.004, EI = m.K_diag()[1], EA = m.K_diag()[5];
  for (double T : {0.5, 3.0}) {
    StaticProblem P(m, lie::SE3::identity());
    auto a = straight(ActuatorKind::cable, d, 0.0);
    a.input = T;
    P.add_actuator(a);
    lie::Vector6 xi;
    xi << 0, T * d / EI, 0, 0, 0, 1 - T / EA;
    for (const char* scheme : kEveryScheme) check_constant_twist(solve(P, scheme, 21), xi, 1e-10);
  }
}

// Reference: the Kirchhoff rod keeps nu = nu*, so only E I kappa_y = T d.
BOOST_AUTO_TEST_CASE(straight_cable_kirchhoff) {
  const auto m = table21(rod::ModelKind::kirchhoff);
  StaticProblem P(m, lie::SE3::identity());
  auto a = straight(ActuatorKind::cable, 0.004, 0.0);
  a.input = 0.5;
  P.add_actuator(a);
  lie::Vector6 xi;
  xi << 0, 0.5 * 0.004 / m.K_diag()[1], 0, 0, 0, 1;
  for (const char* scheme : kEveryScheme) check_constant_twist(solve(P, scheme, 21), xi, 1e-10);
}

// Reference: a straight fluidic chamber at r = [0, e, 0] with pressure P acts as a tendon with
// F = -P A_c (docs/statics.md). c = [r x z; z] = [e, 0, 0, 0, 0, 1], and K (xi - xi*) = -F c gives
// E I kappa_x = P A_c e and E A (nu_z - 1) = P A_c: the rod extends and bends away from the chamber.
BOOST_AUTO_TEST_CASE(straight_fluidic_chamber_extends_and_bends_away) {
  const auto m = table21();
  const double e = 0.003, Ac = std::numbers::pi * 1e-6, P_in = 2e4;
  StaticProblem P(m, lie::SE3::identity());
  auto a = straight(ActuatorKind::fluidic, 0.0, e);
  a.chamber_area = Ac;
  a.input = P_in;
  P.add_actuator(a);
  lie::Vector6 xi;
  xi << P_in * Ac * e / m.K_diag()[0], 0, 0, 0, 0, 1 + P_in * Ac / m.K_diag()[5];
  for (const char* scheme : kEveryScheme) check_constant_twist(solve(P, scheme, 11), xi, 1e-12);
  // The chamber is on +y and the rod bends away from it (towards -y).
  BOOST_TEST(solve(P, "rkmk-rk4", 11).centerline.back().pose.translation().y() < 0.0);
}

// Reference: two cables at +-d with the same tension cancel their moments: pure compression 2T.
BOOST_AUTO_TEST_CASE(opposite_cables_sum_to_compression) {
  const auto m = table21();
  StaticProblem P(m, lie::SE3::identity());
  for (double x : {0.004, -0.004}) {
    auto a = straight(ActuatorKind::cable, x, 0.0);
    a.input = 0.7;
    P.add_actuator(a);
  }
  lie::Vector6 xi;
  xi << 0, 0, 0, 0, 0, 1 - 1.4 / m.K_diag()[5];
  for (const char* scheme : kEveryScheme) check_constant_twist(solve(P, scheme, 11), xi, 1e-12);
}

// Reference: displacement control (2.47) inverts tension control. With the closed form above,
// the cable's current length is (nu_z - kappa d) L (u = nu + omega x r = [0, 0, nu_z - kappa d]);
// prescribing the displacement L - that length must give back T, and the same shape.
BOOST_AUTO_TEST_CASE(displacement_control_recovers_the_tension) {
  const auto m = table21();
  const double d = 0.004, T = 0.5, EI = m.K_diag()[1], EA = m.K_diag()[5];
  const double kappa = T * d / EI, nu_z = 1 - T / EA;
  StaticProblem P(m, lie::SE3::identity());
  auto a = straight(ActuatorKind::cable, d, 0.0);
  a.input = kL - (nu_z - kappa * d) * kL;  // displacement
  a.target_length = 0.0;                   // marks length control; add_actuator sets it
  P.add_actuator(a);
  for (const char* scheme : kEveryScheme) {
    const auto r = solve(P, scheme, 21);
    lie::Vector6 xi;
    xi << 0, kappa, 0, 0, 0, nu_z;
    check_constant_twist(r, xi, 1e-9);
  }
}

// A displacement below the one the cable needs to stay taut asks for a pushing cable: reported.
BOOST_AUTO_TEST_CASE(slack_cable_is_reported) {
  StaticProblem P(table21(), lie::SE3::identity());
  auto a = straight(ActuatorKind::cable, 0.004, 0.0);
  a.input = -0.001;  // let the cable out by 1 mm: it would have to push the rod
  a.target_length = 0.0;
  P.add_actuator(a);
  for (const char* scheme : kEveryScheme) {
    const auto r = solve_static(P, {scheme, 21, 1e-12, 50});
    BOOST_TEST(!r.converged, scheme);
    BOOST_TEST(r.reason.find("slack") != std::string::npos, scheme << ": " << r.reason);
  }
}

// Reference: the muscle's fixed point (2.64)-(2.67). A straight muscle at r = [d, 0, 0] with its
// own stiffness K_a and the linear law F = g q - k (Delta - Delta*)/Delta*, no external load.
// With Delta xi = [0, kappa, 0, 0, 0, e] and t = z, the balance of moments about y and forces
// along z is linear in (kappa, e):
//   (E I + E I_a + d^2 E A_a) kappa - d E A_a e - F d = 0,
//   -d E A_a kappa + (E A + E A_a) e + F = 0,
//   F = g q - k (e - kappa d)          (Delta = (1 + e - kappa d) L, Delta* = L, (2.66)).
BOOST_AUTO_TEST_CASE(muscle_fixed_point) {
  const auto m = table21();
  const double d = 0.003, gain = 0.2, q = 1.5, k = 0.8;
  const auto pa = rod::properties(rod::Circle{0.001});
  const double Ea = 5e6;
  const double EIa = Ea * pa.Ix, EAa = Ea * pa.A, EI = m.K_diag()[1], EA = m.K_diag()[5];
  Eigen::Matrix2d A;
  A << EI + EIa + d * d * EAa - k * d * d, -d * EAa + k * d,  //
      -d * EAa + k * d, EA + EAa - k;
  const Eigen::Vector2d rhs(gain * q * d, -gain * q);
  const Eigen::Vector2d sol = A.partialPivLu().solve(rhs);

  StaticProblem P(m, lie::SE3::identity());
  auto a = straight(ActuatorKind::muscle, d, 0.0);
  a.input = q;
  a.law = loads::make_muscle_law("linear", gain, k);
  a.embedded_stiffness << Ea * pa.Ix, Ea * pa.Iy, Ea / 2.6 * pa.Jt, Ea / 2.6 * pa.A, Ea / 2.6 * pa.A, Ea * pa.A;
  P.add_actuator(a);
  lie::Vector6 xi;
  xi << 0, sol[0], 0, 0, 0, 1 + sol[1];
  for (const char* scheme : kEveryScheme) check_constant_twist(solve(P, scheme, 11), xi, 1e-10);
  BOOST_TEST(sol[0] > 0.0);  // the contracting muscle bends the rod towards itself
}

// Reference: convergence order with a cable that ends off the grid (span [0, 0.0437]) under
// gravity, against rkmk-rk4 at N = 801: the breakpoint splitting keeps every method's order.
BOOST_AUTO_TEST_CASE(partial_span_keeps_the_order) {
  const auto m = table21();
  StaticProblem P(m, lie::SE3::identity());
  P.set_gravity(loads::Gravity(m, lie::Vector3(-9.81, 0, 0)));
  auto a = straight(ActuatorKind::cable, 0.004, 0.002, 0.0, 0.0437);
  a.input = 1.0;
  P.add_actuator(a);
  const lie::Vector3 ref = solve(P, "rkmk-rk4", 801).centerline.back().pose.translation();
  const std::pair<const char*, double> cases[] = {{"rkmk-euler-explicit", 1}, {"rkmk-midpoint-explicit", 2}, {"rkmk-rk4", 4}};
  for (const auto& [scheme, order] : cases) {
    const int N1 = order == 4 ? 11 : 41, N2 = 2 * N1 - 1;
    const double e1 = (solve(P, scheme, N1).centerline.back().pose.translation() - ref).norm();
    const double e2 = (solve(P, scheme, N2).centerline.back().pose.translation() - ref).norm();
    const double observed = std::log2(e1 / e2);
    BOOST_TEST_MESSAGE(scheme << ": errors " << e1 << ", " << e2 << ", observed order " << observed);
    BOOST_TEST(std::abs(observed - order) < 0.3, scheme << " observed order " << observed);
  }
}

// Reference: the rest length of a routed cable on the straight rod is the length of its
// straight-line segments, sqrt(dz^2 + dr^2) summed (2.47 at xi = xi*).
BOOST_AUTO_TEST_CASE(routing_rest_length_and_convergence) {
  const auto m = table21();
  StaticProblem P(m, lie::SE3::identity());
  ActuatorTerm a{ActuatorKind::cable, loads::TendonPath({{0.0, Eigen::Vector2d(0.004, 0)},
                                                        {0.05, Eigen::Vector2d(0.0, 0.004)},
                                                        {0.1, Eigen::Vector2d(-0.004, 0)}},
                                                       0.0, kL)};
  a.input = 0.4;
  P.add_actuator(a);
  const double seg = std::hypot(0.05, std::hypot(0.004, 0.004));
  BOOST_TEST(P.actuators()[0].rest_length == 2 * seg, tt::tolerance(1e-12));
  const lie::Vector3 ref = solve(P, "rkmk-rk4", 401).centerline.back().pose.translation();
  const double e1 = (solve(P, "rkmk-rk4", 11).centerline.back().pose.translation() - ref).norm();
  const double e2 = (solve(P, "rkmk-rk4", 21).centerline.back().pose.translation() - ref).norm();
  BOOST_TEST(std::log2(e1 / e2) > 3.7);
  // A twisted routing makes the rod twist: the tip rotation has a z component.
  BOOST_TEST(std::abs(solve(P, "rkmk-rk4", 21).centerline.back().pose.rotation().log().z()) > 1e-4);
}
