#define BOOST_TEST_MODULE chebyshev
#include <boost/test/unit_test.hpp>

// The `chebyshev` statics scheme (solvers/include/rodlab/solvers/statics/chebyshev.hpp): thesis
// 2.6.2 and the test cases of 2.7 with the rod of Table 2.1 (E = 1 MPa, G = 0.33 MPa,
// rho = 1000 kg/m^3, circle D = 1 cm, L = 10 cm).
//
// References:
//  - the gravity cantilever (2.7.1, (2.110)-(2.112)) and the rod with both ends fixed (2.7.2,
//    (2.113)-(2.115), tip at [0.01, 0, 0.1]) against rkmk-rk4 shooting on a fine grid (1601 and
//    400 nodes; RK4's error there is below 1e-12 m), comparing whole centrelines by spectral
//    interpolation of theta = log(g_0^-1 g) to the RK4 nodes;
//  - pure bending by a tip moment against the circular arc of curvature M / EI in closed form
//    (constant Lambda = [M 0 0 0 0 0], so theta(s) = s xi is linear and the collocation exact);
//  - the full circle M L / EI = 2 pi, which one chart cannot hold (dexp^-1 has its pole at
//    |omega| = 2 pi): the scheme must split into elements by itself.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "rodlab/solvers/common/chebyshev_operators.hpp"
#include "rodlab/solvers/statics/chebyshev.hpp"
#include "rodlab/solvers/statics/shooting.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::solvers::statics;
using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;
using std::numbers::pi;

constexpr double kL = 0.1;
const rod::Material kTable21{1e6, 0.33e6, 1000.0, 0.0};

rod::RodModel table21(rod::ModelKind kind) { return {kL, rod::Circle{0.01}, kTable21, kind}; }
double EI() { return table21(rod::ModelKind::cosserat).K_diag()[0]; }

StaticProblem cantilever(rod::ModelKind kind) {
  StaticProblem P(table21(kind), SE3());
  P.set_gravity(loads::Gravity(P.model(), Vector3(-9.81, 0.0, 0.0)));
  return P;
}

StaticProblem tip_moment(double bending_angle) {  // M L / EI = bending_angle, about body x
  StaticProblem P(table21(rod::ModelKind::cosserat), SE3());
  loads::PointWrench w;
  w.wrench << bending_angle * EI() / kL, 0, 0, 0, 0, 0;
  w.frame = loads::WrenchFrame::body;
  P.set_tip_wrench(w);
  return P;
}

StaticProblem both_ends_fixed() {
  StaticProblem P(table21(rod::ModelKind::cosserat), SE3());
  P.set_tip_clamped(SE3::translation(Vector3(0.01, 0.0, 0.1)));
  return P;
}

result::StaticResult chebyshev(const StaticProblem& P, int nodes, ChebyshevReport* report = nullptr,
                               double tol = 1e-12) {
  ChebyshevOptions o;
  o.nodes = nodes;
  o.tol = tol;
  return solve_chebyshev(P, o, report);
}

result::StaticResult rk4(const StaticProblem& P, int nodes) {
  return solve_shooting(P, RkmkMethod::rk4, {nodes, 1e-12, 50, {}});
}

/// Largest centreline distance between a one-element Chebyshev solution, interpolated
/// spectrally (theta = log(g_0^-1 g) at the nodes, barycentric to the reference's s), and a
/// reference.
double centreline_distance(const result::StaticResult& cheb, const result::StaticResult& ref) {
  const int n = cheb.nodes;
  const SE3 g0 = cheb.centerline.front().pose;
  Eigen::MatrixXd theta(n, 6);
  for (int j = 0; j < n; ++j) theta.row(j) = (g0.inverse() * cheb.centerline[j].pose).log().transpose();
  Eigen::VectorXd t(ref.nodes);
  for (int k = 0; k < ref.nodes; ++k) t[k] = 2.0 * ref.centerline[k].s / kL - 1.0;
  const Eigen::MatrixXd C = solvers::chebyshev_interpolation_matrix(n, t);
  const Eigen::MatrixXd at = C * theta;
  double d = 0.0;
  for (int k = 0; k < ref.nodes; ++k) {
    const SE3 g = g0 * SE3::exp(at.row(k).transpose());
    d = std::max(d, (g.translation() - ref.centerline[k].pose.translation()).norm());
  }
  return d;
}

