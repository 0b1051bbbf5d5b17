#pragma once
// Shared by the actuator tests of tests/statics (test_actuators.cpp: closed forms for every
// scheme and the shooting schemes' orders; test_kinsol_actuators.cpp, test_chebyshev_actuators.cpp):
// the Table 2.1 rod, straight tendon paths, a checked solve, and the closed form of a constant
// twist.
#include <boost/test/unit_test.hpp>

#include <numbers>

#include <Eigen/Dense>

#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::testing::actuators {

using namespace rodlab::solvers::statics;

// Thesis Table 2.1 rod: E = 1 MPa, G = 0.33 MPa, rho = 1000, D = 1 cm, L = 10 cm.
inline rod::RodModel table21(rod::ModelKind kind = rod::ModelKind::cosserat) {
  return {0.1, rod::Circle{0.01}, rod::Material{1e6, 0.33e6, 1000, 0}, kind};
}
inline constexpr double kL = 0.1;

/// A tendon at the constant offset (x, y) over [s0, s1].
inline ActuatorTerm straight(ActuatorKind kind, double x, double y, double s0 = 0.0,
                             double s1 = kL) {
  return {kind, loads::TendonPath({{0.0, Eigen::Vector2d(x, y)}}, s0, s1)};
}

/// Solves to 1e-12; requires convergence and det / orthogonality deviations <= 1e-13.
inline result::StaticResult solve(const StaticProblem& P, const char* scheme, int nodes) {
  auto r = solve_static(P, {scheme, nodes, 1e-12, 50});
  BOOST_TEST_REQUIRE(r.converged, scheme << " N=" << nodes << ": " << r.reason);
  BOOST_TEST(r.max_det_deviation <= 1e-13);
  BOOST_TEST(r.max_orthogonality_error <= 1e-13);
  return r;
}

/// The volume-controlled chamber (2 % over its rest volume) on [0, 0.0613] and the muscle on
/// [0.0287, L] (test_kinsol_actuators, test_chebyshev_actuators): two extra unknowns.
inline void add_chamber_and_muscle(StaticProblem& P) {
  auto a = straight(ActuatorKind::fluidic, 0.0, 0.003, 0.0, 0.0613);
  a.chamber_area = std::numbers::pi * 1e-6;
  a.input = 1.02 * 0.0613 * a.chamber_area;
  a.target_length = 0.0;
  P.add_actuator(a);
  auto mu = straight(ActuatorKind::muscle, 0.003, 0.0, 0.0287, kL);
  mu.input = 1.5;
  mu.law = loads::make_muscle_law("linear", 0.2, 0.8);
  const auto pa = rod::properties(rod::Circle{0.001});
  const double Ea = 5e6;
  mu.embedded_stiffness << Ea * pa.Ix, Ea * pa.Iy, Ea / 2.6 * pa.Jt, Ea / 2.6 * pa.A, Ea / 2.6 * pa.A, Ea * pa.A;
  P.add_actuator(mu);
}

/// The tip position of a result.
inline lie::Vector3 tip(const result::StaticResult& r) {
  return r.centerline.back().pose.translation();
}

/// Every node has the twist xi and the pose exp(s xi) (2.78), to tol (positions to tol L).
inline void check_constant_twist(const result::StaticResult& r, const lie::Vector6& xi,
                                 double tol) {
  for (const auto& node : r.centerline) {
    BOOST_TEST((node.twist - xi).norm() <= tol, "s = " << node.s << " twist " << node.twist.transpose());
    const lie::SE3 exact = lie::SE3::exp(node.s * xi);
    BOOST_TEST((node.pose.translation() - exact.translation()).norm() <= tol * kL);
  }
}

}  // namespace rodlab::testing::actuators
