#define BOOST_TEST_MODULE kinsol
#include <boost/test/unit_test.hpp>

// The `kinsol` statics reference (RKMK Lobatto IIIA / Hermite-Simpson global collocation solved
// by KINSOL + KLU, kinsol_collocation.hpp) against closed forms and against the rkmk-rk4 shooting
// at N = 1601 (two schemes, one answer). The rod is the thesis's Table 2.1 rod: E = 1e6 Pa, G = 0.33e6 Pa, rho = 1000 kg/m^3,
// circle D = 0.01 m, L = 0.1 m, along +z from the origin, gravity [-9.81, 0, 0] m/s^2.

#include <cmath>
#include <sstream>
#include <thread>
#include <vector>

#include "rodlab/solvers/statics/kinsol_collocation.hpp"
#include "rodlab/solvers/statics/shooting.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace {

using namespace rodlab;
using solvers::statics::KinsolCollocationOptions;
using solvers::statics::KinsolCollocationReport;
using solvers::statics::RkmkMethod;
using solvers::statics::StaticProblem;
using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;

constexpr double kL = 0.1;

rod::RodModel table21_rod(rod::ModelKind kind) {
  return rod::RodModel(kL, rod::Circle{0.01}, rod::Material{1e6, 0.33e6, 1000.0, 0.0}, kind);
}

StaticProblem gravity_cantilever(rod::ModelKind kind) {
  StaticProblem P(table21_rod(kind), SE3::identity());
  P.set_gravity(loads::Gravity(P.model(), Vector3(-9.81, 0.0, 0.0)));
  P.set_name("gravity cantilever");
  return P;
}

StaticProblem both_ends_fixed(rod::ModelKind kind) {
  StaticProblem P = gravity_cantilever(kind);
  P.set_tip_clamped(SE3(SO3::identity(), Vector3(0.01, 0.0, 0.1)));
  P.set_name("both ends fixed");
  return P;
}

KinsolCollocationReport kinsol(const StaticProblem& P, int nodes, double tol = 1e-10) {
  KinsolCollocationOptions options;
  options.nodes = nodes;
  options.tol = tol;
  return solvers::statics::solve_kinsol_collocation_report(P, options);
}

result::StaticResult rk4_reference(const StaticProblem& P) {
  const auto r = solvers::statics::solve_shooting(P, RkmkMethod::rk4, {1601, 1e-12, 50, {}});
  BOOST_REQUIRE(r.converged);
  return r;
}

Vector3 tip_position(const result::StaticResult& r) { return r.centerline.back().pose.translation(); }

void check_structure(const KinsolCollocationReport& k) {
  BOOST_TEST(k.result.max_det_deviation <= 1e-13);
  BOOST_TEST(k.result.max_orthogonality_error <= 1e-13);
}

