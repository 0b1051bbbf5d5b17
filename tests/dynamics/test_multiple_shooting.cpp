#define BOOST_TEST_MODULE dynamics_multiple_shooting
#include <boost/test/unit_test.hpp>

// Multiple shooting of the staggered march (staggered_shooting_stepper.cpp, docs/dynamics.md
// "Multiple shooting below the bound"): the same discrete equations as single shooting, solved
// with the rod cut into intervals. Rod: the Table 2.1 cantilever released straight under gravity
// (dynamics_support.hpp), L = 0.1 m.
// (a) Within single shooting's bound, forced intervals reproduce single shooting's run (the
//     same equations solved singly) to the tolerance's effect, for both time rules, a muscle
//     (an actuator unknown) and a clamped tip (whose residual chains every interval's strains).
// (b) Below the bound, where single shooting was refused, the automatic intervals run; the run
//     matches implicit-midpoint-collocation (the midpoint rule on the same staggered rod, each
//     step solved globally by KINSOL: a different second-order discretisation of the poses)
//     with the gap falling as dt^2, with and without actuator unknowns (a muscle, length
//     control), and an undamped rod keeps its energy ledger closed.
// (c) The rod the bound refused outright (steel wire, kappa 52.5) runs and meets collocation.
// (d) More intervals than session 32's dense Newton allowed (32) run: the sparse model.
#include <algorithm>
#include <cmath>
#include <string>

#include "dynamics_support.hpp"
#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::ShootingGrid;

solvers::dynamics::DynamicSolveOptions staggered(
    const std::string& scheme, int nodes, double dt, double t_end, int intervals,
    scene::Initial initial = scene::Initial::straight) {
  auto o = options(scheme, nodes, dt, t_end, initial);
  o.grid = ShootingGrid::staggered;
  o.shooting_intervals = intervals;
  return o;
}

/// The largest distance between the two runs' tips over their output times [m].
double tip_gap(const result::DynamicResult& a, const result::DynamicResult& b) {
  BOOST_REQUIRE_EQUAL(a.tip_position.size(), b.tip_position.size());
  double gap = 0.0;
  for (std::size_t k = 0; k < a.tip_position.size(); ++k)
    gap = std::max(gap, (a.tip_position[k] - b.tip_position[k]).norm());
  return gap;
}

result::DynamicResult run(const scene::Scene& s, const solvers::dynamics::DynamicSolveOptions& o) {
  auto r = solvers::dynamics::solve_dynamic(s, o);
  BOOST_TEST_REQUIRE(r.converged, o.scheme << " dt = " << o.dt << ": " << r.reason);
  return r;
}

/// Beyond single shooting's bound on the staggered grid at tol 1e-10 (so the run uses intervals).
bool beyond_the_bound(const scene::Scene& s, double dt) {
  const auto P = DynamicProblem::from_scene(s);
  return solvers::dynamics::single_shooting_exponent(P, dt) >
         solvers::dynamics::single_shooting_exponent_bound(ShootingGrid::staggered, 1e-10);
}

/// A rod held at both ends, the clamp 1 cm sideways, viscous, under gravity and a sideways push
/// from t = 10 ms (the example scene).
scene::Scene clamped_sideways() {
  return io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/clamped-clamped-dynamics.yaml");
}

}  // namespace

BOOST_AUTO_TEST_CASE(forced_intervals_reproduce_single_shooting) {
  // 5 ms and 20 nodes: kappa 6.6, inside the bound (12.2), where single shooting converges; the
  // gap is the two solves' tolerances (1e-10 on residuals scaled by E I / L^2) carried over 0.1 s
  const auto s = cantilever(300.0);
  for (const char* scheme : {"implicit-midpoint", "bdf-alpha"}) {
    const auto single = run(s, staggered(scheme, 20, 5e-3, 0.1, 1));
    for (const int intervals : {2, 3, 5, 19}) {
      const auto multiple = run(s, staggered(scheme, 20, 5e-3, 0.1, intervals));
      const double gap = tip_gap(single, multiple);
      BOOST_TEST_MESSAGE(scheme << ", " << intervals << " intervals: tip gap " << gap << " m");
      BOOST_TEST(gap < 1e-10);
    }
  }
  // a muscle (its length an unknown of every step): the example scene at N = 11
  const auto muscle =
      io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/muscle-dynamics.yaml");
  const auto muscle_single = run(muscle, staggered("implicit-midpoint", 11, 5e-3, 0.3, 1));
  for (const int intervals : {2, 4}) {
    const auto multiple = run(muscle, staggered("implicit-midpoint", 11, 5e-3, 0.3, intervals));
    const double gap = tip_gap(muscle_single, multiple);
    BOOST_TEST_MESSAGE("muscle, " << intervals << " intervals: tip gap " << gap << " m");
    BOOST_TEST(gap < 1e-10);
  }
  // a clamped tip: its residual is the end-of-step tip pose, chained through every interval
  const auto clamped = clamped_sideways();
  const auto from_statics = scene::Initial::static_equilibrium;
  const auto single = run(clamped, staggered("implicit-midpoint", 21, 5e-3, 0.1, 1, from_statics));
  const auto multiple =
      run(clamped, staggered("implicit-midpoint", 21, 5e-3, 0.1, 4, from_statics));
  const double gap = tip_gap(single, multiple);  // the tip is held: compare the middle instead
  BOOST_TEST(gap < 1e-12);
  BOOST_REQUIRE(!single.final_centerline.empty());
  double mid_gap = 0.0;
  for (std::size_t k = 0; k < single.final_centerline.size(); ++k)
    mid_gap = std::max(mid_gap, (single.final_centerline[k].pose.translation() -
                                 multiple.final_centerline[k].pose.translation()).norm());
  BOOST_TEST_MESSAGE("clamped, 4 intervals: centreline gap at 0.1 s " << mid_gap << " m");
  BOOST_TEST(mid_gap < 1e-10);
}

