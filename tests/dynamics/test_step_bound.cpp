#define BOOST_TEST_MODULE dynamics_step_bound
#include <boost/test/unit_test.hpp>

// Single shooting's lower step bound (solvers/dynamics/shooting/step_bound.hpp, #13 item 3):
// (a) the exponent kappa against its closed form on the Table 2.1 rod (bending dominates);
// (b) on the staggered grid a run beyond the bound runs by multiple shooting (test_multiple_
//     shooting.cpp checks its solutions); on the Euler grid it is refused before it starts
//     (std::invalid_argument, exit 2 on the command line), naming the step it needs and the
//     schemes to use; the Euler grid, whose bound is wider, runs a step the staggered grid's
//     single shooting could not;
// (c) a run 15 % above the smallest admitted step runs to its end (the bound is not
//     conservative where single shooting works).
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "dynamics_support.hpp"
#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::ShootingGrid;

}  // namespace

BOOST_AUTO_TEST_CASE(exponent_matches_its_closed_form) {
  // Table 2.1 rod, viscosity 300 Pa s: bending with Kt = E I + c 3 alpha I dominates at dt = 1 ms
  const auto P = DynamicProblem::from_scene(cantilever(300.0));
  const double D = 0.01, L = 0.1, E = 1e6, rho = 1000, alpha = 300;
  const double I = std::numbers::pi * std::pow(D, 4) / 64, A = std::numbers::pi * D * D / 4;
  for (const double dt : {1e-3, 1e-2}) {
    const double c = 2.0 / dt;
    const double expected = L * std::pow(rho * A * c * c / (E * I + c * 3 * alpha * I), 0.25);
    BOOST_TEST(solvers::dynamics::single_shooting_exponent(P, dt) == expected,
               boost::test_tools::tolerance(1e-12));
  }
  BOOST_TEST(solvers::dynamics::single_shooting_exponent_bound(ShootingGrid::staggered, 1e-10) ==
                 std::log(1e-10 / 2.220446049250313e-16) - 0.8,
             boost::test_tools::tolerance(1e-12));
}

/// The message of a run refused before it starts; fails the test if it was not refused.
std::string refusal(const scene::Scene& s, const solvers::dynamics::DynamicSolveOptions& o) {
  try {
    solvers::dynamics::solve_dynamic(s, o);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  BOOST_ERROR("dt = " << o.dt << " s was not refused");
  return {};
}

BOOST_AUTO_TEST_CASE(beyond_the_bound_is_refused_up_front_on_the_euler_grid) {
  const auto s = cantilever(300.0);
  // dt = 1 ms: kappa 12.3, beyond the staggered grid's 12.2, within the Euler grid's 15.5
  auto o = options("implicit-midpoint", 20, 1e-3, 0.02, scene::Initial::straight);
  o.grid = ShootingGrid::staggered;  // multiple shooting (two intervals)
  auto r = solvers::dynamics::solve_dynamic(s, o);
  BOOST_TEST(r.converged, r.reason);
  o.grid = ShootingGrid::euler;  // its bound is wider: single shooting converges
  r = solvers::dynamics::solve_dynamic(s, o);
  BOOST_TEST(r.converged, r.reason);
  // dt = 0.4 ms: kappa 16.4, beyond the Euler grid's bound too: refused there
  o.dt = 4e-4;
  std::string why = refusal(s, o);
  for (const char* part : {"lower step bound", "implicit-midpoint-collocation", "ida", "dt >="})
    BOOST_TEST(why.find(part) != std::string::npos, why);
  // the staggered grid at 0.4 ms runs (three intervals)
  o.grid = ShootingGrid::staggered;
  r = solvers::dynamics::solve_dynamic(s, o);
  BOOST_TEST(r.converged, r.reason);
}

BOOST_AUTO_TEST_CASE(just_within_the_bound_runs) {
  const auto s = cantilever(300.0);
  const auto P = DynamicProblem::from_scene(s);
  for (const auto grid : {ShootingGrid::staggered, ShootingGrid::euler}) {
    const double dt = 1.15 * solvers::dynamics::single_shooting_min_step(P, grid, 1e-10);
    auto o = options("implicit-midpoint", 20, dt, 20 * dt, scene::Initial::straight);
    o.grid = grid;
    const auto r = solvers::dynamics::solve_dynamic(s, o);
    BOOST_TEST_MESSAGE("grid " << solvers::dynamics::shooting_grid_name(grid) << ": dt = " << dt
                               << " s, kappa = "
                               << solvers::dynamics::single_shooting_exponent(P, dt) << ", "
                               << (r.converged ? "converged" : r.reason));
    BOOST_TEST(r.converged, r.reason);
  }
}

BOOST_AUTO_TEST_CASE(multiple_shooting_intervals) {
  // ceil(kappa / (bound - 4)) beyond the bound (12.2 at tol = 1e-10: 8.2 per interval), at most
  // one per segment; 1 within the bound
  using solvers::dynamics::shooting_intervals;
  const auto staggered = ShootingGrid::staggered;
  BOOST_TEST(shooting_intervals(12.0, staggered, 1e-10, 19) == 1);
  BOOST_TEST(shooting_intervals(12.3, staggered, 1e-10, 19) == 2);
  BOOST_TEST(shooting_intervals(25.1, staggered, 1e-10, 19) == 4);  // dt = 0.1 ms: 3 stalled
  BOOST_TEST(shooting_intervals(110.0, staggered, 1e-10, 19) == 14);
  BOOST_TEST(shooting_intervals(241.0, staggered, 1e-10, 19) == 19);
  BOOST_TEST(shooting_intervals(1100.0, staggered, 1e-10, 99) == 99);
  const double per_interval =
      solvers::dynamics::single_shooting_exponent_bound(staggered, 1e-10) - 4.0;
  BOOST_TEST(shooting_intervals(1100.0, staggered, 1e-10, 999) ==
             static_cast<int>(std::ceil(1100.0 / per_interval)));  // 134: no cap but the segments
  // tol 1e-14 leaves 3.0 - 4 < 1 per interval: one per unit of kappa
  BOOST_TEST(shooting_intervals(3.5, staggered, 1e-14, 19) == 4);
}
