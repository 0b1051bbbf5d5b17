#define BOOST_TEST_MODULE dynamics_failure_messages
#include <boost/test/unit_test.hpp>

#include <string>

#include "dynamics_support.hpp"
#include "rodlab/check.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

// Failure reasons keep their numbers: a step of 2.5e-7 s is printed as 2.5e-07 (fmt {:g},
// rodlab/check.hpp), not as std::to_string's "0.000000". Reference: the %g text of the step.
//
// Rod: a short steel needle, L = 1 cm, D = 2 mm, E = 200 GPa, G = 80 GPa, rho = 7800 kg/m^3,
// under gravity. At N = 20 (ds = 0.53 mm, c = sqrt(E / rho) = 5.1 km/s) the explicit variational
// scheme's stability limit is ~1e-7 s, so 2.5e-7 s is beyond it and the run blows up.

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;

constexpr double kDt = 2.5e-7;
constexpr int kNodes = 20;

/// The support's rod under gravity, made a steel needle.
scene::Scene steel_needle() {
  scene::Scene s = rod_scene("{gravity: [-9.81, 0, 0]}", "{}");
  s.rod.length = 0.01;
  s.rod.section = rod::Circle{0.002};
  s.rod.material = rod::Material{2.0e11, 8.0e10, 7800.0, 0.0};  // E, G, rho, viscosity
  return s;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

// The stepper's own reason names the step: "... (t = ... s, dt = 2.5e-07 s)".
BOOST_AUTO_TEST_CASE(variational_divergence_names_dt) {
  const auto P = solvers::dynamics::DynamicProblem::from_scene(steel_needle());
  const double limit = solvers::dynamics::variational_stable_step(P, kNodes);
  BOOST_TEST_MESSAGE("stability limit " << limit << " s, dt " << kDt << " s");
  BOOST_REQUIRE(kDt > 1.5 * limit);  // the scene really is beyond the explicit limit
  const auto stepper = make_scheme("variational", P, kNodes, straight(P, kNodes));
  solvers::dynamics::StepStatus status;
  long steps = 0;
  for (; steps < 100000 && status.ok; ++steps) status = stepper->step(steps * kDt, kDt);
  BOOST_TEST_MESSAGE("after " << steps << " steps: " << status.reason);
  BOOST_REQUIRE(!status.ok);
  BOOST_TEST(contains(status.reason, "unstable"), status.reason);
  BOOST_TEST(contains(status.reason, "dt = 2.5e-07 s"), status.reason);
  BOOST_TEST(!contains(status.reason, "0.000000"), status.reason);
}

// The same run through solve_dynamic (what goes into the result file): the failed step's own
// reason is kept (the instability check after it does not overwrite it), so the result names
// the step, in %g (std::to_string printed dt = 2.5e-7 s as "0.000000").
BOOST_AUTO_TEST_CASE(solve_dynamic_reason_keeps_its_numbers) {
  const auto r = solvers::dynamics::solve_dynamic(
      steel_needle(), options("variational", kNodes, kDt, 0.01, scene::Initial::straight));
  BOOST_TEST_MESSAGE("dt " << r.dt << " s, " << r.steps << " steps: " << r.reason);
  BOOST_REQUIRE(!r.converged);
  BOOST_TEST(r.dt == kDt, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(contains(r.reason, "unstable"), r.reason);
  BOOST_TEST(contains(r.reason, "dt = 2.5e-07 s"), r.reason);
  BOOST_REQUIRE(!r.t.empty());
  BOOST_TEST(contains(r.reason, rodlab::format("t = {:g} s", r.t.back())), r.reason);
  BOOST_TEST(!contains(r.reason, "0.000000"), r.reason);
}
