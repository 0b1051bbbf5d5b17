#define BOOST_TEST_MODULE chebyshev_actuators
#include <boost/test/unit_test.hpp>

// The chebyshev statics scheme with actuators (solvers/include/rodlab/solvers/statics/chebyshev.hpp,
// "Actuators"; docs/statics.md): spectral elements with boundaries at the actuators' breakpoints,
// the tendon law linearised in the Newton matrix, entry jumps, and extra unknowns with
// Clenshaw-Curtis path lengths. The Table 2.1 rod (E = 1 MPa, G = 0.33 MPa, D = 1 cm, L = 10 cm).
//
// References: the closed forms of constant strain (a straight cable, a straight chamber,
// displacement control and slack, the muscle's fixed point) are in test_actuators.cpp, which
// runs them for every statics scheme; here piecewise constant strain at a span end; otherwise the cases of test_kinsol_actuators.cpp against rkmk-rk4 at N = 401 (against
// which kinsol's errors are 5e-12 .. 3e-11 m at N = 81) and kinsol at N = 81; the Newton matrix
// against central differences of the residual.

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Dense>

#include "../cli/cli_support.hpp"
#include "actuator_support.hpp"
#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/statics/chebyshev.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

using namespace rodlab;
using namespace rodlab::solvers::statics;
using namespace rodlab::testing::actuators;

namespace {

StaticProblem under_gravity(rod::ModelKind kind = rod::ModelKind::cosserat) {
  StaticProblem P(table21(kind), lie::SE3::identity());
  P.set_gravity(loads::Gravity(P.model(), lie::Vector3(-9.81, 0, 0)));
  return P;
}

/// The routed cable of test_kinsol_actuators: offset from [-d, 0] through [0, -d] (knot at L/2)
/// to [d, 0].
ActuatorTerm routed_cable(double tension) {
  ActuatorTerm c{ActuatorKind::cable, loads::TendonPath({{0.0, Eigen::Vector2d(-0.004, 0)},
                                                        {0.05, Eigen::Vector2d(0.0, -0.004)},
                                                        {0.1, Eigen::Vector2d(0.004, 0)}},
                                                       0.0, kL)};
  c.input = tension;
  return c;
}

/// Spectral convergence of the tip against rkmk-rk4 at N = 401, with kinsol at N = 81 as a
/// second reference. Measured (tip errors in m at N = 12, 24, 32, noted per case): the error at
/// N = 24 is 3e-14 .. 3.2e-10 m, and from N = 12 to 24 it falls by 4e4 .. 1e7, an observed
/// algebraic order of 14 .. 22 (log(e12/e24)/log(23/11); kinsol's is 4). Asserted: e24 <= 2e-9,
/// e32 <= 3e-10, e12/e24 >= 1000 (order > 9.4), and within 1e-9 m of kinsol at N = 81 (whose
/// own errors there are up to 3.9e-10 m; measured 6e-12 .. 4e-10).
void check_spectral(const StaticProblem& P, const char* what) {
  const lie::Vector3 ref = tip(solve(P, "rkmk-rk4", 401));
  const lie::Vector3 kin = tip(solve(P, "kinsol", 81));
  double e[3];
  const int Ns[3] = {12, 24, 32};
  for (int k = 0; k < 3; ++k) e[k] = (tip(solve(P, "chebyshev", Ns[k])) - ref).norm();
  const double to_kinsol = (tip(solve(P, "chebyshev", 32)) - kin).norm();
  BOOST_TEST_MESSAGE(what << ": chebyshev tip errors " << e[0] << ", " << e[1] << ", " << e[2]
                          << " m (N = 12, 24, 32), observed order 12 -> 24: "
                          << std::log(e[0] / e[1]) / std::log(23.0 / 11.0) << "; |chebyshev 32 - kinsol 81| "
                          << to_kinsol);
  BOOST_TEST(e[1] <= 2e-9, what);
  BOOST_TEST(e[2] <= 3e-10, what);
  BOOST_TEST(e[0] >= 1000.0 * e[1], what << ": e12 / e24 = " << e[0] / e[1]);
  BOOST_TEST(to_kinsol <= 1e-9, what);
}

}  // namespace