/// Least-squares slope of log(error) against log(1/h).
double fitted_order(const std::vector<int>& nodes, const std::vector<double>& errors) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double x = std::log(nodes[i] - 1.0), y = std::log(errors[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

void cantilever_order_and_agreement(rod::ModelKind kind, const char* label) {
  const StaticProblem P = gravity_cantilever(kind);
  const auto ref = rk4_reference(P);
  const Vector3 p_ref = tip_position(ref);
  BOOST_TEST_MESSAGE(label << ": rkmk-rk4 N = 1601 tip " << p_ref.transpose());
  const std::vector<int> nodes{11, 21, 41, 81};
  std::vector<double> errors;
  for (int N : nodes) {
    const auto k = kinsol(P, N, 1e-12);
    BOOST_TEST(k.result.converged);
    check_structure(k);
    errors.push_back((tip_position(k.result) - p_ref).norm());
    BOOST_TEST_MESSAGE(label << ": N = " << N << "  tip error " << errors.back() << " m, "
                             << k.nonlinear_iterations << " iterations, " << k.jacobian_evaluations
                             << " Jacobians, " << k.function_evaluations << " residuals, "
                             << "max ||q| - 1| " << k.max_quaternion_norm_error << ", "
                             << k.result.wall_time_s * 1e3 << " ms");
  }
  const double order = fitted_order(nodes, errors);
  BOOST_TEST_MESSAGE(label << ": fitted order " << order);
  BOOST_TEST(order >= 3.9);
  for (std::size_t i = 1; i < errors.size(); ++i) BOOST_TEST(errors[i] < errors[i - 1]);

  const auto k200 = kinsol(P, 200);
  BOOST_TEST(k200.result.converged);
  BOOST_TEST(k200.result.residual_norm <= 1e-10);
  check_structure(k200);
  const double e200 = (tip_position(k200.result) - p_ref).norm();
  BOOST_TEST_MESSAGE(label << ": N = 200  tip error " << e200 << " m, base wrench error "
                           << (k200.result.base_wrench - ref.base_wrench).norm() << ", "
                           << k200.nonlinear_iterations << " iterations, " << k200.jacobian_evaluations
                           << " Jacobians, max ||q| - 1| " << k200.max_quaternion_norm_error << ", "
                           << k200.result.wall_time_s * 1e3 << " ms");
  BOOST_TEST(e200 <= 1e-9);
  BOOST_TEST(!k200.used_continuation);
  BOOST_TEST(k200.max_quaternion_norm_error <= 1e-10);
}

}  // namespace

BOOST_AUTO_TEST_CASE(gravity_cantilever_cosserat_order_4_and_agrees_with_rk4) {
  cantilever_order_and_agreement(rod::ModelKind::cosserat, "cosserat");
}

BOOST_AUTO_TEST_CASE(gravity_cantilever_kirchhoff_order_4_and_agrees_with_rk4) {
  cantilever_order_and_agreement(rod::ModelKind::kirchhoff, "kirchhoff");
}

// A body-frame tip moment M about x bends the rod into a circular arc: Lambda = [M 0 0 0 0 0]
// everywhere, xi = [M / (E Ix), 0, 0, 0, 0, 1], g(s) = exp(s xi) (closed form).
BOOST_AUTO_TEST_CASE(pure_bending_is_a_circular_arc) {
  for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
    StaticProblem P(table21_rod(kind), SE3::identity());
    const double EI = P.model().K_diag()[0];
    const double kappa = 1.5 / kL;  // 1.5 rad over the rod
    loads::PointWrench tip;
    tip.wrench << kappa * EI, 0, 0, 0, 0, 0;
    tip.frame = loads::WrenchFrame::body;
    P.set_tip_wrench(tip);
    const auto k = kinsol(P, 100);
    BOOST_TEST(k.result.converged);
    check_structure(k);
    Vector6 xi;
    xi << kappa, 0, 0, 0, 0, 1;
    double position_error = 0, rotation_error = 0, wrench_error = 0;
    for (const auto& sample : k.result.centerline) {
      const SE3 exact = SE3::exp(sample.s * xi);
      position_error = std::max(position_error, (sample.pose.translation() - exact.translation()).norm());
      rotation_error = std::max(
          rotation_error, (exact.rotation().inverse() * sample.pose.rotation()).log().norm());
      wrench_error = std::max(wrench_error, (sample.twist - xi).norm());
    }
    BOOST_TEST_MESSAGE("pure bending: position error " << position_error << " m, rotation error "
                                                       << rotation_error << " rad, strain error "
                                                       << wrench_error << ", max ||q| - 1| "
                                                       << k.max_quaternion_norm_error);
    BOOST_TEST(position_error <= 1e-10);
    BOOST_TEST(rotation_error <= 1e-9);
    BOOST_TEST(wrench_error <= 1e-9 * kappa);
    BOOST_TEST(k.max_quaternion_norm_error <= 1e-10);  // |q| = 1 is a row, solved to tol
  }
}

