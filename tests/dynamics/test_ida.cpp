#define BOOST_TEST_MODULE ida
#include <boost/test/unit_test.hpp>

// The `ida` dynamics reference (method of lines + SUNDIALS IDA/KLU, ida_reference.hpp) on the
// cantilever of scenes/viscous-cantilever.yaml (thesis Table 2.1 rod: L = 0.1 m, circle
// D = 0.01 m, E = 1e6 Pa, G = 0.33e6 Pa, rho = 1000 kg/m^3, gravity [-9.81, 0, 0] m/s^2),
// released straight from rest, N = 10 nodes, rtol = atol = 1e-10, output every 1 ms:
//   (1) undamped: the semi-discrete energy T + U + P is conserved exactly, so its drift is
//       IDA's integration error (tolerance 1e-7 of max |P|);
//   (2) `variational` at the same N converges to `ida` as dt -> 0 (the two share the spatial
//       discretisation): the tip difference at t = 0.05 s falls at second order in dt with the
//       default Stormer-Verlet start, at first order with the thesis' symplectic Euler;
//   (3) Kelvin-Voigt damping (viscosity 300 Pa s): T + U + P never increases (1e-12 J) and
//       T + U + P + dissipated - work_in is conserved (1e-6 of max |P|);
//   (4) every load and actuator at once: the ledger balance still holds.
// Measured (Release, 2-core VM): (1) drift 4.5e-11 relative, 0.4 s; (2) symplectic Euler
// 4.96e-6 and 2.48e-6 m, ratio 2.000 (gravity), Stormer-Verlet 8.7e-10 and 2.1e-10 m; (3) largest
// rise -1.5e-11 J, ledger drift 8.6e-9, 0.5 s; (4) ledger drift 1.1e-10, 0.1 s.

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
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/dynamics/variational/variational.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::Energy;
using solvers::dynamics::IdaOptions;
using solvers::dynamics::RestState;
using solvers::dynamics::Stepper;
using lie::SE3;
using lie::Vector3;

constexpr int kNodes = 10;

/// Every load and actuator the dynamics support, ramped up over 0.05 s: Kelvin-Voigt (30 Pa s),
/// laminar and turbulent drag, a world distributed force, a body tip wrench, and a cable pulled
/// from outside at s0 = 0.03 m (its entry load goes to node 3 at N = 10).
scene::Scene all_loads() {
  return io::load_scene_from_string(R"(schema: rodlab.scene/1
name: ida-all-loads
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 30}
tip:
  free:
    wrench:
      force: {ramp: [[0, [0, 0, 0]], [0.05, [0.02, 0.01, 0]]]}
      moment: {ramp: [[0, [0, 0, 0]], [0.05, [0, 0.001, 0]]]}
      frame: body
loads:
  gravity: [-9.81, 0, 0]
  drag: {fluid_density: 1000, laminar: [1e-8, 1e-8, 1e-8, 1e-3, 1e-3, 1e-3],
         turbulent: [0, 0, 0, 0.01, 0.01, 0.01]}
  distributed: {force: {ramp: [[0, [0, 0, 0]], [0.05, [0, 0.5, 0]]]}, frame: world}
actuators:
  - cable: {offset: [0.003, 0], tension: {ramp: [[0, 0], [0.05, 0.3]]}, span: [0.03, 0.1]}
)",
                                    "ida-all-loads.yaml");
}

/// Runs `stepper` to t_end in steps of dt (run_steps), the energy after every step.
std::vector<Energy> run(Stepper& stepper, double dt, double t_end) {
  return run_steps(stepper, dt, std::lround(t_end / dt)).energy;
}

}  // namespace

BOOST_AUTO_TEST_CASE(undamped_release_conserves_energy) {
  // Reference: exact conservation of the semi-discrete energy (no dissipation, no input), so
  // the drift is IDA's global error; tolerance 1e-7 of max |gravity energy| over 0.2 s.
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  const auto start = std::chrono::steady_clock::now();
  auto ida = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, straight(P, kNodes));
  const auto e = run(*ida, 1e-3, 0.2);
  const double wall = seconds_since(start);
  const double scale = max_abs_gravity(e), drift = ledger_drift(e);
  double ledger = 0.0;
  for (const auto& x : e) ledger = std::max({ledger, std::abs(x.dissipated), std::abs(x.work_in)});
  BOOST_TEST_MESSAGE("undamped, N = 10, 0.2 s: max |P| = " << scale << " J, energy drift "
                     << drift << " J (" << drift / scale << " relative), wall " << wall << " s");
  BOOST_TEST(scale > 1e-4);  // the rod did swing
  BOOST_TEST(drift <= 1e-7 * scale);
  BOOST_TEST(ledger == 0.0);
  BOOST_TEST(ida->max_det_deviation() <= 1e-14);
}