// Reference (closed form): a cable on [0, s1] anchored at s1 = 0.0613 (a span end, a breakpoint
// off the Chebyshev nodes of one element) with no other load: Lambda = 0 everywhere, so the
// strain is the arc's up to s1 and xi* beyond; g(s) = exp(s xi) for s <= s1, exp(s1 xi)
// exp((s - s1) xi*) beyond. An element boundary at s1 makes both pieces exact.
BOOST_AUTO_TEST_CASE(span_end_gives_piecewise_constant_strain) {
  const auto m = table21();
  const double d = 0.004, T = 1.0, s1 = 0.0613;
  StaticProblem P(m, lie::SE3::identity());
  auto a = straight(ActuatorKind::cable, d, 0.0, 0.0, s1);
  a.input = T;
  P.add_actuator(a);
  lie::Vector6 xi;
  xi << 0, T * d / m.K_diag()[1], 0, 0, 0, 1 - T / m.K_diag()[5];
  const auto r = solve(P, "chebyshev", 9);
  bool saw_s1 = false;
  for (const auto& node : r.centerline) {
    saw_s1 = saw_s1 || node.s == s1;
    const lie::SE3 exact = node.s <= s1 ? lie::SE3::exp(node.s * xi)
                                        : lie::SE3::exp(s1 * xi) * lie::SE3::exp((node.s - s1) * m.xi_star());
    BOOST_TEST((node.pose.translation() - exact.translation()).norm() <= 1e-12 * kL, "s = " << node.s);
    BOOST_TEST((node.twist - (node.s < s1 ? xi : m.xi_star())).norm() <= 1e-10, "s = " << node.s);
  }
  BOOST_TEST(saw_s1, "a node at the span end");
}

// Reference: the Newton matrix (closed-form Lambda columns through the linearised tendon law,
// entry-jump rows, chart blocks, the border of extra unknowns) against central differences of
// the residual at the Newton iterate. Measured 8e-12 .. 2e-10 with actuators (1e-10 without);
// with dxi/dLambda = K^-1 (the tendon law's Jacobian left out) 2e-3 .. 6e-2, so the bound 1e-7
// tells them apart.
BOOST_AUTO_TEST_CASE(newton_matrix_is_the_jacobian) {
  auto check = [](const StaticProblem& P, const char* what) {
    for (int N : {8, 16}) {
      const double error = chebyshev_newton_matrix_error(P, {N, 1e-12, 50});
      BOOST_TEST_MESSAGE(what << ", N = " << N << ": Newton matrix error " << error);
      BOOST_TEST(error < 1e-7, what << ", N = " << N);
    }
  };
  {
    StaticProblem P = under_gravity();  // a cable entering at 0.0213 with T = 4 N
    auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.0213, kL);
    a.input = 4.0;
    P.add_actuator(a);
    check(P, "cable entering");
  }
  {
    StaticProblem P = under_gravity();
    add_chamber_and_muscle(P);
    check(P, "volume control and muscle");
  }
  {
    StaticProblem P = under_gravity(rod::ModelKind::kirchhoff);
    auto c = routed_cable(0.0);
    c.input = 0.002;  // displacement control, pulled in by 2 mm
    c.target_length = 0.0;
    P.add_actuator(c);
    check(P, "Kirchhoff, routed cable under displacement control");
  }
}

// Reference: rkmk-rk4 at N = 401 and kinsol at N = 81 (check_spectral). The cases of
// test_kinsol_actuators under gravity. Measured tip errors at N = 12, 24, 32 (m):
//   cable entering at 0.0437          3.9e-6, 2.6e-11, 9e-15
//   chamber on [0.0213, 0.0771]       1.9e-6, 3.6e-11, 4e-14
//   two cables (entry, span end)      1.7e-5, 1.2e-11, 5e-15
//   routed cable (knot at L/2)        3.2e-7, 3.6e-14, 1e-15
//   the three cables                  1.2e-5, 3.2e-10, 3.0e-11
//   volume control + muscle           5.3e-6, 2.1e-11, 5e-15
//   Kirchhoff, cable entering         3.7e-6, 2.2e-11, 9e-15
// (against rkmk-rk4 at N = 1601; 4-6 Newton iterations at tol 1e-10).
BOOST_AUTO_TEST_CASE(cases_converge_spectrally) {
  {
    StaticProblem P = under_gravity();
    auto a = straight(ActuatorKind::cable, 0.004, 0.002, 0.0437, kL);
    a.input = 1.0;
    P.add_actuator(a);
    check_spectral(P, "cable entering at 0.0437");
  }
  {
    StaticProblem P = under_gravity();
    auto b = straight(ActuatorKind::fluidic, 0.0, 0.003, 0.0213, 0.0771);
    b.chamber_area = std::numbers::pi * 1e-6;
    b.input = 2e4;
    P.add_actuator(b);
    check_spectral(P, "fluidic chamber on [0.0213, 0.0771]");
  }
  {
    StaticProblem P = under_gravity();
    auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.0, 0.0613);
    a.input = 0.6;
    auto b = straight(ActuatorKind::cable, 0.0, 0.004, 0.0287, kL);
    b.input = 0.4;
    P.add_actuator(a);
    P.add_actuator(b);
    check_spectral(P, "two straight cables");
    StaticProblem Q = under_gravity();
    Q.add_actuator(routed_cable(0.3));
    check_spectral(Q, "routed cable");
    P.add_actuator(routed_cable(0.3));
    check_spectral(P, "three cables");
  }
  {
    StaticProblem P = under_gravity();
    add_chamber_and_muscle(P);
    check_spectral(P, "volume control and muscle");
  }
  {
    StaticProblem P = under_gravity(rod::ModelKind::kirchhoff);
    auto a = straight(ActuatorKind::cable, 0.004, 0.002, 0.0437, kL);
    a.input = 1.0;
    P.add_actuator(a);
    check_spectral(P, "Kirchhoff, cable entering at 0.0437");
  }
}

