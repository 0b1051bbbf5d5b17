#define BOOST_TEST_MODULE statics_robustness
#include <boost/test/unit_test.hpp>
// rodlab-test-labels: validation

#include <cmath>
#include <string>
#include <vector>

#include "schemes_under_test.hpp"
#include "statics_support.hpp"

// Validation (slow: continuation runs of thousands of Newton iterations): problems with exact
// solutions that the shooting solvers must reach from their own start, with large loads.
//
// 1. Clamped at the end of a pure-bending arc with kappa L = 3 (see clamped_at_the_arc_end in
//    test_fixed_ends.cpp for kappa L <= 1): Lambda(0) = [EI kappa; 0], g(s) = exp(s xi) with
//    xi = [kappa, 0, 0, 0, 0, 1], exact for every scheme.
// 2. Constant-twist loads (2.68)-(2.69) with large shear and extension: xi = [3, -2, 5, 0.04,
//    -0.03, 1.02] /m (scaled tip force [21, -16, 32] EI/L^2) and [8, -5, 12, -0.02, 0.05, 0.95];
//    g(s) = exp(s xi), exact for every scheme (test_constant_strain.cpp has the small-shear ones).
//    Newton tolerance 1e-12 on the scaled residual (the loads are ~30 EI/L^2, so a tighter one
//    is below rounding), node poses to 1e-9.
//
// Every (scheme, N) solves both (docs/statics-validation.md): the large-shear load only through
// the shooting schemes' last resort, multiple shooting, for rkmk-euler-explicit at N = 5 and 11,
// rkmk-euler-implicit at N = 5, 11 and 200 and rkmk-midpoint-implicit at N = 5 (single shooting
// and its continuation stall there). The messages list every outcome.

namespace {

using namespace rodlab;
using namespace rodlab::testing::statics;
using rod::ModelKind;
using loads::WrenchFrame;

}  // namespace

BOOST_AUTO_TEST_CASE(clamped_at_arc_end_kappa_l_3) {
  const double L = Table21::L, kappa = 3.0 / L;
  for (const ModelKind kind : {ModelKind::cosserat, ModelKind::kirchhoff}) {
    StaticProblem problem = table21_problem(kind);
    problem.set_tip_clamped(bent_arc_pose(kappa, L));
    const Vector6 expected = (Vector6() << Table21::EI * kappa, 0, 0, 0, 0, 0).finished();
    const Vector6 scale = problem.wrench_scale();
    for (const auto& s : statics_schemes_under_test()) {
      for (const int N : grid_for(s, {5, 21, 100})) {
        const auto r = solve(problem, s.name, N);
        BOOST_TEST_MESSAGE("clamped arc kappa L = 3 " << kind_name(kind) << " " << describe(r) << ", base wrench "
                                                      << r.base_wrench.transpose());
        if (!check_result(r, N)) continue;
        const double ew = (r.base_wrench - expected).cwiseQuotient(scale).norm() / expected.cwiseQuotient(scale).norm();
        double ep = 0.0;
        for (const auto& c : r.centerline) ep = std::max(ep, pose_error(c.pose, bent_arc_pose(kappa, c.s)).max());
        BOOST_TEST(ew <= 1e-9, kind_name(kind) << " " << describe(r) << ": base wrench error " << ew);
        BOOST_TEST(ep <= 1e-10, kind_name(kind) << " " << describe(r) << ": node pose error " << ep);
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(constant_twist_large_shear) {
  for (const Vector6& xi : {(Vector6() << 3.0, -2.0, 5.0, 0.04, -0.03, 1.02).finished(),
                            (Vector6() << 8.0, -5.0, 12.0, -0.02, 0.05, 0.95).finished()}) {
    const Vector6 Lambda = constant_twist_wrench(xi);
    const StaticProblem problem = constant_twist_problem(ModelKind::cosserat, xi, Lambda);
    for (const auto& s : statics_schemes_under_test()) {
      for (const int N : grid_for(s, {5, 11, 21, 100, 200})) {
        const auto r = solve(problem, s.name, N);  // default tolerance 1e-12: these loads are ~30 EI/L^2
        BOOST_TEST_MESSAGE("constant twist xi = " << xi.transpose() << " " << describe(r));
        if (!check_result(r, N)) continue;
        double e = 0.0;
        for (const auto& node : r.centerline) e = std::max(e, pose_error(node.pose, expm_reference(node.s * xi)).max());
        BOOST_TEST(e <= 1e-9, describe(r) << ": node error " << e);
        BOOST_TEST((r.base_wrench - Lambda).norm() <= 1e-9 * Lambda.norm());
      }
    }
  }
}
