#define BOOST_TEST_MODULE dynamics_variational_packed
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "dynamics_support.hpp"
#include "rodlab/lie/se3.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "../../solvers/dynamics/variational/packed_pair.hpp"

// The packed variational step (VariationalOptions::packed, packed_pair.hpp: the plain Cosserat
// step on pairs of nodes) against the general loop it replaces (packed = false), step by step on
// the same run: the two compute the same equations and differ only in rounding (the packed
// kernels take the longer of the scalar kernels' two series and multiply by 1 / ds and 1 / dt
// where the loop divides). Reference: the general loop. Bound: 1e-12 relative to the motion on
// every recorded quantity (measured: below 3e-16 m on the tip and the middle node over these
// runs, 800 steps each). A difference of
// exactly zero fails too: the two runs then took the same path, and the packed one was not
// tested.

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
namespace d = rodlab::solvers::dynamics;

struct Difference {
  double tip = 0.0;     ///< max over steps of |x_packed - x_loop| [m], x the tip and mid node
  double motion = 0.0;  ///< max over steps of |x - x_0| [m] (the scale)
  double energy = 0.0;  ///< max over steps of the ledger terms' differences [J]
  double energy_scale = 0.0;
  double velocity = 0.0;  ///< max over nodes of the final |eta_packed - eta_loop| (rad/s, m/s)
};

Difference compare(const scene::Scene& scene, int nodes, d::VariationalStep rule, long steps) {
  const auto P = d::DynamicProblem::from_scene(scene);
  const double dt = d::auto_time_step(P, "variational", nodes);
  const d::RestState initial = d::rest_shape(P, nodes);
  auto packed = d::make_variational(P, {nodes, 1e-12, 20, rule, true}, initial);
  auto loop = d::make_variational(P, {nodes, 1e-12, 20, rule, false}, initial);
  // the tip and the middle node (a clamped tip does not move)
  auto points = [](const d::Stepper& s) {
    const auto c = s.centerline();
    return std::pair{s.tip_position(), c[c.size() / 2].pose.translation()};
  };
  const auto [tip0, mid0] = points(*loop);
  Difference out;
  for (long i = 0; i < steps; ++i) {
    const double t = i * dt;
    BOOST_REQUIRE(packed->step(t, dt).ok);
    BOOST_REQUIRE(loop->step(t, dt).ok);
    const auto [tip_a, mid_a] = points(*packed);
    const auto [tip_b, mid_b] = points(*loop);
    out.tip = std::max({out.tip, (tip_a - tip_b).norm(), (mid_a - mid_b).norm()});
    out.motion = std::max({out.motion, (tip_b - tip0).norm(), (mid_b - mid0).norm()});
    const d::Energy a = packed->energy(), b = loop->energy();
    for (const auto& [x, y] : {std::pair{a.kinetic, b.kinetic}, {a.strain, b.strain},
                               {a.gravity, b.gravity}, {a.dissipated, b.dissipated},
                               {a.work_in, b.work_in}}) {
      out.energy = std::max(out.energy, std::abs(x - y));
      out.energy_scale = std::max(out.energy_scale, std::abs(y));
    }
  }
  const auto va = packed->velocities(), vb = loop->velocities();
  for (std::size_t j = 0; j < va.size(); ++j)
    out.velocity = std::max(out.velocity, (va[j] - vb[j]).lpNorm<Eigen::Infinity>());
  BOOST_TEST_MESSAGE(scene.name << " N = " << nodes << ": position " << out.tip << " m of "
                                << out.motion << " m, energy " << out.energy << " J of "
                                << out.energy_scale << " J, velocity " << out.velocity);
  return out;
}

void check(const Difference& d) {
  BOOST_TEST(d.tip > 0.0);  // else the packed step did not run
  BOOST_TEST(d.tip <= 1e-12 * d.motion);
  BOOST_TEST(d.energy <= 1e-12 * d.energy_scale);
  BOOST_TEST(d.velocity <= 1e-9);  // rad/s, m/s (measured: below 1e-10)
}

}  // namespace

// Released straight under gravity, undamped (one pass per step) and viscous (Verlet's
// corrector pass reads what the packed pass stores), N even and odd (an odd count of segments
// or nodes puts one node in both lanes of the last pair).
BOOST_AUTO_TEST_CASE(cantilever_released_under_gravity) {
  for (const double alpha : {0.0, 300.0})
    for (const int nodes : {10, 11, 20})
      for (const auto rule : {d::VariationalStep::verlet, d::VariationalStep::symplectic_euler})
        check(compare(cantilever(alpha), nodes, rule, 800));
}

// Every load the packed nodes take: gravity, a distributed body-frame wrench, drag and a tip
// wrench, with viscosity and without (drag alone: Verlet's damping corrector runs, and the
// segment pass skips the strain rates, which the corrector uses only times the viscosity).
BOOST_AUTO_TEST_CASE(distributed_load_drag_and_tip_load) {
  for (const double alpha : {30.0, 0.0}) {
    const auto scene = rod_scene(
        "{gravity: [-9.81, 0, 0], distributed: {force: [0, 0.3, 0], moment: [0, 0, 0.01], frame: "
        "body}, drag: {fluid_density: 1000, laminar: [0, 0, 0, 1.6e-3, 1.6e-3, 1.6e-3]}}",
        "{wrench: {force: [0, 0, -0.01], moment: [0.001, 0, 0]}}", alpha);
    for (const int nodes : {9, 12}) check(compare(scene, nodes, d::VariationalStep::verlet, 800));
  }
}