// Both ends clamped, tip at [0.01, 0, 0.1] with the base's orientation, under gravity: an S-shape
// that the Cosserat rod reaches by stretching 0.5 % (the base wrench has an axial force).
BOOST_AUTO_TEST_CASE(both_ends_fixed_converges_and_agrees_with_rk4) {
  const StaticProblem P = both_ends_fixed(rod::ModelKind::cosserat);
  const auto ref = rk4_reference(P);
  const double wrench_size = ref.base_wrench.cwiseQuotient(P.wrench_scale()).norm();
  for (int N = 5; N <= 60; ++N) {
    const auto k = kinsol(P, N);
    BOOST_TEST(k.result.converged, "N = " << N << ": " << k.result.reason);
    BOOST_TEST(k.result.residual_norm <= 1e-10);
    check_structure(k);
    const Vector3 tip = tip_position(k.result);
    BOOST_TEST((tip - Vector3(0.01, 0.0, 0.1)).norm() <= 1e-12);
    BOOST_TEST(k.result.centerline.back().pose.rotation().log().norm() <= 1e-12);
    const double h = 1.0 / (N - 1);  // h / L
    const double wrench_error =
        (k.result.base_wrench - ref.base_wrench).cwiseQuotient(P.wrench_scale()).norm() / wrench_size;
    BOOST_TEST(wrench_error <= std::pow(h, 4), "N = " << N);
    // Where the nodes coincide with the reference's (N - 1 divides 1600), the whole centreline.
    double position_error = 0.0;
    if (1600 % (N - 1) == 0) {
      const int stride = 1600 / (N - 1);
      for (int i = 0; i < N; ++i)
        position_error = std::max(position_error, (k.result.centerline[i].pose.translation() -
                                                   ref.centerline[i * stride].pose.translation()).norm());
      BOOST_TEST(position_error <= 0.02 * kL * std::pow(h, 4), "N = " << N);
    }
    std::ostringstream centreline;
    if (1600 % (N - 1) == 0) centreline << ", centreline error " << position_error << " m";
    if (N == 5 || N == 17 || N == 33 || N == 41 || N == 60)
      BOOST_TEST_MESSAGE("both ends fixed: N = " << N << "  relative base wrench error " << wrench_error
                                                 << centreline.str() << ", "
                                                 << k.nonlinear_iterations << " iterations, "
                                                 << k.jacobian_evaluations << " Jacobians, "
                                                 << k.backtracks << " backtracks, " << k.strategy << ", "
                                                 << k.result.wall_time_s * 1e3 << " ms");
  }
}

// Clamped at the end of a constant-strain arc (kappa L = 1 about x) under gravity along -x, so
// the rod bends out of the arc's plane: no closed form, and rk4 shooting does not converge on the
// Kirchhoff rod. Checks: the collocation converges, falls at order 4 between N = 25, 50, 100
// (self-convergence), and rk4 shooting started from its base wrench lands on the target.
BOOST_AUTO_TEST_CASE(clamped_at_an_arc_end_under_gravity) {
  for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
    StaticProblem P = gravity_cantilever(kind);
    Vector6 xi;
    xi << 1.0 / kL, 0, 0, 0, 0, 1;
    const SE3 target = SE3::exp(kL * xi);
    P.set_tip_clamped(target);
    std::vector<Vector6> base;
    for (int N : {25, 50, 100, 200}) {
      const auto k = kinsol(P, N, 1e-12);
      BOOST_TEST(k.result.converged, k.result.reason);
      check_structure(k);
      base.push_back(k.result.base_wrench.cwiseQuotient(P.wrench_scale()));
      BOOST_TEST_MESSAGE((kind == rod::ModelKind::cosserat ? "cosserat" : "kirchhoff")
                         << " arc end + gravity: N = " << N << ", " << k.nonlinear_iterations
                         << " iterations (" << k.strategy << "), " << k.result.wall_time_s * 1e3 << " ms");
    }
    // Differences between successive N fall by 2^4.
    const double d1 = (base[1] - base[0]).norm(), d2 = (base[2] - base[1]).norm(), d3 = (base[3] - base[2]).norm();
    BOOST_TEST_MESSAGE("  base wrench differences " << d1 << ", " << d2 << ", " << d3);
    BOOST_TEST(std::log2(d1 / d2) >= 3.8);
    BOOST_TEST(std::log2(d2 / d3) >= 3.8);
    const auto shot = solvers::statics::shoot(P, RkmkMethod::rk4, 1601, base[3].cwiseProduct(P.wrench_scale()));
    BOOST_TEST(shot.ok);
    const double miss = (shot.tip.g.translation() - target.translation()).norm();
    const double turn = (target.rotation().inverse() * shot.tip.g.rotation()).log().norm();
    BOOST_TEST_MESSAGE("  rk4 shot from the N = 200 base wrench misses by " << miss << " m, " << turn << " rad");
    BOOST_TEST(miss <= 1e-9);
    BOOST_TEST(turn <= 1e-8);
  }
}

