#define BOOST_TEST_MODULE dynamic_length_control
#include <boost/test/unit_test.hpp>

// Length control in the dynamics (docs/dynamics.md "Muscles and length control"): a cable's
// displacement or a fluidic chamber's volume is prescribed on a schedule and its tension
// (pressure) is an unknown of every step, chosen so that the path length at the end of the
// step is the prescribed one (2.47), (2.53). Rod: thesis Table 2.1 (L = 0.1 m, D = 1 cm,
// E = 1 MPa, G = 0.33 MPa, rho = 1000 kg/m^3).
//   (a) the prescribed length is reached at every step to the solver's tolerance, and the
//       tension / pressure comes out with the right sign;
//   (b) under laminar drag the rod settles to the statics of the same scene (rkmk-rk4,
//       N = 401; the tension an unknown of the BVP) at the scheme's spatial order;
//   (c) the ledger closes: the actuator's work -F dL/dt is in work_in;
// `ida` with length control (the stabilised index-2 form): test_ida_constraints.cpp.
// Measured numbers: in each case's comment and the messages (--log_level=message).

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics_support.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::Energy;
using solvers::dynamics::Stepper;
using lie::Vector3;

const std::string kDrag =
    "{drag: {fluid_density: 1000, laminar: [0, 0, 0, 1.6e-3, 1.6e-3, 1.6e-3]}}";

/// A number in YAML, to full precision (std::to_string keeps 6 decimals).
std::string num(double x) {
  std::ostringstream out;
  out << std::setprecision(17) << x;
  return out.str();
}

/// A cable at x = 4 mm pulled in by `displacement` (YAML).
std::string cable(const std::string& displacement, const std::string& span = "") {
  return "  - cable: {offset: [0.004, 0], displacement: " + displacement +
         (span.empty() ? "" : ", span: " + span) + "}\n";
}

/// A chamber (r_c = 1.5 mm) at y = 3 mm holding `volume` (YAML) of fluid.
std::string chamber(const std::string& volume) {
  return "  - fluidic: {offset: [0, 0.003], chamber_radius: 0.0015, volume: " + volume + "}\n";
}
constexpr double kChamberArea = std::numbers::pi * 0.0015 * 0.0015;

/// run_steps and, after every step (from step `first_checked` on), every length-controlled
/// actuator's length against its target at the step's end (`target(k, t)` of actuator k).
struct Trace : StepTrace {
  double worst_length_error = 0.0;  ///< max over steps and actuators of |length - target|
  double min_force = 1e300, max_force = -1e300;
};

template <class Target>
Trace run(Stepper& s, double dt, long steps, Target target, long first_checked = 0) {
  Trace r;
  static_cast<StepTrace&>(r) = run_steps(s, dt, steps, [&](long i) {
    if (i < first_checked) return;
    for (const auto& a : s.actuator_readings()) {
      r.worst_length_error =
          std::max(r.worst_length_error, std::abs(a.length - target(a.actuator, (i + 1) * dt)));
      r.min_force = std::min(r.min_force, a.force);
      r.max_force = std::max(r.max_force, a.force);
    }
  });
  return r;
}

/// A ramp 0 -> v over [0, t1], then held.
std::string ramp(double v, double t1) {
  return "{ramp: [[0, 0], [" + num(t1) + ", " + num(v) + "]]}";
}

const char* const kSchemes[] = {"implicit-midpoint-collocation", "variational", "implicit-midpoint",
                                "bdf-alpha"};

/// The time step of a scheme in these tests: 2 ms for collocation, the stable step (dt: auto)
/// for variational; the shooting schemes need 10 ms or more at N = 11 (their lower step bound,
/// docs/dynamics.md).
double step_of(const std::string& scheme, const DynamicProblem& P, int nodes) {
  if (scheme == "variational") return solvers::dynamics::auto_time_step(P, scheme, nodes);
  return scheme == "implicit-midpoint-collocation" ? 2e-3 : 1e-2;
}

}  // namespace

