#pragma once
// Shared scenes and measurements of the dynamics tests. The rod is the thesis' Table 2.1 rod
// (L = 0.1 m, D = 1 cm, E = 1 MPa, G = 0.33 MPa, rho = 1000 kg/m^3), clamped at the origin,
// along +z.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/result/dynamic_result.hpp"
#include "rodlab/result/oscillation.hpp"
#include "rodlab/rod/energies.hpp"
#include "rodlab/solvers/dynamics/shooting/bdf_alpha.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/ida_reference.hpp"
#include "rodlab/solvers/dynamics/shooting/implicit_midpoint.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/implicit_midpoint_collocation.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/variational/variational.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::testing::dynamics {

/// The rod with extra YAML lines under `loads:` / `tip:`; viscosity alpha [Pa s].
inline scene::Scene rod_scene(const std::string& loads, const std::string& tip, double alpha = 0.0,
                              const std::string& model = "cosserat") {
  const std::string yaml =
      "schema: rodlab.scene/1\nname: dynamics-test\nrod:\n  model: " + model +
      "\n  length: 0.1\n  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: " + std::to_string(alpha) + "}\n"
      "tip:\n  free: " + tip + "\nloads: " + loads + "\n";
  return io::load_scene_from_string(yaml, "dynamics-test.yaml");
}

/// The rod (free tip) with YAML lines under `loads:` and an `actuators:` list (each line a list
/// item, "  - muscle: {...}"); viscosity alpha [Pa s].
inline scene::Scene actuated_scene(const std::string& loads, const std::string& actuators,
                                   double alpha = 0.0, const std::string& model = "cosserat") {
  const std::string yaml =
      "schema: rodlab.scene/1\nname: actuated-test\nrod:\n  model: " + model +
      "\n  length: 0.1\n  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: " + std::to_string(alpha) + "}\n"
      "tip:\n  free: {}\nloads: " + loads + "\nactuators:\n" + actuators;
  return io::load_scene_from_string(yaml, "actuated-test.yaml");
}

/// A stepper of the scheme named `scheme` with N nodes, at rest from `initial` (KINSOL / shooting
/// tolerance tol; ida at rtol = atol = ida_tol).
/// The shooting schemes (implicit-midpoint, bdf-alpha) on `grid`: these tests check the thesis'
/// Euler grid by default (ShootingGrid::euler, kept by name); the library's default, the
/// staggered grid, is tested in test_staggered_shooting.cpp and through the command line.
inline std::unique_ptr<solvers::dynamics::Stepper> make_scheme(
    const std::string& scheme, const solvers::dynamics::DynamicProblem& P, int nodes,
    const solvers::dynamics::RestState& initial, double tol = 1e-10, double ida_tol = 1e-10,
    solvers::dynamics::ShootingGrid grid = solvers::dynamics::ShootingGrid::euler) {
  namespace d = solvers::dynamics;
  if (scheme == "variational") return d::make_variational(P, {nodes, 1e-12, 20}, initial);
  if (scheme == "implicit-midpoint") return d::make_implicit_midpoint(P, {nodes, tol, 50, grid}, initial);
  if (scheme == "bdf-alpha") {
    d::BdfAlphaOptions o;
    o.nodes = nodes;
    o.tol = tol;
    o.grid = grid;
    return d::make_bdf_alpha(P, o, initial);
  }
  if (scheme == "ida") {
    d::IdaOptions o;
    o.nodes = nodes;
    o.rtol = o.atol = ida_tol;
    return d::make_ida(P, o, initial);
  }
  d::ImplicitMidpointCollocationOptions o;
  o.nodes = nodes;
  o.tol = tol;
  return d::make_implicit_midpoint_collocation(P, o, initial);
}