// An inextensible rod cannot reach a tip 0.1005 m from the base with L = 0.1 m: no solution.
// Non-convergence is a status with KINSOL's flag name, after the continuation was tried.
BOOST_AUTO_TEST_CASE(unreachable_clamped_tip_is_reported_not_thrown) {
  const StaticProblem P = both_ends_fixed(rod::ModelKind::kirchhoff);
  const auto k = kinsol(P, 5);
  BOOST_TEST(!k.result.converged);
  BOOST_TEST(k.used_continuation);
  BOOST_TEST(k.result.reason.rfind("KIN_", 0) == 0, k.result.reason);
  BOOST_TEST(k.result.residual_norm > 1e-10);
  BOOST_TEST_MESSAGE("unreachable tip: " << k.result.reason);
}

// Large dead tip loads (world frame, F L^2 / (E I) = 10 and 41) with gravity. From the straight
// rod the direct Newton iteration needs backtracking and, for 0.5 N, converges to a coiled
// (unstable) equilibrium; the solver then follows the load path by continuation and finds the
// equilibrium the rk4 shooting finds (and a continuation in steps of 0.01 finds).
BOOST_AUTO_TEST_CASE(large_dead_tip_loads_follow_the_load_path) {
  for (const double force : {0.5, 2.0}) {
    StaticProblem P = gravity_cantilever(rod::ModelKind::cosserat);
    loads::PointWrench tip;
    tip.wrench << 0, 0, 0, -force, 0, 0;
    tip.frame = loads::WrenchFrame::world;
    P.set_tip_wrench(tip);
    const auto ref = rk4_reference(P);
    const auto k = kinsol(P, 100);
    BOOST_TEST(k.result.converged, k.result.reason);
    BOOST_TEST(k.strategy == "continuation");
    BOOST_TEST(k.kinsol_solves > 1);
    check_structure(k);
    const double error = (tip_position(k.result) - tip_position(ref)).norm();
    BOOST_TEST_MESSAGE("dead tip load " << force << " N: tip " << tip_position(k.result).transpose()
                                        << ", error against rk4 " << error << " m, " << k.kinsol_solves
                                        << " KINSOL solves, " << k.nonlinear_iterations << " iterations, "
                                        << k.jacobian_evaluations << " Jacobians, "
                                        << k.result.wall_time_s * 1e3 << " ms");
    BOOST_TEST(error <= 1e-8);
  }
}