// Segments bent by more than small_angle::kSmallAngle (0.25 rad): a rest arc of 1.2 rad on
// 4 segments (0.3 rad each) under gravity, so that every pair's logarithm takes the scalar
// fallback.
BOOST_AUTO_TEST_CASE(segments_above_the_small_angle_bound) {
  const auto scene = io::load_scene_from_string(
      "schema: rodlab.scene/1\nname: coarse-arc\nrod:\n  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 0}\n"
      "  rest_strain: {arc: {angle: 1.2}}\ntip:\n  free: {}\nloads: {gravity: [-9.81, 0, 0]}\n",
      "coarse-arc.yaml");
  check(compare(scene, 5, d::VariationalStep::verlet, 800));
}

// A clamped tip (its node is held; the packed node pass stops before it), viscous, under
// gravity across the rod, released from straight.
BOOST_AUTO_TEST_CASE(clamped_tip) {
  const auto scene = io::load_scene_from_string(
      "schema: rodlab.scene/1\nname: clamped-clamped\nrod:\n  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 30}\n"
      "tip:\n  clamped: {position: [0, 0, 0.1], rotation: identity}\n"
      "loads: {gravity: [-9.81, 0, 0]}\n",
      "clamped-clamped.yaml");
  for (const int nodes : {10, 11}) check(compare(scene, nodes, d::VariationalStep::verlet, 800));
}

// A Kirchhoff rod (nu = nu*: no force part in the segments' stress, the constraint solve after
// the packed pass), released under gravity, undamped and viscous.
BOOST_AUTO_TEST_CASE(kirchhoff_rod) {
  for (const double alpha : {0.0, 300.0})
    for (const int nodes : {10, 11})
      check(compare(rod_scene("{gravity: [-9.81, 0, 0]}", "{}", alpha, "kirchhoff"), nodes,
                    d::VariationalStep::verlet, 800));
}

// The kernels the segment pass moves a segment with (packed_pair.hpp). Reference: lie::SE3's
// own products. inverse_compose(a, b, c) against a^-1 b c lane by lane for poses of segment
// size (angles up to 0.2 rad, lengths 0.01-1): quaternions and positions within 4 eps of their
// size (measured: 1.5 eps); shifted and lane_twice move lanes exactly.
BOOST_AUTO_TEST_CASE(segment_kernels_against_se3) {
  namespace packed = d::packed;
  using lie::SE3;
  using lie::Vector6;
  std::srand(7);
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const double length = trial % 2 ? 0.01 : 1.0;
    auto pose = [length] {
      Vector6 x = Vector6::Random();
      x.head<3>() *= 0.2 / std::sqrt(3.0);
      x.tail<3>() *= length;
      return SE3::exp(x);
    };
    const SE3 a[2] = {pose(), pose()}, b[2] = {pose(), pose()}, c[2] = {pose(), pose()};
    const packed::Pose g = packed::inverse_compose(packed::load(a[0], a[1]),
                                                   packed::load(b[0], b[1]),
                                                   packed::load(c[0], c[1]));
    for (int l = 0; l < 2; ++l) {
      const SE3 expected = a[l].inverse() * b[l] * c[l];
      const SE3 got = packed::lane(g, l);
      const double eps = std::numeric_limits<double>::epsilon();
      const double dq = (got.rotation().quaternion().coeffs() -
                         expected.rotation().quaternion().coeffs()).lpNorm<Eigen::Infinity>();
      const double dp = (got.translation() - expected.translation()).lpNorm<Eigen::Infinity>() /
                        std::max(length, expected.translation().norm());
      worst = std::max({worst, dq / eps, dp / eps});
    }
    // shifted: (first[1], second[0]); without `both`, (first[1], first[1]); lane_twice
    const packed::Pose first = packed::load(a[0], a[1]), second = packed::load(b[0], b[1]);
    const SE3 s0 = packed::lane(packed::shifted(first, second, true), 0);
    const SE3 s1 = packed::lane(packed::shifted(first, second, true), 1);
    const SE3 t1 = packed::lane(packed::shifted(first, second, false), 1);
    const SE3 u1 = packed::lane(packed::lane_twice(first, 0), 1);
    BOOST_TEST((s0.translation() == a[1].translation() && s1.translation() == b[0].translation()));
    BOOST_TEST((s0.rotation().quaternion().coeffs() == a[1].rotation().quaternion().coeffs()));
    BOOST_TEST((t1.translation() == a[1].translation() && u1.translation() == a[0].translation()));
  }
  BOOST_TEST_MESSAGE("inverse_compose(a, b, c) against SE3: " << worst << " eps");
  BOOST_TEST(worst <= 4.0);
}