BOOST_AUTO_TEST_CASE(prescribed_lengths_are_reached_at_every_step) {
  // Reference: the schedule itself. A cable (span [0.02, 0.1], entering from outside at
  // s0 = 0.02 m) pulled in by 0 -> 2 mm over 0.1 s, and a chamber filled from its rest volume
  // A_c L to 1.03 A_c L over 0.1 s; viscosity 300 Pa s, N = 11, 0.2 s (dt: step_of). After every
  // step (variational: from the second on, its forces act on the next step's positions) each
  // path length (on the scheme's grid) equals its target at the end of the step to
  // 1e-10 m (the solvers' tolerance 1e-10 on length / L is 1e-11 m); the tension is positive
  // and the pressure -F / A_c is positive (the rod is pulled and pressurised).
  const double rest_volume = kChamberArea * 0.1;
  const std::string filling = "{ramp: [[0, " + num(rest_volume) + "], [0.1, " +
                              num(1.03 * rest_volume) + "]]}";
  for (const std::string& a : {cable(ramp(0.002, 0.1), "[0.02, 0.1]"), chamber(filling)}) {
    const auto s = actuated_scene("{}", a, 300.0);
    const auto P = DynamicProblem::from_scene(s);
    const auto& actuator = P.actuators()[0];
    for (const char* scheme : kSchemes) {
      auto st = make_scheme(scheme, P, 11, straight(P, 11));
      const auto readings0 = st->actuator_readings();
      BOOST_REQUIRE_EQUAL(readings0.size(), 1U);
      const double rest = readings0[0].length;  // the grid's rest length
      const double dt = step_of(scheme, P, 11);
      const long steps = std::lround(0.2 / dt);
      // variational: the force of step n sets the lengths of step n + 1 (SHAKE), so the first
      // step's end keeps the initial length
      const long first = std::string(scheme) == "variational" ? 1 : 0;
      const Trace r = run(
          *st, dt, steps, [&](int, double t) { return actuator.target_length(t, rest); }, first);
      const bool is_cable = actuator.is_cable;
      BOOST_TEST_MESSAGE((is_cable ? "cable" : "chamber")
                         << " " << scheme << ": max |length - target| = " << r.worst_length_error
                         << " m; " << (is_cable ? "tension " : "pressure ")
                         << (is_cable ? r.min_force : -r.max_force / kChamberArea) << " .. "
                         << (is_cable ? r.max_force : -r.min_force / kChamberArea)
                         << (is_cable ? " N" : " Pa") << ", "
                         << double(r.iterations) / steps << " iterations/step, wall " << r.wall
                         << " s");
      BOOST_TEST(r.worst_length_error <= 1e-10);
      if (is_cable)
        BOOST_TEST(r.min_force > 0.0);
      else
        BOOST_TEST(r.max_force < 0.0);
    }
  }
}

BOOST_AUTO_TEST_CASE(kirchhoff_rods_keep_both_constraints) {
  // Reference: the two constraints. A Kirchhoff rod (nu = nu*) pulled by a cable, 0 -> 2 mm
  // over 0.1 s, viscosity 300 Pa s, N = 11, 0.2 s: collocation solves the constraint forces,
  // the cable force and both end-of-step constraints in one system; the shooting schemes keep
  // nu = nu* by construction. Every step ends with the prescribed length to 1e-10 m and
  // max |nu - nu*| <= 1e-10 (node strains; the staggered grid averages its segments').
  const auto P = DynamicProblem::from_scene(actuated_scene("{}", cable(ramp(0.002, 0.1)), 300.0,
                                                           "kirchhoff"));
  const auto& actuator = P.actuators()[0];
  for (const char* scheme : {"implicit-midpoint-collocation", "bdf-alpha"}) {
    auto st = make_scheme(scheme, P, 11, straight(P, 11));
    const double rest = st->actuator_readings()[0].length;
    const double dt = step_of(scheme, P, 11);
    const Trace r = run(*st, dt, std::lround(0.2 / dt),
                        [&](int, double t) { return actuator.target_length(t, rest); });
    double nu = 0.0;
    for (const auto& c : st->centerline())
      nu = std::max(nu, (c.twist.tail<3>() - Vector3(0, 0, 1)).lpNorm<Eigen::Infinity>());
    BOOST_TEST_MESSAGE("kirchhoff " << scheme << ": max |length - target| = "
                       << r.worst_length_error << " m, |nu - nu*| = " << nu << ", tension "
                       << r.min_force << " .. " << r.max_force << " N");
    BOOST_TEST(r.worst_length_error <= 1e-10);
    BOOST_TEST(nu <= 1e-10);
    BOOST_TEST(r.min_force > 0.0);
  }
}