/// scenes/viscous-cantilever.yaml with the given viscosity.
inline scene::Scene cantilever(double viscosity) {
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

/// The statics tip of a scene, the reference of the settling tests: chebyshev at N = 24 (exact to
/// ~1e-13 m on these scenes) unless another scheme and N are asked for.
inline lie::Vector3 static_tip(const scene::Scene& s, const std::string& scheme = "chebyshev",
                               int nodes = 24, double tol = 1e-10) {
  solvers::statics::StaticSolveOptions so;
  so.scheme = scheme;
  so.nodes = nodes;
  so.tol = tol;
  const auto eq = solvers::statics::solve_static(s, so);
  BOOST_REQUIRE_MESSAGE(eq.converged, eq.reason);
  return eq.centerline.back().pose.translation();
}

/// max |total - total_0| over an energy series: the ledger's drift (kinetic + strain + gravity +
/// dissipated - work_in is constant in the semi-discrete balance).
inline double ledger_drift(const std::vector<solvers::dynamics::Energy>& e) {
  double d = 0.0;
  for (const auto& x : e) d = std::max(d, std::abs(x.total() - e.front().total()));
  return d;
}

/// max |gravity energy| over an energy series (the scale of a gravity release's ledger).
inline double max_abs_gravity(const std::vector<solvers::dynamics::Energy>& e) {
  double m = 0.0;
  for (const auto& x : e) m = std::max(m, std::abs(x.gravity));
  return m;
}

/// max |work_in| over an energy series (the scale of an actuated run's ledger).
inline double max_abs_work_in(const std::vector<solvers::dynamics::Energy>& e) {
  double m = 0.0;
  for (const auto& x : e) m = std::max(m, std::abs(x.work_in));
  return m;
}

/// What run_steps records: the state after every step (and at t = 0).
struct StepTrace {
  std::vector<double> t;
  std::vector<lie::Vector3> tip;
  std::vector<solvers::dynamics::Energy> energy;
  long iterations = 0;  ///< summed StepStatus::iterations
  double wall = 0.0;    ///< seconds for the steps
};

/// `steps` steps of dt from t = 0, each required to converge; after step i, after_step(i).
template <class AfterStep>
StepTrace run_steps(solvers::dynamics::Stepper& s, double dt, long steps, AfterStep after_step) {
  StepTrace r;
  r.t.push_back(0.0);
  r.tip.push_back(s.tip_position());
  r.energy.push_back(s.energy());
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < steps; ++i) {
    const auto status = s.step(i * dt, dt);
    BOOST_REQUIRE_MESSAGE(status.ok, "step " << i << " (dt = " << dt << "): " << status.reason);
    r.iterations += status.iterations;
    r.t.push_back((i + 1) * dt);
    r.tip.push_back(s.tip_position());
    r.energy.push_back(s.energy());
    after_step(i);
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}
inline StepTrace run_steps(solvers::dynamics::Stepper& s, double dt, long steps) {
  return run_steps(s, dt, steps, [](long) {});
}

/// At rest in the reference configuration (straight along +z).
inline solvers::dynamics::RestState straight(const solvers::dynamics::DynamicProblem& P, int nodes) {
  return solvers::dynamics::rest_shape(P, nodes);
}

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Free vibration: held bent by a tip force P (world x) at t < 1e-9 s, released at rest from the
/// static equilibrium; no gravity, no damping unless alpha > 0.
inline scene::Scene released_scene(double P, double alpha = 0.0) {
  const std::string force = "{steps: [[0, [" + std::to_string(P) + ", 0, 0]], [1.0e-9, [0, 0, 0]]]}";
  return rod_scene("{}", "{wrench: {force: " + force + ", frame: world}}", alpha);
}

inline solvers::dynamics::DynamicSolveOptions options(const std::string& scheme, int nodes,
                                                       double dt, double t_end,
                                                       scene::Initial initial) {
  solvers::dynamics::DynamicSolveOptions o;
  o.scheme = scheme;
  o.grid = solvers::dynamics::ShootingGrid::euler;  // the thesis' grid, as make_scheme
  o.nodes = nodes;
  o.dt = dt;
  o.t_end = t_end;
  o.initial = initial;
  return o;
}

using result::mean_period;  // rodlab/result/oscillation.hpp

inline std::vector<double> tip_x(const result::DynamicResult& r) {
  std::vector<double> x;
  for (const auto& p : r.tip_position) x.push_back(p.x());
  return x;
}

inline double max_of(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace rodlab::testing::dynamics
