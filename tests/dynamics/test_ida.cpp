#define BOOST_TEST_MODULE ida
#include <boost/test/unit_test.hpp>

// The `ida` dynamics reference (method of lines + SUNDIALS IDA/KLU, ida_reference.hpp) on the
// cantilever of scenes/viscous-cantilever.yaml (thesis Table 2.1 rod: L = 0.1 m, circle
// D = 0.01 m, E = 1e6 Pa, G = 0.33e6 Pa, rho = 1000 kg/m^3, gravity [-9.81, 0, 0] m/s^2),
// released straight from rest, N = 10 nodes, rtol = atol = 1e-10:
//   (1) undamped: the semi-discrete energy T + U + P is conserved exactly, so its drift is
//       IDA's integration error (tolerance 1e-7 of max |P|);
//   (2) `variational` at the same N converges to `ida` as dt -> 0 (the two share the spatial
//       discretisation): the tip difference at t = 0.05 s shrinks with dt at the measured
//       first order in time;
//   (3) Kelvin-Voigt damping (viscosity 300 Pa s): T + U + P never increases (1e-12 J) and
//       T + U + P + dissipated - work_in is conserved (1e-6 of max |P|).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/rod/energies.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/ida_reference.hpp"
#include "rodlab/solvers/dynamics/variational.hpp"

namespace {

using namespace rodlab;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::Energy;
using solvers::dynamics::IdaOptions;
using solvers::dynamics::Stepper;
using lie::SE3;
using lie::Vector3;

constexpr int kNodes = 10;

/// scenes/viscous-cantilever.yaml with the given viscosity.
scene::Scene cantilever(double viscosity) {
  return io::load_scene_from_string(R"(schema: rodlab.scene/1
name: viscous-cantilever
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: )" +
                                        std::to_string(viscosity) + R"(}
tip:
  free: {}
loads:
  gravity: [-9.81, 0, 0]
)",
                                    "viscous-cantilever.yaml");
}

std::vector<SE3> straight(const DynamicProblem& P, int nodes) {
  std::vector<SE3> g(nodes);
  const double ds = P.length() / (nodes - 1);
  for (int j = 0; j < nodes; ++j) g[j] = rod::reference_pose(P.model(), P.base(), j * ds);
  return g;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Runs `stepper` to t_end in steps of dt, recording the energy after every step.
std::vector<Energy> run(Stepper& stepper, double dt, double t_end) {
  std::vector<Energy> e{stepper.energy()};
  const long steps = std::lround(t_end / dt);
  for (long i = 0; i < steps; ++i) {
    const auto status = stepper.step(i * dt, dt);
    BOOST_REQUIRE_MESSAGE(status.ok, status.reason);
    e.push_back(stepper.energy());
  }
  return e;
}

double max_abs_gravity(const std::vector<Energy>& e) {
  double m = 0.0;
  for (const auto& x : e) m = std::max(m, std::abs(x.gravity));
  return m;
}

}  // namespace

BOOST_AUTO_TEST_CASE(undamped_release_conserves_energy) {
  // Reference: exact conservation of the semi-discrete energy (no dissipation, no input), so
  // the drift is IDA's global error; tolerance 1e-7 of max |gravity energy| over 0.2 s.
  const auto scene = cantilever(0.0);
  const auto P = DynamicProblem::from_scene(scene);
  const auto g0 = straight(P, kNodes);
  const auto start = std::chrono::steady_clock::now();
  auto ida = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, g0);
  const auto e = run(*ida, 1e-3, 0.2);
  const double wall = seconds_since(start);
  const double scale = max_abs_gravity(e);
  double drift = 0.0, dissipated = 0.0;
  for (const auto& x : e) {
    drift = std::max(drift, std::abs(x.total() - e.front().total()));
    dissipated = std::max({dissipated, std::abs(x.dissipated), std::abs(x.work_in)});
  }
  BOOST_TEST_MESSAGE("undamped, N = 10, 0.2 s: max |P| = " << scale << " J, energy drift "
                     << drift << " J (" << drift / scale << " relative), wall " << wall << " s");
  BOOST_TEST(scale > 1e-4);  // the rod did swing
  BOOST_TEST(drift <= 1e-7 * scale);
  BOOST_TEST(dissipated == 0.0);
  BOOST_TEST(ida->max_det_deviation() <= 1e-14);
}