BOOST_AUTO_TEST_CASE(variational_converges_to_ida) {
  // Reference: `ida` at rtol = atol = 1e-10 is the time-exact solution of the semi-discrete
  // system that `variational` discretises in time. The tip difference at t = 0.05 s, from dt =
  // 2e-5 to 1e-5 s: with the thesis' symplectic Euler it halves (first order; ratio in [1.7,
  // 2.3], measured 2.000 for gravity alone) and is below 1e-4 L at 1e-5 s; with the default
  // Stormer-Verlet start (and its trapezoidal damping) the observed order is 2.0 +- 0.1
  // (measured 2.025 gravity, 2.000 all loads) and the difference below 1e-8 L (measured 2.1e-10
  // and 1.7e-10 m). The loaded scene checks that the two schemes apply the same forces (viscosity,
  // drag, distributed, tip, cable and its entry load) and that the damping is second order too.
  using solvers::dynamics::VariationalStep;
  for (const bool loaded : {false, true}) {
    const auto P = DynamicProblem::from_scene(loaded ? all_loads() : cantilever(0.0));
    const auto g0 = straight(P, kNodes);
    const double t_end = 0.05;
    auto start = std::chrono::steady_clock::now();
    auto ida = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, g0);
    run(*ida, 1e-3, t_end);
    const Vector3 tip_ida = ida->tip_position();
    BOOST_TEST_MESSAGE((loaded ? "all loads" : "gravity") << ": ida to 0.05 s: wall "
                       << seconds_since(start) << " s");
    for (const auto rule : {VariationalStep::symplectic_euler, VariationalStep::verlet}) {
      const bool verlet = rule == VariationalStep::verlet;
      std::vector<double> diff;
      for (double dt : {2e-5, 1e-5}) {
        start = std::chrono::steady_clock::now();
        solvers::dynamics::VariationalOptions options{kNodes, 1e-12, 20};
        options.step = rule;
        auto var = solvers::dynamics::make_variational(P, options, g0);
        run(*var, dt, t_end);
        diff.push_back((var->tip_position() - tip_ida).norm());
        BOOST_TEST_MESSAGE("  variational (" << variational_step_name(rule) << ") dt = " << dt
                           << ": tip difference " << diff.back() << " m, wall "
                           << seconds_since(start) << " s");
      }
      const double order = std::log2(diff[0] / diff[1]);
      BOOST_TEST_MESSAGE("  observed order (dt = 2e-5 / 1e-5): " << order);
      if (verlet) {
        BOOST_TEST(std::abs(order - 2.0) <= 0.1);
        BOOST_TEST(diff[1] <= 1e-8 * P.length());
      } else {
        BOOST_TEST(order >= std::log2(1.7));
        BOOST_TEST(order <= std::log2(2.3));
        BOOST_TEST(diff[1] <= 1e-4 * P.length());
      }
    }
  }
}

BOOST_AUTO_TEST_CASE(damped_release_dissipates_and_balances) {
  // Reference: dE/dt = -(viscous power) <= 0 for E = T + U + P, and the ledger identity
  // T + U + P + dissipated - work_in = const of the semi-discrete system. Tolerances: E never
  // grows by more than 1e-12 J between outputs (1 ms); the ledger total stays within 1e-6 of
  // max |P| over 1 s (4.4 periods of the first bending mode, damping ratio ~1 %, so about a
  // tenth of max |P| is dissipated: asserted > 5 %).
  const auto P = DynamicProblem::from_scene(cantilever(300.0));
  const auto start = std::chrono::steady_clock::now();
  auto ida = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, straight(P, kNodes));
  const auto e = run(*ida, 1e-3, 1.0);
  const double wall = seconds_since(start);
  const double scale = max_abs_gravity(e), drift = ledger_drift(e);
  double max_rise = -1e300;
  for (std::size_t i = 1; i < e.size(); ++i)
    max_rise = std::max(max_rise, e[i].mechanical() - e[i - 1].mechanical());
  BOOST_TEST_MESSAGE("damped, N = 10, 1 s: max |P| = " << scale << " J, dissipated "
                     << e.back().dissipated << " J, largest rise of T + U + P " << max_rise
                     << " J, ledger drift " << drift << " J (" << drift / scale
                     << " relative), wall " << wall << " s");
  BOOST_TEST(e.back().dissipated > 0.05 * scale);
  BOOST_TEST(max_rise <= 1e-12);
  BOOST_TEST(drift <= 1e-6 * scale);
  BOOST_TEST(e.back().work_in == 0.0);
}

