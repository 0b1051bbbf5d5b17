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
//   (e) |q| = 1 is kept (a quadratic invariant of the midpoint rule) and det R = 1;
//   (f) Kirchhoff rods (constraint forces, the constraint at the end of every step): the rod
//       settles to the Kirchhoff statics with variational's discretisation error, keeps
//       nu = nu* over a run, and follows `variational` to the time-discretisation error.
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
#include "rodlab/solvers/dynamics/semi_discrete/ida_reference.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/implicit_midpoint_collocation.hpp"
#include "rodlab/solvers/dynamics/variational/variational.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

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

}  // namespace

BOOST_AUTO_TEST_CASE(no_lower_time_step_bound) {
  // Reference: the requirement (implicit-midpoint, the thesis form, fails below ~6 ms at
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
  // exception, and the state stays at t.
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

}

namespace {

/// The Kirchhoff cantilever of test_variational's
/// `kirchhoff_settles_to_static_equilibrium_at_second_order`: gravity and strong laminar drag.
scene::Scene kirchhoff_scene() {
  return rod_scene(
      "{gravity: [-9.81, 0, 0], drag: {fluid_density: 1000, laminar: [0, 0, 0, 1.6e-3, 1.6e-3, 1.6e-3]}}",
      "{}", 0.0, "kirchhoff");
}

/// max_k |nu_k - nu*| (nu* = e3) over the segments of the stepper's last state.
double nu_deviation(const Stepper& s) {
  double worst = 0.0;
  for (const auto& c : s.centerline())
    worst = std::max(worst, (c.twist.tail<3>() - Vector3(0, 0, 1)).lpNorm<Eigen::Infinity>());
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_CASE(kirchhoff_settles_to_static_equilibrium) {
  // Reference: the Kirchhoff statics (chebyshev, N = 24, exact to 1e-13 m). Released straight
  // under gravity with laminar drag, N = 6 and 11, dt = 2 ms, 2.5 s: the static limit of the
  // midpoint rule is the semi-discrete equilibrium (f(y) = 0, c(y) = 0), the same as
  // variational's, so the tip errors are variational's (2.03e-5, 5.06e-6 m) to 2 %, and fall at
  // second order in ds. Over every run max |nu - nu*| <= 1e-10 (the constraint is solved at the
  // end of every step, the same tolerance as the rates).
  const auto s = kirchhoff_scene();
  const Vector3 tip = static_tip(s);
  const auto P = DynamicProblem::from_scene(s);
  const double dt = 2e-3;
  const long steps = 1250;
  std::vector<double> errors;
  for (const int n : {6, 11}) {
    auto c = collocation(P, n);
    double worst_nu = nu_deviation(*c);
    long iterations = 0;
    const auto start = std::chrono::steady_clock::now();
    for (long i = 0; i < steps; ++i) {
      const auto status = c->step(i * dt, dt);
      BOOST_REQUIRE_MESSAGE(status.ok, "step " << i << ": " << status.reason);
      iterations += status.iterations;
      worst_nu = std::max(worst_nu, nu_deviation(*c));
    }
    errors.push_back((c->tip_position() - tip).norm());
    BOOST_TEST_MESSAGE("kirchhoff N = " << n << ": |tip - static| = " << errors.back()
                       << " m (deflection " << tip.x() << " m), max |nu - nu*| over the run "
                       << worst_nu << ", " << double(iterations) / steps << " iterations/step, "
                       << c->jacobian_evaluations() << " Jacobians, wall "
                       << seconds_since(start) << " s");
    BOOST_TEST(worst_nu <= 1e-10);
  }
  BOOST_TEST(std::abs(errors[0] / 2.03e-5 - 1.0) <= 0.02);
  BOOST_TEST(std::abs(errors[1] / 5.06e-6 - 1.0) <= 0.02);
  const double order = std::log2(errors[0] / errors[1]);
  BOOST_TEST_MESSAGE("observed order " << order);
  BOOST_TEST(order > 1.8);
}

BOOST_AUTO_TEST_CASE(kirchhoff_follows_variational) {
  // Reference: `variational` (Kirchhoff, constraint forces by SHAKE) on the same grid, N = 11,
  // tip at t = 0.05 s of the release of kirchhoff_scene(); variational is first order in time,
  // so its Richardson extrapolation 2 v(dt/2) - v(dt) from dt = 1e-5, 5e-6 s is the reference
  // (checked against 2.5e-6 s: the extrapolations differ by 8.7e-11 m). Measured collocation tip
  // errors 2.59e-5, 1.09e-5, 2.30e-6, 3.05e-7, 1.82e-8, 3.43e-8 m at dt = 2, 1, 0.5, 0.25,
  // 0.125, 0.0625 ms: pre-asymptotic at the coarse steps (the release from straight excites the
  // grid's fast bending-rotation modes), then at the level of a ~3e-8 m floor (3e-6 of the
  // deflection). Asserted: at dt = 1, 0.5, 0.25 ms each error at least 3x below the previous,
  // and below 5e-7 m at 0.25 ms.
  const int nodes = 11;
  const double t_end = 0.05;
  const auto P = DynamicProblem::from_scene(kirchhoff_scene());
  std::vector<Vector3> v;
  for (const double dt : {1e-5, 5e-6}) {
    solvers::dynamics::VariationalOptions vo;
    vo.nodes = nodes;
    auto s = solvers::dynamics::make_variational(P, vo, straight(P, nodes));
    const long steps = std::lround(t_end / dt);
    for (long i = 0; i < steps; ++i) BOOST_REQUIRE(s->step(i * dt, dt).ok);
    v.push_back(s->tip_position());
  }
  const Vector3 ref = 2.0 * v[1] - v[0];
  BOOST_TEST_MESSAGE("variational N = 11 at t = 0.05 s: tip " << ref.transpose()
                     << " (extrapolated), error at dt = 5e-6 s " << (v[1] - ref).norm() << " m");
  std::vector<double> err;
  for (const int k : {50, 100, 200}) {
    const double dt = t_end / k;
    auto c = collocation(P, nodes, 1e-12);
    const Run r = run(*c, dt, k);
    err.push_back((c->tip_position() - ref).norm());
    BOOST_TEST_MESSAGE("  collocation dt = " << dt << ": tip error " << err.back() << " m, "
                       << double(r.iterations) / k << " iterations/step, wall " << r.wall
                       << " s, max |nu - nu*| " << nu_deviation(*c));
  }
  for (std::size_t i = 1; i < err.size(); ++i) {
    const double order = std::log2(err[i - 1] / err[i]);
    BOOST_TEST_MESSAGE("  observed order " << order);
    BOOST_TEST(err[i] * 3.0 <= err[i - 1]);
  }
  BOOST_TEST(err.back() < 5e-7);
}

namespace {

struct Trajectories {
  double max_tip_difference = 0.0;  ///< over every step, m
  long kept_jacobians = 0, exact_jacobians = 0, kept_iterations = 0, exact_iterations = 0;
};

/// `steps` steps of dt from rest with the default Jacobian policy (kept across steps with its
/// KLU factors) and with exact Newton (a fresh Jacobian at every iteration).
Trajectories kept_against_exact_newton(const DynamicProblem& P, int nodes, double dt,
                                       long steps) {
  ImplicitMidpointCollocationOptions kept;
  kept.nodes = nodes;
  ImplicitMidpointCollocationOptions exact = kept;
  exact.max_setup_calls = 1;
  exact.jacobian_max_age = 0;
  auto a = solvers::dynamics::make_implicit_midpoint_collocation(P, kept, straight(P, nodes));
  auto b = solvers::dynamics::make_implicit_midpoint_collocation(P, exact, straight(P, nodes));
  Trajectories r;
  for (long i = 0; i < steps; ++i) {
    const auto sa = a->step(i * dt, dt), sb = b->step(i * dt, dt);
    BOOST_REQUIRE_MESSAGE(sa.ok && sb.ok, "step " << i << ": " << sa.reason << sb.reason);
    r.kept_iterations += sa.iterations;
    r.exact_iterations += sb.iterations;
    const double d = (a->tip_position() - b->tip_position()).norm();
    if (d > 1e-10 && r.max_tip_difference <= 1e-10)
      BOOST_TEST_MESSAGE("first departure at step " << i << ": " << d << " m, iterations "
                                                     << sa.iterations << " / " << sb.iterations);
    r.max_tip_difference = std::max(r.max_tip_difference, d);
  }
  r.kept_jacobians = a->jacobian_evaluations();
  r.exact_jacobians = b->jacobian_evaluations();
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(kept_jacobian_leaves_the_solution_unchanged) {
  // Reference: the same scheme with exact Newton (jacobian_max_age = 0, max_setup_calls = 1: a
  // fresh finite-difference Jacobian, factorised afresh, at every iteration). Both stop at the
  // same scaled residual (tol = 1e-10), so their steps differ by the Newton tolerance only, not
  // by the Jacobian policy or by the kept KLU factors: the tip trajectories agree to 1e-10 m at
  // every step. Cases: the viscous cantilever at N = 20, 300 steps of 1 ms (the Jacobian kept
  // for many steps) and 100 steps of 10 ms (modified Newton needs ~10 iterations), at N = 100,
  // 50 steps of 2 ms, and the Kirchhoff cantilever (constraint forces), N = 20, 300 steps of
  // 1 ms. The kept runs must have reused (under a third of the exact runs' Jacobians; a quarter
  // until session 17, when the analytic Jacobian made exact Newton itself faster: 3.98 -> 3.57
  // iterations per step at 10 ms, while the kept run's 90 -> 94 Jacobians stayed), the exact
  // runs not (one Jacobian per iteration). Not at dt: auto (22.6 ms): there exact Newton
  // with the line search fails in step 26 and the step is split (28 iterations), so the two runs
  // no longer share a time grid (their tips then differ by 4e-4 m, the time error).
  struct Case {
    const char* name;
    scene::Scene scene;
    int nodes;
    double dt;
    long steps;
  };
  const Case cases[] = {{"viscous N = 20, 1 ms", cantilever(300.0), 20, 1e-3, 300},
                        {"viscous N = 20, 10 ms", cantilever(300.0), 20, 1e-2, 100},
                        {"viscous N = 100, 2 ms", cantilever(300.0), 100, 2e-3, 50},
                        {"kirchhoff N = 20, 1 ms", kirchhoff_scene(), 20, 1e-3, 300}};
  for (const Case& c : cases) {
    const auto P = DynamicProblem::from_scene(c.scene);
    const Trajectories r = kept_against_exact_newton(P, c.nodes, c.dt, c.steps);
    BOOST_TEST_MESSAGE(c.name << ": max tip difference " << r.max_tip_difference
                              << " m; Jacobians kept " << r.kept_jacobians << " / exact "
                              << r.exact_jacobians << ", iterations per step "
                              << double(r.kept_iterations) / c.steps << " / "
                              << double(r.exact_iterations) / c.steps);
    BOOST_TEST(r.max_tip_difference <= 1e-10, c.name);
    BOOST_TEST(r.exact_jacobians >= r.exact_iterations, c.name);
    BOOST_TEST(3 * r.kept_jacobians < r.exact_jacobians, c.name);
  }
}

BOOST_AUTO_TEST_CASE(condensed_linear_solver_matches_klu) {
  // Reference: the same scheme with KLU on the whole Newton matrix (linear_solver = klu). The
  // default condenses the pose rows and solves the 6 x 6 block-tridiagonal Schur system by block
  // LU (kinsol_solver.hpp NewtonLinearSolver): the same Newton iterates to rounding, so the tip
  // trajectories agree far below the Newton tolerance (1e-10), and the iterations are as many
  // (rounding decides a few steps' last iteration: measured 0.96 - 1.00 of KLU's).
  // Cases: the viscous cantilever at N = 20 at dt: auto (22.6 ms, ~10 modified-Newton
  // iterations per step), 1 ms and 50 ms (steps split into halves), N = 100 at 2 ms, and the
  // undamped cantilever at N = 10, 10 ms.
  struct Case {
    const char* name;
    double viscosity;
    int nodes;
    double dt;
    long steps;
  };
  const Case cases[] = {{"viscous N = 20, 22.6 ms", 300.0, 20, 2.26e-2, 40},
                        {"viscous N = 20, 1 ms", 300.0, 20, 1e-3, 300},
                        {"viscous N = 20, 50 ms", 300.0, 20, 5e-2, 20},
                        {"viscous N = 100, 2 ms", 300.0, 100, 2e-3, 50},
                        {"undamped N = 10, 10 ms", 0.0, 10, 1e-2, 100}};
  for (const Case& c : cases) {
    const auto P = DynamicProblem::from_scene(cantilever(c.viscosity));
    ImplicitMidpointCollocationOptions o;
    o.nodes = c.nodes;
    const auto g0 = straight(P, c.nodes);
    auto condensed = solvers::dynamics::make_implicit_midpoint_collocation(P, o, g0);
    o.linear_solver = solvers::NewtonLinearSolver::klu;
    auto klu = solvers::dynamics::make_implicit_midpoint_collocation(P, o, g0);
    double worst = 0.0;
    long iterations_condensed = 0, iterations_klu = 0;
    for (long i = 0; i < c.steps; ++i) {
      const auto a = condensed->step(i * c.dt, c.dt);
      const auto b = klu->step(i * c.dt, c.dt);
      BOOST_REQUIRE_MESSAGE(a.ok && b.ok, c.name << ", step " << i << ": " << a.reason << b.reason);
      iterations_condensed += a.iterations, iterations_klu += b.iterations;
      worst = std::max(worst, (condensed->tip_position() - klu->tip_position()).norm());
    }
    BOOST_TEST_MESSAGE(c.name << ": max tip difference " << worst << " m; iterations "
                              << iterations_condensed << " (condensed), " << iterations_klu
                              << " (KLU)");
    BOOST_TEST(worst <= 1e-12, c.name);
    BOOST_TEST(iterations_condensed <= 1.05 * iterations_klu, c.name);
  }
}

BOOST_AUTO_TEST_CASE(failure_after_kept_steps_is_reported_and_leaves_no_trace) {
  // A step that KINSOL cannot solve (50 s on the undamped cantilever, N = 10, even split into
  // 2^6 substeps) after 20 steps of 1 ms that kept the Jacobian and its KLU factors: a failed
  // StepStatus naming KINSOL's flag (the CLI's exit 1), the state left at t. Then 20 more steps
  // of 1 ms: the same tip, to 1e-10 m (the Newton tolerance), as a run that never tried the
  // large step (the failure left no stale Jacobian, factors or predictor history behind).
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  auto c = collocation(P, 10);
  auto clean = collocation(P, 10);
  const double dt = 1e-3;
  for (int i = 0; i < 20; ++i) {
    BOOST_REQUIRE(c->step(i * dt, dt).ok);
    BOOST_REQUIRE(clean->step(i * dt, dt).ok);
  }
  const Vector3 tip = c->tip_position();
  const double t = 20 * dt;
  const auto failed = c->step(t, 50.0);
  BOOST_TEST_MESSAGE("50 s step: " << failed.reason << " (" << failed.iterations
                     << " iterations)");
  BOOST_TEST(!failed.ok);
  BOOST_TEST(failed.reason.find("KIN_") != std::string::npos, failed.reason);
  BOOST_TEST((c->tip_position() - tip).norm() == 0.0);
  double worst = 0.0;
  for (int i = 20; i < 40; ++i) {
    BOOST_REQUIRE(c->step(i * dt, dt).ok);
    BOOST_REQUIRE(clean->step(i * dt, dt).ok);
    worst = std::max(worst, (c->tip_position() - clean->tip_position()).norm());
  }
  BOOST_TEST_MESSAGE("after the failure: max tip difference to the clean run " << worst << " m");
  BOOST_TEST(worst <= 1e-10);
}
