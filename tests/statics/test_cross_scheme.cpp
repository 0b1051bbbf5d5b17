#define BOOST_TEST_MODULE statics_cross_scheme
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>

#include "fixed_ends_support.hpp"

// Case 10: every scheme at N = 100 agrees with rkmk-rk4 at N = 400 within its own error
// estimate C (h/L)^p, h/L = 1/99, p the design order, C = 2 (stated once for both problems):
//   - gravity cantilever (thesis 2.7.1, Table 2.1, gravity [-9.81, 0, 0]), Cosserat and
//     Kirchhoff: tip error max(|dp|/L, rotation distance). Measured constants err / (h/L)^p at
//     N = 100: euler-explicit 0.75, euler-implicit 0.74, midpoint-explicit 0.26,
//     midpoint-implicit 0.13, rk4 1.5e-3.
//   - fixed ends (2.7.2), Cosserat: dimensionless base-wrench difference (fixed_ends_support.hpp).
//     Measured: 0.042, 0.049, 0.88, 0.54, 1.05.
// The reference's own error (rk4, N = 400) is ~6e-14 (cantilever) and ~4e-11 (fixed ends) by the
// same constants, so the floor of the bound is 1e-10 (spectral schemes: the floor only).

namespace {

using namespace rodlab;
using namespace rodlab::testing::statics;
using rod::ModelKind;

constexpr int kN = 100, kNref = 400;
constexpr double kC = 2.0, kFloor = 1e-10;

}  // namespace

BOOST_AUTO_TEST_CASE(gravity_cantilever_n100_against_rk4_n400) {
  for (const ModelKind kind : {ModelKind::cosserat, ModelKind::kirchhoff}) {
    const auto problem = gravity_cantilever(kind);
    const auto ref = solve(problem, "rkmk-rk4", kNref);
    BOOST_TEST_REQUIRE(check_result(ref, kNref));
    for (const auto& s : statics_schemes_under_test()) {
      const auto r = solve(problem, s.name, kN);
      if (!check_result(r, kN)) continue;
      const double e = tip_error(r, ref), bound = agreement_bound(s, kN, kC, kFloor);
      BOOST_TEST(e <= bound, kind_name(kind) << " " << describe(r) << ": tip differs from rk4 N=400 by " << e
                                             << " > C h^p = " << bound);
      BOOST_TEST_MESSAGE(kind_name(kind) << " gravity cantilever " << describe(r) << ": tip error " << e
                                         << ", C h^p = " << bound << ", e/(h/L)^p = "
                                         << (s.spectral ? 0.0 : e / std::pow(1.0 / (kN - 1), s.design_order)));
    }
  }
}

BOOST_AUTO_TEST_CASE(fixed_ends_n100_against_rk4_n400) {
  const auto problem = fixed_ends(ModelKind::cosserat);
  const auto ref = solve(problem, "rkmk-rk4", kNref);
  BOOST_TEST_REQUIRE(check_result(ref, kNref));
  for (const auto& s : statics_schemes_under_test()) {
    const auto r = solve(problem, s.name, kN);
    if (!check_result(r, kN)) continue;
    const double e = base_wrench_error(problem, r, ref), bound = agreement_bound(s, kN, kC, kFloor);
    BOOST_TEST(e <= bound, describe(r) << ": base wrench differs from rk4 N=400 by " << e << " > C h^p = " << bound);
    BOOST_TEST_MESSAGE("fixed ends " << describe(r) << ": base wrench error " << e << ", C h^p = " << bound
                                     << ", e/(h/L)^p = "
                                     << (s.spectral ? 0.0 : e / std::pow(1.0 / (kN - 1), s.design_order)));
  }
  // The whole centreline, on shared nodes: node i of N = 100 is at s = i L/99, node 4 i of
  // rk4 at N = 397 = 4 * 99 + 1. Same bound.
  const auto fine = solve(problem, "rkmk-rk4", 397);
  BOOST_TEST_REQUIRE(check_result(fine, 397));
  for (const auto& s : statics_schemes_under_test()) {
    const auto r = solve(problem, s.name, kN);
    if (!r.converged || static_cast<int>(r.centerline.size()) != kN) continue;
    bool uniform = true;  // Chebyshev-Lobatto nodes are not: skip those schemes here
    for (int i = 0; i < kN; ++i) uniform = uniform && std::abs(r.centerline[i].s - fine.centerline[4 * i].s) <= 1e-15;
    if (!uniform) continue;
    double worst = 0.0;
    for (int i = 0; i < kN; ++i)
      worst = std::max(worst, pose_error(r.centerline[i].pose, fine.centerline[4 * i].pose).max());
    const double bound = agreement_bound(s, kN, kC, kFloor);
    BOOST_TEST(worst <= bound, describe(r) << ": centreline differs from rk4 N=397 by " << worst);
    BOOST_TEST_MESSAGE("fixed ends " << describe(r) << ": worst node pose difference " << worst);
  }
}