void check_structure(const result::StaticResult& r) {
  BOOST_TEST(r.max_det_deviation <= 1e-13);
  BOOST_TEST(r.max_orthogonality_error <= 1e-13);
}

}  // namespace

// 2.7.1: tip position error against rkmk-rk4 at 1601 nodes for N = 6..30; spectral decay to
// <= 1e-9 m by N = 24, for Cosserat and Kirchhoff rods.
BOOST_AUTO_TEST_CASE(gravity_cantilever_converges_spectrally) {
  for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
    const auto P = cantilever(kind);
    const auto ref = rk4(P, 1601);
    BOOST_TEST_REQUIRE(ref.converged);
    const Vector3 p_ref = ref.centerline.back().pose.translation();
    std::printf("gravity cantilever, %s: rk4 tip [%.12g %.12g %.12g] m\n",
                kind == rod::ModelKind::cosserat ? "cosserat" : "kirchhoff", p_ref.x(), p_ref.y(), p_ref.z());
    std::printf("   N   tip error [m]   centreline [m]  iterations  LU\n");
    std::vector<double> err(31, 0.0);
    for (int N = 6; N <= 30; ++N) {
      ChebyshevReport rep;
      const auto r = chebyshev(P, N, &rep);
      BOOST_TEST_CONTEXT("N = " << N) {
        BOOST_TEST_REQUIRE(r.converged);
        BOOST_TEST(rep.elements == 1);
        BOOST_TEST(r.nodes == N);
        check_structure(r);
      }
      err[N] = (r.centerline.back().pose.translation() - p_ref).norm();
      std::printf("  %2d   %.3e       %.3e       %2d       %d\n", N, err[N], centreline_distance(r, ref),
                  r.iterations, rep.factorizations);
    }
    // Spectral: each 6 more nodes gain well over an order of magnitude until rounding level.
    BOOST_TEST(err[12] < 1e-2 * err[6]);
    BOOST_TEST(err[18] < 1e-2 * err[12]);
    for (int N = 24; N <= 30; ++N) BOOST_TEST(err[N] <= 1e-9);
  }
}

// Pure bending: the exact solution is the arc p(s) = [0, (cos(k s) - 1)/k, sin(k s)/k],
// R(s) = Rx(k s), k = M / EI, Lambda = [M 0 0 0 0 0] everywhere.
BOOST_AUTO_TEST_CASE(pure_bending_matches_circular_arc) {
  const double angle = pi / 2.0, kappa = angle / kL;
  ChebyshevReport rep;
  const auto r = chebyshev(tip_moment(angle), 10, &rep);
  BOOST_TEST_REQUIRE(r.converged);
  BOOST_TEST(rep.elements == 1);
  double dp = 0.0, dR = 0.0, dL = 0.0;
  for (const auto& c : r.centerline) {
    const Vector3 p(0.0, (std::cos(kappa * c.s) - 1.0) / kappa, std::sin(kappa * c.s) / kappa);
    dp = std::max(dp, (c.pose.translation() - p).norm());
    dR = std::max(dR, (c.pose.rotation_matrix() - SO3::exp(Vector3(kappa * c.s, 0, 0)).matrix()).norm());
    Vector6 xi;
    xi << kappa, 0, 0, 0, 0, 1;
    dL = std::max(dL, (c.twist - xi).norm() * kL);
  }
  std::printf("pure bending N = 10: position %.2e m, rotation %.2e, strain %.2e, %d iterations\n", dp, dR, dL,
              r.iterations);
  BOOST_TEST(dp <= 1e-12);
  BOOST_TEST(dR <= 1e-12);
  BOOST_TEST(dL <= 1e-12);
  check_structure(r);
}