// Reference: kinsol at N = 161 (4e-12 m from rkmk-rk4 at N = 1601 here). A cable entering at
// 0.0213 with T = 4 N takes the tip past 90 degrees under gravity. Convergence is slower than in
// the cases above: measured 4.0e-6 m at N = 24, 5.1e-9 at N = 32, 2.6e-10 at N = 40 (the
// short element before the entry is compressed by the 4 N pull and takes most of the error).
BOOST_AUTO_TEST_CASE(large_tension_past_ninety_degrees) {
  StaticProblem P = under_gravity();
  auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.0213, kL);
  a.input = 4.0;
  P.add_actuator(a);
  const auto ref = solve(P, "kinsol", 161);
  ChebyshevReport report;
  const auto r = solve_chebyshev(P, {40, 1e-12, 50}, &report);
  BOOST_TEST_REQUIRE(r.converged, r.reason);
  const lie::Vector3 z_tip = r.centerline.back().pose.rotation_matrix().col(2);
  BOOST_TEST(z_tip.z() < 0.0, "tip tangent " << z_tip.transpose());
  const double err = (tip(r) - tip(ref)).norm();
  BOOST_TEST_MESSAGE("tension 4 N, N = 40: tip error " << err << " m, " << report.elements << " elements, "
                                                       << r.iterations << " iterations");
  BOOST_TEST(err < 2e-9);
  BOOST_TEST(report.elements == 3);  // the entry and the split of the 2.56 rad stretch
}

// Reference: kinsol at N = 161. Both ends clamped (the tip at the reference tip) with a cable
// on [0, 0.0613] under gravity: the base wrench (the reaction), which the tip conditions fix.
BOOST_AUTO_TEST_CASE(clamped_tip_with_a_cable) {
  StaticProblem P = under_gravity();
  P.set_tip_clamped(P.reference_tip());
  auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.0, 0.0613);
  a.input = 1.0;
  P.add_actuator(a);
  const auto ref = solve(P, "kinsol", 161);
  const auto r = solve(P, "chebyshev", 24);
  const lie::Vector6 scaled = (r.base_wrench - ref.base_wrench).cwiseQuotient(P.wrench_scale());
  BOOST_TEST_MESSAGE("clamped with a cable: base wrench difference (scaled) " << scaled.lpNorm<Eigen::Infinity>());
  BOOST_TEST(scaled.lpNorm<Eigen::Infinity>() < 1e-8);
}

// Bad input: every stretch between breakpoints is an element of at least one interval, so a
// cable on [0.03, 0.07] (two breakpoints) needs N >= 4; N = 3 is refused with the reason.
BOOST_AUTO_TEST_CASE(too_few_nodes_for_the_breakpoints) {
  StaticProblem P(table21(), lie::SE3::identity());
  auto a = straight(ActuatorKind::cable, 0.004, 0.0, 0.03, 0.07);
  a.input = 0.5;
  P.add_actuator(a);
  try {
    solve_static(P, {"chebyshev", 3, 1e-12, 50});
    BOOST_FAIL("chebyshev accepted 3 nodes for 2 breakpoints");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find("breakpoints") != std::string::npos, e.what());
  }
  BOOST_TEST(solve_static(P, {"chebyshev", 4, 1e-12, 50}).converged);
}

// Reference: kinsol at N = 100. The example scenes with actuators (scenes/cable-driven.yaml
// names chebyshev as its scheme; the chamber at t = 1.5 s, pressure 2e4 Pa), and
// `rodlab static` on the cable scene exits 0.
BOOST_AUTO_TEST_CASE(example_scenes) {
  const std::string dir = std::string(RODLAB_SOURCE_DIR) + "/scenes/";
  for (const auto& [name, t] : {std::pair{"cable-driven.yaml", 0.0}, std::pair{"fluidic-chamber.yaml", 1.5},
                                std::pair{"muscle.yaml", 0.0}}) {
    const scene::Scene scene = io::load_scene(dir + name);
    StaticSolveOptions options{"chebyshev", 24, 1e-12, 50};
    options.time = t;
    const auto r = solve_static(scene, options);
    BOOST_TEST_REQUIRE(r.converged, name << ": " << r.reason);
    options.scheme = "kinsol";
    options.nodes = 100;
    const auto ref = solve_static(scene, options);
    BOOST_TEST((tip(r) - tip(ref)).norm() < 1e-10 * kL, name);
  }
  rodlab::testing::cli::Sandbox box("cheb-actuators");
  const auto run = box.run("static " + rodlab::testing::cli::quote(dir + "cable-driven.yaml"));
  BOOST_TEST(run.status == 0, run.err);
  BOOST_TEST(rodlab::testing::cli::contains(run.out, "chebyshev"), run.out);
}
