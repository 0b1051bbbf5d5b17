#define BOOST_TEST_MODULE dynamics_pre_curved_at_rest
#include <boost/test/unit_test.hpp>

// Pre-curved rods at rest (issue #18): a rod whose reference twist xi* is curved (an arc,
// kappa* L = 1, and helices with curvature and torsion; rod.reference_twist or rod.rest_strain),
// released at rest in its rest shape with no load, is an equilibrium of every dynamics scheme:
// the strain energy (2.28) is written in xi - xi*, so the stresses vanish and nothing may move.
// Reference: the initial state itself. Every scheme and grid, Cosserat and Kirchhoff rods,
// N = 10, 100 steps (variational at its automatic step, the implicit schemes at 5 ms and
// tol 1e-12, ida to 0.1 s at rtol = atol = 1e-10). Tolerances: 1e-12 m on the tip's displacement
// and 3e-10 1/s on any node's angular velocity (and linear velocity / L); measured at most
// 1.1e-14 m and 1.0e-10 1/s (the staggered implicit-midpoint on the coiled helix, kappa L = 4.3:
// it keeps its shooting residual as motion; every other scheme <= 4e-11). A scheme that assumed
// a straight rest shape anywhere (a reference strain of [0, 0, 0, 0, 0, 1] in a stress, an energy
// or a march) moves the rod at O(E I kappa*) and fails by orders of magnitude.
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
/// staggered implicit-midpoint on the arc, which does not damp it: 1e-9 1/s at the default
/// 1e-10, 4e-11 at 1e-12, 5e-12 at 1e-13, measured; 1e-13 is below the coiled helix's rounding
/// floor), so they solve close to rounding here.
constexpr double kTol = 1e-12;

/// The Table 2.1 rod (viscosity 30 Pa s) with the rest shape `rest` (a `rod:` line:
/// reference_twist or rest_strain), free tip, no loads.
scene::Scene pre_curved(const std::string& rest, const std::string& model) {
  return io::load_scene_from_string(
      "schema: rodlab.scene/1\nname: pre-curved\nrod:\n  model: " + model +
          "\n  length: 0.1\n  section: {shape: circle, diameter: 0.01}\n"
          "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 30}\n"
          "  " + rest + "\ntip:\n  free: {}\n",
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

void check(const std::string& rest, const std::string& model) {
  const auto P = DynamicProblem::from_scene(pre_curved(rest, model));
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
    BOOST_TEST_MESSAGE(model << ", " << rest << ", " << r.name
                             << ": tip moved " << d.tip << " m, largest velocity " << d.velocity
                             << " 1/s");
    BOOST_TEST(d.tip <= 1e-12, r.name << ": tip moved " << d.tip << " m");
    BOOST_TEST(d.velocity <= 3e-10, r.name << ": velocity " << d.velocity << " 1/s");
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(arc_at_rest_in_every_scheme) {
  check("reference_twist: [10, 0, 0, 0, 0, 1]", "cosserat");
  check("rest_strain: {arc: {angle: 1}}", "kirchhoff");
}

BOOST_AUTO_TEST_CASE(helix_at_rest_in_every_scheme) {
  check("reference_twist: [6, 0, 4, 0, 0, 1]", "cosserat");
  check("rest_strain: {helix: {radius: 0.02, pitch: 0.05}}", "cosserat");
}