/// implicit-midpoint (multiple shooting) against implicit-midpoint-collocation at dt, dt / 2,
/// dt / 4, all below single shooting's bound: the gap's ratios per halving.
void gap_falls_at_second_order(const scene::Scene& s, int nodes, double dt, double t_end) {
  double last = 0.0;
  for (int k = 0; k < 3; ++k, dt /= 2.0) {
    BOOST_TEST_REQUIRE(beyond_the_bound(s, dt));
    const auto ms = run(s, staggered("implicit-midpoint", nodes, dt, t_end, 0));
    const auto co = run(s, staggered("implicit-midpoint-collocation", nodes, dt, t_end, 0));
    const double gap = tip_gap(ms, co);
    BOOST_TEST_MESSAGE(s.name << ", dt = " << dt << " s: tip gap to collocation " << gap << " m");
    if (last > 0.0) BOOST_TEST(last / gap == 4.0, boost::test_tools::tolerance(0.1));
    last = gap;
  }
}

BOOST_AUTO_TEST_CASE(below_the_bound_meets_collocation_at_second_order) {
  // implicit-midpoint-collocation integrates the poses by the midpoint rule too, but from the
  // velocities: the two differ by O(dt^2), so the gap must fall by 4 per halving, while an error
  // of multiple shooting would not scale so. The viscous cantilever at N = 20 below single
  // shooting's smallest step (1.02 ms): dt = 0.8, 0.4, 0.2 ms (kappa 13.2, 16.4, 20.0: 2, 2, 3
  // intervals; measured ratios 4.006, 4.001).
  gap_falls_at_second_order(cantilever(300.0), 20, 8e-4, 0.04);
  // With actuator unknowns (their columns re-march every interval): the example muscle switched
  // on and off (N = 11; 1, 0.5, 0.25 ms, kappa 12.3-18.8; measured 3.99, 4.00), and a cable
  // pulled in by 0.1 mm over 10 ms under length control (measured 3.98, 3.96).
  const auto muscle =
      io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/muscle-dynamics.yaml");
  gap_falls_at_second_order(muscle, 11, 1e-3, 0.3);
  const auto pulled = actuated_scene(
      "{gravity: [-9.81, 0, 0]}",
      "  - cable: {offset: [0.004, 0], displacement: {steps: [[0, 0], [0.01, 1.0e-4]]}}\n", 300.0);
  gap_falls_at_second_order(pulled, 20, 1e-3, 0.1);
}

BOOST_AUTO_TEST_CASE(a_stalled_step_is_retried_with_more_intervals) {
  // The viscous cantilever at N = 20, dt = 0.1 ms (kappa 25.1): forced to three intervals
  // (8.4 each) the joins stall on their rounding at t = 0.073 s (measured without the retry:
  // residual 1.3e-10 against tol 1e-10); the retry with six carries the run to its end, on the
  // automatic run's (four intervals) tip.
  const auto s = cantilever(300.0);
  const auto automatic = run(s, staggered("implicit-midpoint", 20, 1e-4, 0.15, 0));
  const auto three = run(s, staggered("implicit-midpoint", 20, 1e-4, 0.15, 3));
  const double gap = tip_gap(automatic, three);
  BOOST_TEST_MESSAGE("three intervals, retried: tip gap to the automatic run " << gap << " m");
  BOOST_TEST(gap < 1e-10);
}