// M L / EI = 2 pi: the rod closes into a circle, the tip back at the base with R = I. No hand-made
// guess: the scheme starts from the straight rod and splits into elements by itself (4 elements
// of >= 5 nodes from N = 17; 2 elements of 3-4 nodes, pi per chart, for N = 5..8).
BOOST_AUTO_TEST_CASE(full_circle_converges) {
  for (int N : {5, 6, 8, 9, 17, 24, 40}) {
    ChebyshevReport rep;
    const auto r = chebyshev(tip_moment(2.0 * pi), N, &rep);
    BOOST_TEST_CONTEXT("N = " << N) {
      BOOST_TEST_REQUIRE(r.converged);
      const auto& tip = r.centerline.back().pose;
      std::printf("full circle N = %d: %d elements, tip |p| = %.2e m, |R - I| = %.2e, %d iterations, %d LU\n", N,
                  rep.elements, tip.translation().norm(),
                  (tip.rotation_matrix() - Eigen::Matrix3d::Identity()).norm(), r.iterations, rep.factorizations);
      BOOST_TEST(rep.elements == (N >= 17 ? 4 : 2));
      BOOST_TEST(r.nodes == N);
      BOOST_TEST(tip.translation().norm() <= 1e-12);
      BOOST_TEST((tip.rotation_matrix() - Eigen::Matrix3d::Identity()).norm() <= 1e-12);
      const double radius = kL / (2.0 * pi);
      for (const auto& c : r.centerline)
        BOOST_TEST(std::abs((c.pose.translation() - Vector3(0, -radius, 0)).norm() - radius) <= 1e-12);
      check_structure(r);
    }
  }
}

// 2.7.2: both ends fixed, tip at [0.01, 0, 0.1] with R = I, no loads. Converges for every N in
// 5..60 and agrees with rkmk-rk4 at 400 nodes to 1e-8 m along the whole centreline from N = 20.
BOOST_AUTO_TEST_CASE(both_ends_fixed_converges_and_agrees) {
  const auto P = both_ends_fixed();
  const auto ref = rk4(P, 400);
  BOOST_TEST_REQUIRE(ref.converged);
  std::printf("both ends fixed:\n   N   centreline [m]  base wrench (scaled)  iterations\n");
  for (int N = 5; N <= 60; ++N) {
    ChebyshevReport rep;
    const auto r = chebyshev(P, N, &rep);
    BOOST_TEST_CONTEXT("N = " << N) {
      BOOST_TEST_REQUIRE(r.converged);
      BOOST_TEST(rep.elements == 1);
      check_structure(r);
      const double d = centreline_distance(r, ref);
      const double dw = (r.base_wrench - ref.base_wrench).cwiseQuotient(P.wrench_scale()).lpNorm<Eigen::Infinity>();
      if (N <= 30 || N % 10 == 0) std::printf("  %2d   %.3e       %.3e            %d\n", N, d, dw, r.iterations);
      if (N >= 20) BOOST_TEST(d <= 1e-8);
      const auto& tip = r.centerline.back().pose;
      BOOST_TEST((tip.translation() - Vector3(0.01, 0, 0.1)).norm() <= 1e-12);
    }
  }
}