BOOST_AUTO_TEST_CASE(every_input_and_loss_is_in_the_ledger) {
  // Reference: the semi-discrete balance T + U + P + dissipated - work_in = const holds for every
  // load, so a missing or wrong power term (viscous, drag, distributed, tip, actuator, cable
  // entry) shows as drift. Tolerance: 1e-6 of max(|work_in|, |P|) over 0.1 s.
  const auto P = DynamicProblem::from_scene(all_loads());
  BOOST_REQUIRE(P.has_drag() && P.has_actuators() && P.entry_nodes(10).size() == 1);
  const auto start = std::chrono::steady_clock::now();
  auto ida = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, straight(P, kNodes));
  const auto e = run(*ida, 1e-3, 0.1);
  const double wall = seconds_since(start);
  const double scale = std::max(max_abs_gravity(e), max_abs_work_in(e));
  const double drift = ledger_drift(e);
  BOOST_TEST_MESSAGE("all loads, N = 10, 0.1 s: work_in " << e.back().work_in << " J, dissipated "
                     << e.back().dissipated << " J, ledger drift " << drift << " J ("
                     << drift / scale << " relative), wall " << wall << " s");
  BOOST_TEST(e.back().work_in > 0.0);
  BOOST_TEST(e.back().dissipated > 0.0);
  BOOST_TEST(drift <= 1e-6 * scale);
}

BOOST_AUTO_TEST_CASE(restart_off_the_current_time) {
  // A step whose t is not the time reached restarts IDA there (an ODE: y' = f(t, y)). Reference:
  // two runs of the undamped cantilever to 0.02 s, one with a restart at 0.01 s (the second
  // half called from t = 0.01 + 1e-9, a shift the gravity scene does not feel); tip positions
  // agree to 1e-8 m (the integration tolerance times a few restarts' worth of error).
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  const auto g0 = straight(P, kNodes);
  auto a = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, g0);
  auto b = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, g0);
  BOOST_REQUIRE(a->step(0.0, 0.02).ok);
  BOOST_REQUIRE(b->step(0.0, 0.01).ok);
  BOOST_REQUIRE(b->step(0.01 + 1e-9, 0.01 - 1e-9).ok);
  const double d = (a->tip_position() - b->tip_position()).norm();
  BOOST_TEST_MESSAGE("restart: tip difference " << d << " m");
  BOOST_TEST(d <= 1e-8);
}

BOOST_AUTO_TEST_CASE(failures_are_reported) {
  // Too few internal steps: a failed StepStatus naming IDA's flag, not an exception.
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  IdaOptions few{kNodes};
  few.max_steps = 10;
  auto ida = solvers::dynamics::make_ida(P, few, straight(P, kNodes));
  const auto status = ida->step(0.0, 0.1);
  BOOST_TEST(!status.ok);
  BOOST_TEST(status.reason.find("IDA_TOO_MUCH_WORK") != std::string::npos, status.reason);
}

// A stiff rod (#13 item 2): the steel guidewire of docs/dynamics.md "ida on stiff rods" (E =
// 200 GPa, G = 80 GPa, rho = 7800, D = 1 mm, L = 0.3 m, gravity, released straight), N = 12, one
// step of 5 ms. The release excites the rotation-shear mode sqrt(G A / rho I) = 2 MHz above the
// tolerances, which IDA resolves (about 3.3e7 internal steps per second of simulated time):
// (a) a fixed budget of 100 000 internal steps per step() (the old default) stops with
// IDA_TOO_MUCH_WORK before 5 ms, and the failure reports where IDA stopped (inside the step);
// (b) the budget that scales with the interval and the rod's highest frequency reaches 5 ms;
// (c) its tip agrees with implicit-midpoint-collocation at dt = 50 us (second order in dt;
// measured difference 8e-9 m of a 1.1e-4 m deflection) to 5e-8 m.
BOOST_AUTO_TEST_CASE(stiff_steel_wire_reaches_the_end_of_a_long_step) {
  const auto s = io::load_scene_from_string(R"(schema: rodlab.scene/1
name: steel-guidewire
rod:
  length: 0.3
  section: {shape: circle, diameter: 0.001}
  material: {E: 200.0e9, G: 80.0e9, rho: 7800}
tip:
  free: {}
loads:
  gravity: [-9.81, 0, 0]
)", "steel-guidewire.yaml");
  const auto P = DynamicProblem::from_scene(s);
  constexpr int n = 12;
  constexpr double dt = 5e-3;
  {
    IdaOptions fixed{n};
    fixed.max_steps = 100000;
    auto ida = solvers::dynamics::make_ida(P, fixed, straight(P, n));
    const auto status = ida->step(0.0, dt);
    BOOST_TEST(!status.ok);
    BOOST_TEST(status.reason.find("IDA_TOO_MUCH_WORK") != std::string::npos, status.reason);
    BOOST_TEST((status.reached > 0.0 && status.reached < dt), status.reached);
  }
  solvers::dynamics::DynamicSolveOptions o;
  o.nodes = n;
  o.dt = dt;
  o.t_end = dt;
  o.scheme = "ida";
  const auto r = solvers::dynamics::solve_dynamic(s, o);
  BOOST_REQUIRE_MESSAGE(r.converged, r.reason);
  BOOST_TEST(r.t.back() == dt);
  o.scheme = "implicit-midpoint-collocation";
  o.dt = 5e-5;
  const auto c = solvers::dynamics::solve_dynamic(s, o);
  BOOST_REQUIRE_MESSAGE(c.converged, c.reason);
  const double diff = (r.tip_position.back() - c.tip_position.back()).norm();
  BOOST_TEST_MESSAGE("steel wire, one 5 ms step: ida tip " << r.tip_position.back().transpose()
                     << ", collocation " << c.tip_position.back().transpose() << ", |diff| "
                     << diff << " m, ida wall " << r.wall_time_s << " s");
  BOOST_TEST(diff < 5e-8);
  BOOST_TEST(std::abs(r.tip_position.back().x()) > 1e-4);  // the wire has sagged
}

