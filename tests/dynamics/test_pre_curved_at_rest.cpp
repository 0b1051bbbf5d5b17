#define BOOST_TEST_MODULE dynamics_pre_curved_at_rest
#include <boost/test/unit_test.hpp>

// Pre-curved rods at rest (issue #18): a rod whose reference twist xi* is curved (an arc,
// kappa* L = 1, and a helix with curvature and torsion; rod.reference_twist), released at rest in
// its rest shape with no load, is an equilibrium of every dynamics scheme: the strain energy
// (2.28) is written in xi - xi*, so the stresses vanish and nothing may move. Reference: the
// initial state itself. Every scheme and grid, Cosserat and Kirchhoff rods, N = 10, 100 steps
// (variational at its automatic step, the implicit schemes at 5 ms and tol 1e-13, ida to 0.1 s
// at rtol = atol = 1e-10). Tolerance: rounding, 1e-12 m on the tip's displacement and 1e-10 rad/s
// on any node's angular velocity (times L for the linear ones); measured at most 2e-15 m and
// 4e-11 1/s. A scheme that assumed a straight rest shape anywhere (a
// reference strain of [0, 0, 0, 0, 0, 1] in a stress, an energy or a march) moves the rod at
// O(E I kappa*) and fails by orders of magnitude.
#include <algorithm>
#include <string>

#include "dynamics_support.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::ShootingGrid;

constexpr int kNodes = 10;
constexpr long kSteps = 100;
/// The implicit schemes' solver tolerance: the motion they leave is their residual's (the
/// staggered implicit-midpoint, which does not damp it, 1e-9 1/s at the default 1e-10, 4e-11 at
/// 1e-12, 5e-12 at 1e-13: measured), so they solve to near rounding here.
constexpr double kTol = 1e-13;

/// The Table 2.1 rod (viscosity 30 Pa s) with reference twist `twist`, free tip, no loads.
scene::Scene pre_curved(const std::string& twist, const std::string& model) {
  return io::load_scene_from_string(
      "schema: rodlab.scene/1\nname: pre-curved\nrod:\n  model: " + model +
          "\n  length: 0.1\n  section: {shape: circle, diameter: 0.01}\n"
          "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 30}\n"
          "  reference_twist: " + twist + "\ntip:\n  free: {}\n",
      "pre-curved.yaml");
}

struct Drift {
  double tip = 0.0;       ///< max |tip - tip_0| [m]
  double velocity = 0.0;  ///< max over nodes of |omega|, |v| / L at the end
};

Drift run_at_rest(const DynamicProblem& P, const std::string& scheme, ShootingGrid grid) {
  const double dt = scheme == "variational" ? solvers::dynamics::auto_time_step(P, scheme, kNodes)
                    : scheme == "ida"       ? 1e-3
                                            : 5e-3;
  auto stepper = make_scheme(scheme, P, kNodes, straight(P, kNodes), kTol, 1e-10, grid);
  const lie::Vector3 tip0 = stepper->tip_position();
  Drift d;
  for (long i = 0; i < kSteps; ++i) {
    const auto s = stepper->step(i * dt, dt);
    BOOST_REQUIRE_MESSAGE(s.ok, scheme << ": " << s.reason);
    d.tip = std::max(d.tip, (stepper->tip_position() - tip0).norm());
  }
  for (const auto& eta : stepper->velocities())
    d.velocity = std::max({d.velocity, eta.head<3>().norm(), eta.tail<3>().norm() / P.length()});
  return d;
}

void check(const std::string& twist, const std::string& model) {
  const auto P = DynamicProblem::from_scene(pre_curved(twist, model));
  struct Run {
    const char* scheme;
    ShootingGrid grid;
    const char* name;
  };
  for (const Run& r : {Run{"variational", ShootingGrid::euler, "variational"},
                       Run{"implicit-midpoint", ShootingGrid::staggered, "implicit-midpoint"},
                       Run{"implicit-midpoint", ShootingGrid::euler, "implicit-midpoint (Euler)"},
                       Run{"bdf-alpha", ShootingGrid::staggered, "bdf-alpha"},
                       Run{"implicit-midpoint-collocation", ShootingGrid::euler, "collocation"},
                       Run{"ida", ShootingGrid::euler, "ida"}}) {
    const Drift d = run_at_rest(P, r.scheme, r.grid);
    BOOST_TEST_MESSAGE(model << ", reference twist " << twist << ", " << r.name
                             << ": tip moved " << d.tip << " m, largest velocity " << d.velocity
                             << " 1/s");
    BOOST_TEST(d.tip <= 1e-12, r.name << ": tip moved " << d.tip << " m");
    BOOST_TEST(d.velocity <= 1e-10, r.name << ": velocity " << d.velocity << " 1/s");
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(arc_at_rest_in_every_scheme) {
  check("[10, 0, 0, 0, 0, 1]", "cosserat");
  check("[10, 0, 0, 0, 0, 1]", "kirchhoff");
}

BOOST_AUTO_TEST_CASE(helix_at_rest_in_every_scheme) {
  check("[6, 0, 4, 0, 0, 1]", "cosserat");
}
