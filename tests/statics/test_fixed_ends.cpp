#define BOOST_TEST_MODULE statics_fixed_ends
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "fixed_ends_support.hpp"

// Case 7: both ends fixed (thesis 2.7.2): Table 2.1 Cosserat rod, no loads, base at the
// identity, tip clamped at [0.1 L, 0, L] with the identity rotation. Every scheme must converge
// from the solver's own start for N in {5, ..., 20, 25, 50, 100, 150, 200} (the full 5..200 sweep
// is test_fixed_ends_sweep.cpp, validation), with the tip on its target and the base wrench
// within C h^p of rkmk-rk4 at N = 1601 (fixed_ends_support.hpp). The thesis reports that its
// implicit midpoint scheme failed at N = 15; checked explicitly below.
//
// The thesis's target is not reachable by a Kirchhoff rod (inextensible: the centreline from
// the origin to [0.1 L, 0, L] is longer than L): it must be reported as not converged. (A
// reachable offset such as [0.1 L, 0, 0.95 L] compresses the rod into a post-buckled S with
// several equilibria, and different schemes and N land on different ones, so it is not used.)
// The Kirchhoff clamped-clamped check is the arc-end target, which has a closed form.

namespace {

using namespace rodlab;
using namespace rodlab::testing::statics;
using rod::ModelKind;

std::vector<int> unit_grid() {
  std::vector<int> n;
  for (int i = 5; i <= 20; ++i) n.push_back(i);
  for (const int i : {25, 50, 100, 150, 200}) n.push_back(i);
  return n;
}

const StaticResult& cosserat_reference() {
  static const StaticResult r = solve(fixed_ends(ModelKind::cosserat), "rkmk-rk4", 1601);
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_scheme_converges_and_agrees) {
  const auto problem = fixed_ends(ModelKind::cosserat);
  const auto& ref = cosserat_reference();
  BOOST_TEST_REQUIRE(check_result(ref, 1601));
  BOOST_TEST_MESSAGE("reference " << describe(ref) << ", base wrench " << ref.base_wrench.transpose());
  for (const auto& s : statics_schemes_under_test()) {
    std::ostringstream row;
    row << s.name << ":";
    int max_it = 0;
    double worst_ratio = 0.0;
    for (const int N : grid_for(s, unit_grid())) {
      const auto r = solve(problem, s.name, N);
      const double e = check_fixed_ends(problem, s, r, ref);
      if (!r.converged) row << " N=" << N << " FAILED";
      max_it = std::max(max_it, r.iterations);
      if (!s.spectral) worst_ratio = std::max(worst_ratio, e / std::pow(1.0 / (N - 1), s.design_order));
      if (N == 5 || N == 15 || N == 100 || N == 200) row << " N=" << N << " e=" << e << " it=" << r.iterations;
    }
    row << "; max iterations " << max_it << ", max e/(h/L)^p = " << worst_ratio;
    BOOST_TEST_MESSAGE(row.str());
  }
}

// The thesis (2.7.2, Results): "Only one solution failed to solve which was the fixed ends implicit
// midpoint scheme with N = 15". Here it must converge, like every other N.
BOOST_AUTO_TEST_CASE(implicit_midpoint_n15) {
  const auto problem = fixed_ends(ModelKind::cosserat);
  const auto r = solve(problem, "rkmk-midpoint-implicit", 15);
  if (!check_result(r, 15)) return;
  BOOST_TEST_MESSAGE("rkmk-midpoint-implicit N = 15: " << describe(r) << ", base wrench error "
                                                      << base_wrench_error(problem, r, cosserat_reference()));
}

// Symmetry of the S-shape: the configuration is centrally symmetric about the midpoint
// (p(L - s) = p_L - p(s), R(L - s) = R(s), curvature odd), so the bending moments at the two
// ends are equal and opposite: m_y(0) = -m_y(L), where m(L) = K_w omega(L) is the moment the tip
// clamp exerts. With no distributed load the world-frame force is constant; R(0) = R(L) = I,
// so Lambda_f(L) = Lambda_f(0). Checked to the discretisation bound of each scheme (N = 101).
BOOST_AUTO_TEST_CASE(s_shape_end_moments_equal_and_opposite) {
  const auto problem = fixed_ends(ModelKind::cosserat);
  const Vector6 K = problem.model().K_diag();
  for (const auto& s : statics_schemes_under_test()) {
    const int N = nodes_cap(s, 101);
    const auto r = solve(problem, s.name, N);
    if (!check_result(r, N)) continue;
    const Vector6 Lambda_L = K.cwiseProduct(r.centerline.back().twist - problem.model().xi_star());
    const double m0 = r.base_wrench[1], mL = Lambda_L[1];
    const double bound = agreement_bound(s, N, kFixedEndsC, 1e-9);
    BOOST_TEST(std::abs(m0 + mL) <= bound * std::abs(m0),
               describe(r) << ": m_y(0) = " << m0 << ", m_y(L) = " << mL);
    BOOST_TEST((r.base_wrench.tail<3>() - Lambda_L.tail<3>()).norm() <= bound * r.base_wrench.tail<3>().norm());
    // Other moment components vanish (the problem is planar).
    BOOST_TEST(std::abs(r.base_wrench[0]) + std::abs(r.base_wrench[2]) <= 1e-12 * std::abs(m0));
    BOOST_TEST_MESSAGE(describe(r) << ": (m_y(0) + m_y(L)) / m_y(0) = " << (m0 + mL) / m0);
  }
}

// Small-displacement limit: lateral offset delta = 1e-4 L. Guided (clamped-clamped with a
// lateral offset) Timoshenko beam: bending deflection F L^3/(12 EI) (x = delta (3 (s/L)^2 -
// 2 (s/L)^3), EI x''' = -12 EI delta / L^3) plus shear deflection F L/(GA), so
//     F = delta / (L^3/(12 EI) + L/(GA)),   end moments F L / 2.
// Relative 1e-3 (nonlinear corrections O((delta/L)^2), the axial force from stretching is
// ~1e-8 EA). Each scheme on a grid where its discretisation error is below 1e-4: the measured
// constants of the end moment are 1.0 (h/L) for the Euler schemes and 1.0 (h/L)^2 for the
// midpoint schemes, so nodes_for(C = 1, 1e-4): N = 10001, 101, 11 for orders 1, 2, 4.
BOOST_AUTO_TEST_CASE(small_offset_lateral_force) {
  const double L = Table21::L, delta = 1e-4 * L;
  const double F = delta / (L * L * L / (12.0 * Table21::EI) + L / Table21::GA);
  const auto problem = fixed_ends(ModelKind::cosserat, delta);
  for (const auto& s : statics_schemes_under_test()) {
    const int N = nodes_for(s, 1.0, 1e-4, 11, 10001);
    const auto r = solve(problem, s.name, N);
    if (!check_result(r, N)) continue;
    // The clamp at the base exerts -Lambda(0); Lambda_f,x(0) is the force the rod beyond
    // exerts across the base section: +F pulls the tip towards +x.
    const double ef = r.base_wrench[3] / F - 1.0, em = r.base_wrench[1] / (F * L / 2.0) - 1.0;
    BOOST_TEST(std::abs(ef) <= 1e-3, describe(r) << ": lateral force " << r.base_wrench[3] << ", Timoshenko " << F);
    BOOST_TEST(std::abs(em) <= 1e-3, describe(r) << ": base moment " << r.base_wrench[1] << ", F L/2 = " << F * L / 2);
    BOOST_TEST_MESSAGE(describe(r) << ": lateral force rel err " << ef << ", end moment rel err " << em);
  }
  // The shear correction matters at this tolerance: 12 EI / (GA L^2) = 2.3 %.
  BOOST_TEST(12.0 * Table21::EI / (Table21::GA * L * L) > 10 * 1e-3);
}

// A clamped tip with a closed-form solution: the end pose of the pure-bending arc,
// g_target = exp(L xi) with xi = [kappa, 0, 0, 0, 0, 1] (case 1). The arc, with the constant
// internal wrench Lambda = [EI kappa, 0, 0, 0, 0, 0], satisfies (2.34) with no loads and reaches
// the target, and every scheme reproduces it to rounding (constant strain), so the solve must
// return Lambda(0) = [EI kappa; 0] and the arc's poses at every node, for both rod models
// (Kirchhoff: the constraint force is 0). kappa L in {0.3, 1} here, 3 in the validation file
// test_statics_robustness.cpp; the continuation walks the target along the SE(3) geodesic from
// the straight rod's tip pose.
//
// FAILS (solver, reported to the lead): Cosserat, kappa L = 1. rkmk-euler-implicit N = 5 does not
// converge (continuation stalls at load factor 0.12), and rkmk-midpoint-explicit,
// rkmk-midpoint-implicit and rkmk-rk4 at N = 100 report convergence (residual ~1e-14) to a
// different, spurious equilibrium: a coiled rod with 30 % axial stretch, shear strain up to 0.86,
// curvature up to 370 /m and base wrench ~[0.058 N m, 0, 0, 0, -11.2 N, 20.5 N] instead of
// [EI kappa = 4.9e-3 N m; 0]. At N = 21 every scheme finds the arc. Kirchhoff rods find the arc
// for every scheme and N (4-17 iterations).
BOOST_AUTO_TEST_CASE(clamped_at_the_arc_end) {
  const double L = Table21::L;
  double worst_wrench = 0.0, worst_pose = 0.0;
  for (const ModelKind kind : {ModelKind::cosserat, ModelKind::kirchhoff}) {
    for (const double kL : {0.3, 1.0}) {
      const double kappa = kL / L;
      StaticProblem problem = table21_problem(kind);
      problem.set_tip_clamped(bent_arc_pose(kappa, L));
      const Vector6 expected = (Vector6() << Table21::EI * kappa, 0, 0, 0, 0, 0).finished();
      const Vector6 scale = problem.wrench_scale();
      for (const auto& s : statics_schemes_under_test()) {
        for (const int N : grid_for(s, {5, 21, 100})) {
          const auto r = solve(problem, s.name, N);
          if (!check_result(r, N)) continue;
          const double ew = (r.base_wrench - expected).cwiseQuotient(scale).norm() / expected.cwiseQuotient(scale).norm();
          double ep = 0.0;
          for (const auto& c : r.centerline) ep = std::max(ep, pose_error(c.pose, bent_arc_pose(kappa, c.s)).max());
          BOOST_TEST(ew <= 1e-9, kind_name(kind) << " kappa L = " << kL << " " << describe(r) << ": base wrench error " << ew);
          BOOST_TEST(ep <= 1e-10, kind_name(kind) << " kappa L = " << kL << " " << describe(r) << ": node pose error " << ep);
          worst_wrench = std::max(worst_wrench, ew);
          worst_pose = std::max(worst_pose, ep);
          if (N == 21) BOOST_TEST_MESSAGE("clamped arc " << kind_name(kind) << " kappa L = " << kL << " " << describe(r));
        }
      }
    }
  }
  BOOST_TEST_MESSAGE("clamped arc: worst base wrench error " << worst_wrench << ", worst node pose error " << worst_pose);
}

// The same arc's target moved by rounding-level twists (1e-15 to 4e-15 in each component, 20
// moves; Cosserat, kappa L = 0.3, N = 5). A clamped Cosserat tip's axial position error costs
// EA / L of axial force, 16 (L / D)^2 = 1600 times the force scale, so a solve stopped on the
// residual's tolerance alone left base wrench errors up to 1.9e-9 (over 1e-9 in 6-10 of the 20
// for every shooting scheme, session 34); the shooting's step tolerance holds the wrench
// (docs/statics.md "Stopping where the tip is clamped"). Reference: the closed form, which the
// moves change by about 1.3e-10 (chebyshev's and kinsol's error).
BOOST_AUTO_TEST_CASE(clamped_arc_under_rounding_level_moves_of_the_target) {
  const double L = Table21::L, kappa = 0.3 / L;
  const Vector6 expected = (Vector6() << Table21::EI * kappa, 0, 0, 0, 0, 0).finished();
  for (const auto& s : statics_schemes_under_test()) {
    double worst = 0.0;
    for (int k = 0; k < 20; ++k) {
      StaticProblem problem = table21_problem(ModelKind::cosserat);
      Vector6 twist = Vector6::Zero();
      twist[k % 6] = (1 + k / 6) * 1e-15;
      problem.set_tip_clamped(bent_arc_pose(kappa, L) * SE3::exp(twist));
      const auto r = solve(problem, s.name, 5);
      if (!check_result(r, 5)) continue;
      const Vector6 scale = problem.wrench_scale();
      worst = std::max(worst, (r.base_wrench - expected).cwiseQuotient(scale).norm() /
                                  expected.cwiseQuotient(scale).norm());
    }
    BOOST_TEST(worst <= 1e-9, s.name << ": worst base wrench error " << worst);
    BOOST_TEST_MESSAGE("clamped arc, moved targets, " << s.name << ": worst " << worst);
  }
}

// Kirchhoff: the thesis's target would need the inextensible rod to stretch (the centreline from
// the origin to [0.1 L, 0, L] is longer than L); no scheme may report it as a solution.
BOOST_AUTO_TEST_CASE(kirchhoff_unreachable_target_not_converged) {
  const auto unreachable = fixed_ends(ModelKind::kirchhoff);
  for (const auto& s : statics_schemes_under_test()) {
    const auto r = solve(unreachable, s.name, 11);
    BOOST_TEST(!r.converged, describe(r) << " claims to reach a target beyond the inextensible rod's length");
    BOOST_TEST(!r.reason.empty());
    BOOST_TEST_MESSAGE("kirchhoff unreachable " << describe(r));
  }
}