BOOST_AUTO_TEST_CASE(variational_converges_to_ida) {
  // Reference: `ida` at rtol = atol = 1e-10 is the time-exact solution of the semi-discrete
  // system that `variational` discretises in time. Tolerance: the difference at t = 0.05 s
  // halves with dt (measured ratio MEASURED; asserted in [1.7, 2.3], first order), and is
  // below 1e-4 L at dt = 1e-5 s.
  const auto scene = cantilever(0.0);
  const auto P = DynamicProblem::from_scene(scene);
  const auto g0 = straight(P, kNodes);
  const double t_end = 0.05;
  auto start = std::chrono::steady_clock::now();
  auto ida = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, g0);
  run(*ida, 1e-3, t_end);
  const Vector3 tip_ida = ida->tip_position();
  BOOST_TEST_MESSAGE("ida to 0.05 s: wall " << seconds_since(start) << " s");
  std::vector<double> diff;
  for (double dt : {2e-5, 1e-5}) {
    start = std::chrono::steady_clock::now();
    auto var = solvers::dynamics::make_variational(P, {kNodes, 1e-12, 20}, g0);
    run(*var, dt, t_end);
    diff.push_back((var->tip_position() - tip_ida).norm());
    BOOST_TEST_MESSAGE("variational dt = " << dt << ": tip difference " << diff.back()
                       << " m, wall " << seconds_since(start) << " s");
  }
  const double ratio = diff[0] / diff[1];
  BOOST_TEST_MESSAGE("ratio of differences (dt = 2e-5 / 1e-5): " << ratio);
  BOOST_TEST(ratio >= 1.7);
  BOOST_TEST(ratio <= 2.3);
  BOOST_TEST(diff[1] <= 1e-4 * P.length());
}

BOOST_AUTO_TEST_CASE(damped_release_dissipates_and_balances) {
  // Reference: dE/dt = -(viscous power) <= 0 for E = T + U + P, and the ledger identity
  // T + U + P + dissipated - work_in = const of the semi-discrete system. Tolerances: E never
  // grows by more than 1e-12 J between outputs (1 ms); the ledger total stays within 1e-6 of
  // max |P| over 0.2 s.
  const auto scene = cantilever(300.0);
  const auto P = DynamicProblem::from_scene(scene);
  const auto g0 = straight(P, kNodes);
  const auto start = std::chrono::steady_clock::now();
  auto ida = solvers::dynamics::make_ida(P, IdaOptions{kNodes}, g0);
  const auto e = run(*ida, 1e-3, 0.2);
  const double wall = seconds_since(start);
  const double scale = max_abs_gravity(e);
  double max_rise = -1e300, drift = 0.0;
  for (std::size_t i = 1; i < e.size(); ++i) {
    max_rise = std::max(max_rise, e[i].mechanical() - e[i - 1].mechanical());
    drift = std::max(drift, std::abs(e[i].total() - e.front().total()));
  }
  BOOST_TEST_MESSAGE("damped, N = 10, 0.2 s: max |P| = " << scale << " J, dissipated "
                     << e.back().dissipated << " J, largest rise of T + U + P " << max_rise
                     << " J, ledger drift " << drift << " J (" << drift / scale
                     << " relative), wall " << wall << " s");
  BOOST_TEST(e.back().dissipated > 0.1 * scale);
  BOOST_TEST(max_rise <= 1e-12);
  BOOST_TEST(drift <= 1e-6 * scale);
  BOOST_TEST(e.back().work_in == 0.0);
}

BOOST_AUTO_TEST_CASE(kirchhoff_is_rejected) {
  const std::string text(R"(schema: rodlab.scene/1
rod:
  length: 0.1
  model: kirchhoff
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000}
tip:
  free: {}
)");
  const auto P = DynamicProblem::from_scene(io::load_scene_from_string(text, "kirchhoff.yaml"));
  const auto g0 = straight(P, kNodes);
  BOOST_CHECK_THROW(solvers::dynamics::make_ida(P, IdaOptions{kNodes}, g0), std::invalid_argument);
}