// A soft cantilever at a tolerance near the rows' rounding level: E = 2500 Pa (G = 0.33 E, the
// Table 2.1 geometry) under gravity, rho g A L^3 / E I = 628, N = 100, tol 1e-12. The direct solve
// fails and the load continuation used to stall at load factor 0.30: its correctors, held to
// 1e-12, stopped at residuals of 1.1-2.4e-12 with line-search cuts in the rounding noise, which
// the walk takes for leaving the branch. A failed walk is now walked again with its correctors
// to 1e-9, and the solution polished at the full load (kinsol_collocation.cpp). Reference:
// rkmk-rk4 at N = 1601 (measured: 1.5e-7 m, kinsol's own error at N = 100, which is fourth
// order).
BOOST_AUTO_TEST_CASE(soft_cantilever_at_a_tight_tolerance) {
  StaticProblem P(rod::RodModel(kL, rod::Circle{0.01}, rod::Material{2500.0, 825.0, 1000.0, 0.0},
                                rod::ModelKind::cosserat),
                  SE3::identity());
  P.set_gravity(loads::Gravity(P.model(), Vector3(-9.81, 0.0, 0.0)));
  const auto k = kinsol(P, 100, 1e-12);
  BOOST_TEST_REQUIRE(k.result.converged, k.result.reason);
  BOOST_TEST(k.strategy == "continuation");
  check_structure(k);
  const double error = (tip_position(k.result) - tip_position(rk4_reference(P))).norm();
  BOOST_TEST_MESSAGE("soft cantilever: tip " << tip_position(k.result).transpose() << ", residual "
                                             << k.result.residual_norm << ", error against rk4 "
                                             << error << " m, " << k.nonlinear_iterations
                                             << " iterations");
  BOOST_TEST(k.result.residual_norm <= 1e-10);  // at the rounding floor, not the tolerance
  BOOST_TEST(error <= 5e-6);
}

// The solver kept on a thread between solves of the same pattern (kinsol_collocation.cpp,
// ThreadSolver: its SUNDIALS objects and KLU's analysis) does not carry one solve's pivots into
// the next: the gravity cantilever at N = 100 after a solve of another size and a continuation
// solve of the same pattern (the 2 N dead tip load) comes out bit for bit as in a fresh thread.
BOOST_AUTO_TEST_CASE(repeated_solves_do_not_depend_on_the_ones_before) {
  const StaticProblem P = gravity_cantilever(rod::ModelKind::cosserat);
  auto tip_of = [&P](int nodes) {
    const auto k = kinsol(P, nodes);
    BOOST_TEST_REQUIRE(k.result.converged);
    return tip_position(k.result);
  };
  Vector3 fresh;
  std::thread([&] { fresh = tip_of(100); }).join();
  tip_of(50);
  StaticProblem loaded = P;
  loads::PointWrench tip;
  tip.wrench << 0, 0, 0, -2.0, 0, 0;
  tip.frame = loads::WrenchFrame::world;
  loaded.set_tip_wrench(tip);
  BOOST_TEST_REQUIRE(kinsol(loaded, 100).result.converged);
  const Vector3 again = tip_of(100);
  BOOST_TEST((again - fresh).norm() == 0.0, "after other solves: " << again.transpose()
                                                << ", in a fresh thread: " << fresh.transpose());
}

BOOST_AUTO_TEST_CASE(dispatch_through_solve_static) {
  const StaticProblem P = gravity_cantilever(rod::ModelKind::cosserat);
  solvers::statics::StaticSolveOptions options;
  options.scheme = "kinsol";
  options.nodes = 30;
  const auto r = solvers::statics::solve_static(P, options);
  BOOST_TEST(r.converged);
  BOOST_TEST(r.scheme == "kinsol");
  BOOST_TEST(r.nodes == 30);
  BOOST_TEST(r.iterations >= 1);
  BOOST_TEST(r.residual_norm <= 1e-10);
  BOOST_TEST(r.reason.empty());
}

BOOST_AUTO_TEST_CASE(bad_options_throw) {
  const StaticProblem P = gravity_cantilever(rod::ModelKind::cosserat);
  KinsolCollocationOptions options;
  options.nodes = 1;
  BOOST_CHECK_THROW(solvers::statics::solve_kinsol_collocation(P, options), std::invalid_argument);
  options.nodes = 10;
  options.tol = 0.0;
  BOOST_CHECK_THROW(solvers::statics::solve_kinsol_collocation(P, options), std::invalid_argument);
}