BOOST_AUTO_TEST_CASE(wall_time_guard_stops_a_run) {
  // --max-wall-time: a run that needs far longer stops, not converged, naming the limit, within
  // about one chunk of internal steps (ida) or one step (the others) past it.
  const auto P = DynamicProblem::from_scene(cantilever(0.0));
  solvers::dynamics::DynamicSolveOptions o;
  o.scheme = "variational";
  o.nodes = 20;
  o.dt = solvers::dynamics::auto_time_step(P, "variational", 20);
  o.t_end = 1e6 * o.dt;
  o.max_wall_time = 0.05;
  const auto start = std::chrono::steady_clock::now();
  const auto r = solvers::dynamics::solve_dynamic(cantilever(0.0), o);
  const double wall = seconds_since(start);
  BOOST_TEST(!r.converged);
  BOOST_TEST(r.reason.find("wall-time limit of 0.05 s") != std::string::npos, r.reason);
  BOOST_TEST(wall < 2.0);
  BOOST_TEST(r.t.back() < o.t_end);
}

BOOST_AUTO_TEST_CASE(condensed_linear_solver_matches_klu) {
  // Reference: the same integration with KLU on the whole Newton matrix (linear_solver = klu).
  // The default condenses the node blocks' pose rows, solves the 6 x 6 block-tridiagonal Schur
  // system by block LU and the two ledger rows by forward substitution
  // (newton_linear_solver.hpp): the same Newton iterates to rounding, which IDA's step-size
  // choices may turn into differences of its tolerance (rtol = atol = 1e-10), not more. Cases:
  // the viscous cantilever N = 20 and N = 50, and every load of all_loads() at N = 10 (a cable
  // pulled from outside and tip wrenches: no actuator unknowns, so the condensed solver runs),
  // 0.1 s in steps of 5 ms; ledger rows compared too. Measured: tips 5.7e-12 .. 1.7e-11 m,
  // ledgers 3.9e-10 .. 1.1e-8 of max |gravity energy|.
  struct Case {
    const char* name;
    scene::Scene scene;
    int nodes;
  };
  const Case cases[] = {{"viscous N = 20", cantilever(300.0), 20},
                        {"viscous N = 50", cantilever(300.0), 50},
                        {"all loads N = 10", all_loads(), 10}};
  for (const Case& c : cases) {
    const auto P = DynamicProblem::from_scene(c.scene);
    IdaOptions o{c.nodes};
    auto condensed = solvers::dynamics::make_ida(P, o, straight(P, c.nodes));
    o.linear_solver = solvers::NewtonLinearSolver::klu;
    auto klu = solvers::dynamics::make_ida(P, o, straight(P, c.nodes));
    double tip = 0.0, ledger = 0.0, scale = 0.0;
    const double dt = 5e-3;
    for (int i = 0; i < 20; ++i) {
      const auto a = condensed->step(i * dt, dt);
      const auto b = klu->step(i * dt, dt);
      BOOST_REQUIRE_MESSAGE(a.ok && b.ok, c.name << ", step " << i << ": " << a.reason << b.reason);
      tip = std::max(tip, (condensed->tip_position() - klu->tip_position()).norm());
      const Energy ea = condensed->energy(), eb = klu->energy();
      ledger = std::max({ledger, std::abs(ea.dissipated - eb.dissipated),
                         std::abs(ea.work_in - eb.work_in)});
      scale = std::max(scale, std::abs(ea.gravity));
    }
    BOOST_TEST_MESSAGE(c.name << ": max tip difference " << tip << " m, ledger " << ledger
                              << " J (max |gravity energy| " << scale << " J)");
    BOOST_TEST(tip <= 1e-9, c.name);
    BOOST_TEST(ledger <= 1e-7 * scale, c.name);
  }
}
