#define BOOST_TEST_MODULE implicit_midpoint_collocation
#include <boost/test/unit_test.hpp>

// `implicit-midpoint-collocation` (implicit midpoint in time on the semi-discrete rod of `ida`,
// each step solved globally by KINSOL + KLU; implicit_midpoint_collocation.hpp) on the cantilever
// of scenes/viscous-cantilever.yaml (thesis Table 2.1 rod: L = 0.1 m, circle D = 0.01 m,
// E = 1e6 Pa, G = 0.33e6 Pa, rho = 1000 kg/m^3, viscosity 300 Pa s, gravity [-9.81, 0, 0] m/s^2),
// released straight from rest:
//   (a) no lower time-step bound: N = 20 and N = 100 converge for dt = 1e-1 ... 1e-6 s;
//   (b) second order in dt against `ida` at the same N (the two share the semi-discretisation);
//   (c) undamped: no secular energy drift (the midpoint rule is symmetric);
//   (d) damped: the ledger T + U + P + dissipated - work_in is constant to the time error;
//   (e) |q| = 1 is kept (a quadratic invariant of the midpoint rule) and det R = 1.
// Measured numbers: see each case's comment and the messages (--log_level=message).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "dynamics_support.hpp"
#include "rodlab/rod/energies.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/ida_reference.hpp"
#include "rodlab/solvers/dynamics/implicit_midpoint_collocation.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::Energy;
using solvers::dynamics::IdaOptions;
using solvers::dynamics::ImplicitMidpointCollocationOptions;
using solvers::dynamics::RestState;
using solvers::dynamics::Stepper;
using lie::SE3;
using lie::Vector3;

std::unique_ptr<solvers::dynamics::ImplicitMidpointCollocationStepper> collocation(
    const DynamicProblem& P, int nodes, double tol = 1e-10) {
  ImplicitMidpointCollocationOptions o;
  o.nodes = nodes;
  o.tol = tol;
  return solvers::dynamics::make_implicit_midpoint_collocation(P, o, straight(P, nodes));
}

struct Run {
  std::vector<Energy> energy;  ///< after every step, the initial state first
  long iterations = 0;
  double wall = 0.0;
};

/// `steps` steps of dt from t = 0, every one required to converge.
Run run(Stepper& stepper, double dt, long steps) {
  Run r;
  r.energy.push_back(stepper.energy());
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    const auto status = stepper.step(i * dt, dt);
    BOOST_REQUIRE_MESSAGE(status.ok, "step " << i << " of dt = " << dt << ": " << status.reason);
    r.iterations += status.iterations;
    r.energy.push_back(stepper.energy());
  }
  r.wall = seconds_since(start);
  return r;
}

double max_abs_gravity(const std::vector<Energy>& e) {
  double m = 0.0;
  for (const auto& x : e) m = std::max(m, std::abs(x.gravity));
  return m;
}

double ledger_drift(const std::vector<Energy>& e) {
  double d = 0.0;
  for (const auto& x : e) d = std::max(d, std::abs(x.total() - e.front().total()));
  return d;
}

}  // namespace