BOOST_AUTO_TEST_CASE(every_scheme_settles_to_the_statics) {
  // Reference: the statics of the same scene at the final input (rkmk-rk4, N = 401, the tension
  // / pressure an unknown of the BVP). Displacement 1.5 mm (or the chamber at 1.02 x its rest
  // volume) reached over 0.1 s under laminar drag and Kelvin-Voigt 300 Pa s, 2.5 s (dt:
  // step_of; 20 ms for the shooting schemes); a uniform world force 0.05 N/m along y makes the
  // strain non-uniform. Collocation and variational (staggered grid): observed order in
  // [1.8, 2.3] between N = 6 and 11; shooting schemes (Euler in s): [0.8, 1.3] between N = 11
  // and 21 (their tip the mean of the last two steps: implicit-midpoint's stiff viscous modes
  // flip sign).
  const double rest_volume = kChamberArea * 0.1;
  const std::string volume = "{ramp: [[0, " + num(rest_volume) + "], [0.1, " +
                             num(1.02 * rest_volume) + "]]}";
  const std::string held_volume = num(1.02 * rest_volume);
  struct Case {
    const char* what;
    std::string dynamic, statics;
  };
  const Case cases[] = {{"cable", cable(ramp(0.0015, 0.1)), cable("0.0015")},
                        {"chamber", chamber(volume), chamber(held_volume)}};
  for (const auto& c : cases) {
    const std::string loads =
        "{distributed: {force: [0, 0.05, 0], frame: world}, "
        "drag: {fluid_density: 1000, laminar: [0, 0, 0, 1.6e-3, 1.6e-3, 1.6e-3]}}";
    const Vector3 tip = static_tip(actuated_scene(loads, c.statics), "rkmk-rk4", 401, 1e-12);
    BOOST_TEST_MESSAGE(c.what << ": static tip " << tip.transpose());
    const auto P = DynamicProblem::from_scene(actuated_scene(loads, c.dynamic, 300.0));
    for (const char* scheme : kSchemes) {
      const bool staggered = std::string(scheme) == "implicit-midpoint-collocation" ||
                             std::string(scheme) == "variational";
      std::vector<double> err;
      for (const int n : staggered ? std::vector<int>{6, 11} : std::vector<int>{11, 21}) {
        auto st = make_scheme(scheme, P, n, straight(P, n));
        const double dt = std::string(scheme) == "variational"
                              ? solvers::dynamics::auto_time_step(P, scheme, n)
                              : staggered ? 2e-3 : 2e-2;
        const Trace r = run(*st, dt, std::lround(2.5 / dt), [](int, double) { return 0.0; });
        const auto k = r.tip.size();
        err.push_back((0.5 * (r.tip[k - 1] + r.tip[k - 2]) - tip).norm());
        BOOST_TEST_MESSAGE("  " << scheme << " N = " << n << ": |tip - static| = " << err.back()
                           << " m, wall " << r.wall << " s");
      }
      const double order = std::log2(err[0] / err[1]);
      BOOST_TEST_MESSAGE("  observed order " << order);
      BOOST_TEST(order >= (staggered ? 1.8 : 0.8));
      BOOST_TEST(order <= (staggered ? 2.3 : 1.3));
    }
  }
}

BOOST_AUTO_TEST_CASE(ledger_closes_with_a_displacement_schedule) {
  // Reference: the energy balance. Gravity, viscosity 300 Pa s, the cable pulled in by
  // 0 -> 2 mm over 0.1 s and released to 1 mm at 0.2 s; N = 11, dt = 1 ms (variational: its
  // stable step), 0.4 s.
  // T + U + P + dissipated - work_in stays within 1 % of max |work_in| (the cable's work
  // -F dL/dt, which the prescribed shortening makes positive while it is pulled in), on the
  // staggered grid (the shooting schemes' balance is not exact in s, with any actuator:
  // docs/dynamics.md).
  const auto s = actuated_scene("{gravity: [-9.81, 0, 0]}",
                                cable("{ramp: [[0, 0], [0.1, 0.002], [0.2, 0.001]]}"), 300.0);
  const auto P = DynamicProblem::from_scene(s);
  for (const std::string scheme : {"implicit-midpoint-collocation", "variational"}) {
    auto st = make_scheme(scheme, P, 11, straight(P, 11));
    const double dt = scheme == "variational" ? step_of(scheme, P, 11) : 1e-3;
    const Trace r = run(*st, dt, std::lround(0.4 / dt), [](int, double) { return 0.0; });
    const double work = max_abs_work_in(r.energy);
    const double drift = ledger_drift(r.energy);
    BOOST_TEST_MESSAGE(scheme << ": max |work_in| " << work << " J, ledger drift " << drift
                       << " J = " << drift / work << " of it, wall " << r.wall << " s");
    BOOST_TEST(work > 1e-5);
    BOOST_TEST(drift <= 0.01 * work);
  }
}