// Both ends clamped at the end of a circular arc of angle kappa L (the constant twist L xi,
// xi = [kappa 0 0 0 0 1], is the exact solution, Lambda = [EI kappa 0 0 0 0 0]), Cosserat and
// Kirchhoff. The Kirchhoff rod's Newton matrix is singular at the straight start (its axial force
// is undetermined to first order), which the least-squares steps must get past.
BOOST_AUTO_TEST_CASE(clamped_at_the_end_of_an_arc) {
  for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
    for (double angle : {0.3, 1.0, 3.0}) {
      const double kappa = angle / kL;
      StaticProblem P(table21(kind), SE3());
      P.set_tip_clamped(SE3(SO3::exp(Vector3(angle, 0, 0)), Vector3(0, (std::cos(angle) - 1) / kappa,
                                                                    std::sin(angle) / kappa)));
      for (int N : {5, 12, 24}) {
        ChebyshevReport rep;
        const auto r = chebyshev(P, N, &rep);
        BOOST_TEST_CONTEXT((kind == rod::ModelKind::cosserat ? "cosserat" : "kirchhoff")
                           << " kappa L = " << angle << ", N = " << N) {
          BOOST_TEST_REQUIRE(r.converged);
          BOOST_TEST(std::abs(r.base_wrench[0] - EI() * kappa) <= 1e-10 * EI() * kappa);
          double dp = 0.0;
          for (const auto& c : r.centerline) {
            const Vector3 p(0.0, (std::cos(kappa * c.s) - 1.0) / kappa, std::sin(kappa * c.s) / kappa);
            dp = std::max(dp, (c.pose.translation() - p).norm());
          }
          BOOST_TEST(dp <= 1e-12);
          check_structure(r);
        }
      }
    }
  }
}

// A Kirchhoff rod cannot reach [0.1 L, 0, L] (farther than L from the base). At some N the
// collocation equations have spurious roots there (huge axial forces, wild polynomials between
// the nodes); they must be reported as not converged.
BOOST_AUTO_TEST_CASE(unreachable_kirchhoff_target_is_not_a_solution) {
  StaticProblem P(table21(rod::ModelKind::kirchhoff), SE3());
  P.set_tip_clamped(SE3::translation(Vector3(0.01, 0.0, 0.1)));
  for (int N : {5, 11, 21}) {
    const auto r = chebyshev(P, N);
    BOOST_TEST_CONTEXT("N = " << N) {
      BOOST_TEST(!r.converged);
      BOOST_TEST(!r.reason.empty());
    }
  }
}

// Large N: the residual's rounding level grows like N^2, beyond a tight tol; the solve must stop
// there as converged rather than fail.
BOOST_AUTO_TEST_CASE(large_n_converges_at_rounding_level) {
  const auto r = chebyshev(both_ends_fixed(), 100, nullptr, 1e-14);
  BOOST_TEST(r.converged);
  BOOST_TEST(r.residual_norm <= 1e-10);
}

// Through the common entry point, with timing of N = 24 (printed, not checked).
BOOST_AUTO_TEST_CASE(solve_static_dispatch_and_timing) {
  const auto P = cantilever(rod::ModelKind::cosserat);
  StaticSolveOptions o;
  o.scheme = "chebyshev";
  o.nodes = 24;
  const auto r = solve_static(P, o);
  BOOST_TEST(r.converged);
  BOOST_TEST(r.scheme == "chebyshev");
  BOOST_TEST(r.nodes == 24);
  BOOST_TEST(r.wall_time_s > 0.0);
  const int reps = 50;
  const auto start = std::chrono::steady_clock::now();
  int iterations = 0;
  for (int k = 0; k < reps; ++k) iterations += solve_static(P, o).iterations;
  const double ms = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * 1e3 / reps;
  std::printf("gravity cantilever N = 24: %.3f ms per solve, %d iterations\n", ms, iterations / reps);
}

BOOST_AUTO_TEST_CASE(bad_arguments) {
  ChebyshevOptions o;
  o.nodes = 1;
  BOOST_CHECK_THROW(solve_chebyshev(cantilever(rod::ModelKind::cosserat), o), std::invalid_argument);
  o.nodes = 5;
  o.elements = 5;
  BOOST_CHECK_THROW(solve_chebyshev(cantilever(rod::ModelKind::cosserat), o), std::invalid_argument);
}
