#define BOOST_TEST_MODULE statics_convergence_order
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "schemes_under_test.hpp"
#include "statics_support.hpp"

// Case 6: observed order of every scheme on the thesis's gravity cantilever (2.7.1): Table 2.1
// rod along +z, clamped at the origin, gravity [-9.81, 0, 0] (q L^3/EI = 1.57, a tip deflection
// of 0.19 L), Cosserat and Kirchhoff. Tip error max(|dp|/L, rotation distance) against rkmk-rk4
// at N = 1601 (its own error is ~1e-16 by its measured constant, below the Newton tolerance), for
// N in {11, 21, 41, 81} (order >= 4 and spectral schemes: {6, 11, 21, 41}, so that the error stays
// above rounding). The order is the least-squares slope of log(err) against log(h); it must be
// within 0.15 of the design order (1, 1, 2, 2, 4).
//
// Measured (see the table this test prints), for euler-explicit, euler-implicit,
// midpoint-explicit, midpoint-implicit, rk4: Cosserat 1.02, 0.975, 2.00, 2.00, 4.04 and
// Kirchhoff 1.02, 0.975, 2.00, 2.00, 4.04 (rk4 errors 2.6e-6 at N = 6 to 5.8e-10 at N = 41).

namespace {

using namespace rodlab;
using namespace rodlab::testing::statics;
using rod::ModelKind;

std::vector<int> order_grid(const SchemeUnderTest& s) {
  if (s.spectral || s.design_order >= 4) return {6, 11, 21, 41};
  return {11, 21, 41, 81};
}

void order_table(ModelKind kind) {
  const auto problem = gravity_cantilever(kind);
  const auto reference = solve(problem, "rkmk-rk4", 1601);
  BOOST_TEST_REQUIRE(check_result(reference, 1601));
  const Vector3 p_ref = reference.centerline.back().pose.translation();
  BOOST_TEST_MESSAGE(kind_name(kind) << " gravity cantilever, reference " << describe(reference) << ": tip "
                                     << p_ref.transpose() / Table21::L << " L");
  BOOST_TEST_MESSAGE("scheme                   design  N: tip error (iterations)                                   observed");
  for (const auto& s : statics_schemes_under_test()) {
    std::vector<double> h, err;
    std::ostringstream row;
    row << std::left << std::setw(24) << s.name << " " << std::setw(7) << s.order;
    for (const int N : order_grid(s)) {
      const auto r = solve(problem, s.name, N);
      if (!check_result(r, N)) continue;
      h.push_back(Table21::L / (N - 1));
      err.push_back(tip_error(r, reference));
      row << " " << N << ": " << std::setprecision(3) << err.back() << " (" << r.iterations << ")";
    }
    if (h.size() < 2) continue;
    const double p = check_observed_order(s, h, err, 1e-12, std::string(kind_name(kind)) + " gravity cantilever");
    row << "  p = " << std::setprecision(3) << p;
    BOOST_TEST_MESSAGE(row.str());
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(gravity_cantilever_order_cosserat) { order_table(ModelKind::cosserat); }

BOOST_AUTO_TEST_CASE(gravity_cantilever_order_kirchhoff) { order_table(ModelKind::kirchhoff); }

// The least-squares fit itself, on exact power laws (a test of the test).
BOOST_AUTO_TEST_CASE(fitted_order_is_exact_on_power_laws) {
  for (const double p : {1.0, 2.0, 4.0}) {
    std::vector<double> h{0.1, 0.05, 0.025, 0.0125}, e;
    for (const double x : h) e.push_back(3.0 * std::pow(x, p));
    BOOST_TEST(std::abs(fitted_order(h, e) - p) <= 1e-12);
  }
}