BOOST_AUTO_TEST_CASE(undamped_energy_ledger_below_the_bound) {
  // The undamped cantilever at dt = 0.1 ms, N = 20 (kappa 110, 14 intervals): the midpoint rule
  // on the staggered grid conserves the energy (kinetic, strain and gravity's potential) up to
  // the solves' tolerance.
  const auto s = cantilever(0.0);
  BOOST_TEST_REQUIRE(beyond_the_bound(s, 1e-4));
  const auto r = run(s, staggered("implicit-midpoint", 20, 1e-4, 0.02, 0));
  double worst = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < r.energy.total.size(); ++k) {
    worst = std::max(worst, std::abs(r.energy.total[k] - r.energy.total.front()));
    scale = std::max(scale, std::abs(r.energy.gravity[k]));
  }
  BOOST_TEST_MESSAGE("energy drift " << worst << " J against |gravity| " << scale << " J");
  BOOST_TEST(scale > 1e-6);
  BOOST_TEST(worst < 1e-8 * scale);
}

BOOST_AUTO_TEST_CASE(steel_wire_runs_and_meets_collocation) {
  // Steel, E = 200 GPa, D = 1 mm, L = 0.1 m, N = 12, dt = 5.75 us (the implicit schemes' dt auto):
  // kappa 52.5, refused by single shooting's bound before multiple shooting; the tip after
  // 5 steps against collocation's (measured 4.05e-9 m of sag, the same to 1e-15 m).
  const auto s = io::load_scene_from_string(R"(schema: rodlab.scene/1
name: steel-wire
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.001}
  material: {E: 2.0e11, poisson: 0.3, rho: 7850}
tip:
  free: {}
loads:
  gravity: [-9.81, 0, 0]
)",
                                            "steel-wire.yaml");
  const double dt = 5.75015e-6;
  BOOST_TEST_REQUIRE(beyond_the_bound(s, dt));
  const auto ms = run(s, staggered("implicit-midpoint", 12, dt, 5 * dt, 0));
  const auto co = run(s, staggered("implicit-midpoint-collocation", 12, dt, 5 * dt, 0));
  const double sag = std::abs(co.tip_position.back().x());
  BOOST_TEST_MESSAGE("sag " << sag << " m, gap " << tip_gap(ms, co) << " m");
  BOOST_TEST(sag > 1e-9);
  BOOST_TEST(tip_gap(ms, co) < 1e-3 * sag);
}

BOOST_AUTO_TEST_CASE(more_intervals_than_the_dense_inverse_allowed) {
  // The undamped cantilever at N = 100, dt = 1 us: more than 32 intervals (the cap of session
  // 32's dense inverse, where this run stalled at its first step); the sparse Newton model
  // (inverse_broyden.hpp) runs it. Reference: in 0.2 ms a shear or bending wave from the clamp
  // travels a few millimetres, so the tip is in free fall, x = -g t^2 / 2 (the midpoint rule is
  // exact for a constant acceleration), and collocation on the same grid. Measured (99
  // intervals): free-fall gap 8.3e-20 m of a 1.96e-7 m fall, tip and centreline within 1.1e-16 m
  // of collocation's, node 1 held 1.03e-7 m above free fall by the clamp.
  const auto s = cantilever(0.0);
  const double dt = 1e-6, t_end = 2e-4;
  const auto P = DynamicProblem::from_scene(s);
  const int wanted = solvers::dynamics::shooting_intervals(
      solvers::dynamics::single_shooting_exponent(P, dt), ShootingGrid::staggered, 1e-10, 99);
  BOOST_TEST_MESSAGE("intervals " << wanted);
  BOOST_TEST_REQUIRE(wanted > 32);
  auto o = staggered("implicit-midpoint", 100, dt, t_end, 0);
  o.output_every = 50;
  const auto ms = run(s, o);
  o.scheme = "implicit-midpoint-collocation";
  const auto co = run(s, o);
  double fall = 0.0;
  for (std::size_t k = 0; k < ms.t.size(); ++k) {
    const double t = ms.t[k];
    fall = std::max(fall, std::abs(ms.tip_position[k].x() + 0.5 * 9.81 * t * t));
  }
  // near the clamp the rod bends: the centreline against collocation's, and how far its nodes
  // but the clamped one are from free fall there (so that the comparison sees the bending)
  BOOST_REQUIRE_EQUAL(ms.final_centerline.size(), co.final_centerline.size());
  double centreline = 0.0, bent = 0.0;
  for (std::size_t j = 0; j < ms.final_centerline.size(); ++j) {
    const auto& p = ms.final_centerline[j].pose.translation();
    centreline = std::max(centreline, (p - co.final_centerline[j].pose.translation()).norm());
    if (j > 0) bent = std::max(bent, std::abs(p.x() + 0.5 * 9.81 * t_end * t_end));
  }
  BOOST_TEST_MESSAGE("free fall gap " << fall << " m of " << 0.5 * 9.81 * t_end * t_end
                                      << " m, collocation gap " << tip_gap(ms, co)
                                      << " m; centreline gap " << centreline
                                      << " m, bending " << bent << " m");
  BOOST_TEST(fall < 1e-12);
  BOOST_TEST(tip_gap(ms, co) < 1e-12);
  BOOST_TEST(bent > 1e-8);
  BOOST_TEST(centreline < 1e-3 * bent);
}