BOOST_AUTO_TEST_CASE(no_lower_time_step_bound) {
  // Reference: the issue's requirement (implicit-midpoint, the thesis form, fails below ~6 ms at
  // N = 20; docs/dynamics.md). Every step of every dt from 1e-1 to 1e-6 s converges (KINSOL to
  // the default tolerance), at N = 20 and N = 100, and the ledger stays closed to 2e-3 of
  // max |P| (the midpoint rule's O(dt^2) ledger error: measured 1.22e-3 at dt = 1e-2 over
  // 0.1 s, 6.7e-8 at 1e-3). Larger steps must complete too (0.1 s only by splitting steps that
  // KINSOL cannot solve: KIN_MXNEWT_5X_EXCEEDED at the fourth step without splitting); their
  // accuracy is reported, not asserted: the ledger is off by 2.0 and 0.023 of max |P| at 0.05
  // and 0.02 s, too coarse a step to be accurate.
  for (const int nodes : {20, 100}) {
    const auto P = DynamicProblem::from_scene(cantilever(300.0));
    for (const double dt : {1e-1, 5e-2, 2e-2, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
      const long steps = dt >= 1e-2 ? 10 : 4;
      auto stepper = collocation(P, nodes);
      std::vector<Energy> e{stepper->energy()};
      long iterations = 0, done = 0;
      std::string reason;
      const auto start = std::chrono::steady_clock::now();
      for (; done < steps; ++done) {
        const auto status = stepper->step(done * dt, dt);
        iterations += status.iterations;
        if (!status.ok) {
          reason = status.reason;
          break;
        }
        e.push_back(stepper->energy());
      }
      const double wall = seconds_since(start);
      const double scale = std::max(max_abs_gravity(e), 1e-300);
      BOOST_TEST_MESSAGE("N = " << nodes << ", dt = " << dt << ": " << done << "/" << steps
                         << " steps, " << double(iterations) / std::max(1L, done)
                         << " iterations/step, " << stepper->jacobian_evaluations()
                         << " Jacobians, " << 1e3 * wall / std::max(1L, done)
                         << " ms/step, ledger drift " << ledger_drift(e) / scale << " of max |P|"
                         << (reason.empty() ? "" : "; failed: " + reason));
      BOOST_TEST(reason.empty(), reason);
      if (dt > 1e-2) continue;  // accuracy measured only (docs/dynamics.md)
      BOOST_TEST(ledger_drift(e) <= 2e-3 * scale);
      BOOST_TEST(stepper->tip_position().allFinite());
    }
  }
}

BOOST_AUTO_TEST_CASE(second_order_against_ida) {
  // Reference: `ida` at rtol = atol = 1e-12 on the same semi-discrete system (N = 20) is the
  // time-exact solution; the tip error of the midpoint rule at t = 0.05 s for dt = 0.05 / 16,
  // / 32, / 64 falls at the observed order log2(e1 / e2) in [1.8, 2.2].
  const int nodes = 20;
  const double t_end = 0.05;
  const auto P = DynamicProblem::from_scene(cantilever(300.0));
  auto start = std::chrono::steady_clock::now();
  IdaOptions io{nodes};
  io.rtol = io.atol = 1e-12;
  auto ida = solvers::dynamics::make_ida(P, io, straight(P, nodes));
  BOOST_REQUIRE(ida->step(0.0, t_end).ok);
  const Vector3 tip_ida = ida->tip_position();
  BOOST_TEST_MESSAGE("ida N = 20 to 0.05 s: tip " << tip_ida.transpose() << ", wall "
                     << seconds_since(start) << " s");
  std::vector<double> err;
  for (const int k : {16, 32, 64}) {
    const double dt = t_end / k;
    auto c = collocation(P, nodes, 1e-12);
    const Run r = run(*c, dt, k);
    err.push_back((c->tip_position() - tip_ida).norm());
    BOOST_TEST_MESSAGE("  dt = " << dt << ": tip error " << err.back() << " m, "
                       << double(r.iterations) / k << " iterations/step, wall " << r.wall << " s");
  }
  for (std::size_t i = 1; i < err.size(); ++i) {
    const double order = std::log2(err[i - 1] / err[i]);
    BOOST_TEST_MESSAGE("  observed order " << order);
    BOOST_TEST(order >= 1.8);
    BOOST_TEST(order <= 2.2);
  }
}

BOOST_AUTO_TEST_CASE(undamped_energy_has_no_secular_drift) {
  // Reference: the midpoint rule is symmetric (time-reversible), so on the undamped rod the
  // energy error oscillates without a secular trend. Undamped cantilever under gravity, N = 20,
  // dt = 2 ms, 4 s (about 18 periods of the first mode): the largest |E - E0| in the second
  // half is at most 1.5 times that of the first half (a linear drift would double it), and
  // below 1e-3 of max |P|.
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  auto c = collocation(P, 20);
  const double dt = 2e-3;
  const long steps = 2000;
  const Run r = run(*c, dt, steps);
  const double scale = max_abs_gravity(r.energy), e0 = r.energy.front().mechanical();
  double first = 0.0, second = 0.0;
  for (long i = 0; i <= steps; ++i) {
    const double d = std::abs(r.energy[i].mechanical() - e0);
    (i <= steps / 2 ? first : second) = std::max(i <= steps / 2 ? first : second, d);
  }
  BOOST_TEST_MESSAGE("undamped N = 20, dt = 2 ms, 4 s: max |P| = " << scale << " J, max |E - E0| "
                     << first / scale << " (first half), " << second / scale
                     << " (second half) of max |P|; " << double(r.iterations) / steps
                     << " iterations/step, " << c->jacobian_evaluations() << " Jacobians, wall "
                     << r.wall << " s");
  BOOST_TEST(scale > 1e-4);
  BOOST_TEST(second <= 1.5 * first);
  BOOST_TEST(second <= 1e-3 * scale);
  BOOST_TEST(r.energy.back().dissipated == 0.0);
  BOOST_TEST(r.energy.back().work_in == 0.0);
}

BOOST_AUTO_TEST_CASE(damped_ledger_closes) {
  // Reference: the semi-discrete ledger T + U + P + dissipated - work_in = const; the midpoint
  // rule keeps it to its O(dt^2) time error. Viscous cantilever, N = 20, dt = 1 ms, 1 s:
  // drift within 1e-5 of max |P|, and T + U + P decreasing overall (dissipated > 5 % of max |P|).
  const auto P = DynamicProblem::from_scene(cantilever(300.0));
  auto c = collocation(P, 20);
  const Run r = run(*c, 1e-3, 1000);
  const double scale = max_abs_gravity(r.energy), drift = ledger_drift(r.energy);
  BOOST_TEST_MESSAGE("damped N = 20, dt = 1 ms, 1 s: dissipated " << r.energy.back().dissipated
                     << " J, ledger drift " << drift << " J (" << drift / scale
                     << " of max |P|), " << double(r.iterations) / 1000 << " iterations/step, "
                     << c->jacobian_evaluations() << " Jacobians, wall " << r.wall << " s");
  BOOST_TEST(r.energy.back().dissipated > 0.05 * scale);
  BOOST_TEST(drift <= 1e-5 * scale);
}

BOOST_AUTO_TEST_CASE(unit_quaternions_are_kept) {
  // Reference: |q|^2 is a quadratic invariant of q_dot = q (x) [0; psi] / 2, which the midpoint
  // rule conserves exactly; the solver residual (1e-10, a rate scaled by omega_1) leaves
  // |q| - 1 at the 1e-12 level over 1000 steps. det R is formed from the normalised q:
  // |det R - 1| <= 1e-12.
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  auto c = collocation(P, 20);
  run(*c, 1e-3, 1000);
  BOOST_TEST_MESSAGE("after 1000 steps of 1 ms: max ||q| - 1| = "
                     << c->max_quaternion_norm_deviation() << ", max |det R - 1| = "
                     << c->max_det_deviation());
  BOOST_TEST(c->max_quaternion_norm_deviation() <= 1e-10);
  BOOST_TEST(c->max_det_deviation() <= 1e-12);
}

BOOST_AUTO_TEST_CASE(failures_are_reported) {
  // Too few iterations for a large step: a failed StepStatus naming KINSOL's flag, not an
  // exception, and the state stays at t. Kirchhoff rods are rejected.
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  ImplicitMidpointCollocationOptions o;
  o.nodes = 10;
  o.max_iterations = 1;
  auto c = solvers::dynamics::make_implicit_midpoint_collocation(P, o, straight(P, 10));
  const Vector3 tip0 = c->tip_position();
  const auto status = c->step(0.0, 0.5);
  BOOST_TEST(!status.ok);
  BOOST_TEST(status.reason.find("KIN_") != std::string::npos, status.reason);
  BOOST_TEST((c->tip_position() - tip0).norm() == 0.0);

  const auto K = DynamicProblem::from_scene(io::load_scene_from_string(R"(schema: rodlab.scene/1
rod:
  length: 0.1
  model: kirchhoff
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000}
tip:
  free: {}
)",
                                                                       "kirchhoff.yaml"));
  BOOST_CHECK_THROW(solvers::dynamics::make_implicit_midpoint_collocation(
                        K, ImplicitMidpointCollocationOptions{}, straight(K, 20)),
                    std::invalid_argument);
}
