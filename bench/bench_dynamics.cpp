// Dynamics benchmarks: the cost of one time step per node (the hot path of every dynamics
// scheme) against N, on the viscous cantilever of thesis 3.4 (Table 2.1 rod, alpha = 300 Pa s,
// gravity along -x), stepping from rest in the straight configuration at the scheme's automatic
// step (variational also undamped, and with the thesis' symplectic-Euler time rule, whose
// damping is lagged: no corrector pass). Run: build/bin/bench_dynamics --benchmark_repetitions=5
// Counter ns_per_node_step = time per step / N; real_time_ratio = wall time per simulated second.
// ida/20ms: the reference scheme over a fixed interval (its steps are its own).
#include <benchmark/benchmark.h>

#include "bench_main.hpp"

#include <memory>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/shooting/bdf_alpha.hpp"
#include "rodlab/solvers/dynamics/shooting/implicit_midpoint.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/ida_reference.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/implicit_midpoint_collocation.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/dynamics/variational/variational.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::solvers::dynamics;

/// The Table 2.1 cantilever under gravity with Kelvin-Voigt viscosity alpha [Pa s].
std::string cantilever(double viscosity) {
  return fmt::format(R"(schema: rodlab.scene/1
name: cantilever
rod:
  length: 0.1
  section: {{shape: circle, diameter: 0.01}}
  material: {{E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: {}}}
tip:
  free: {{}}
loads:
  gravity: [-9.81, 0, 0]
)",
                     viscosity);
}

RestState straight(const DynamicProblem& p, int n) { return rest_shape(p, n); }

/// `fixed_dt` > 0: that step instead of the scheme's automatic one; `grid`: the shooting
/// schemes' spatial grid; `rule` and `viscosity`: variational's time rule and the rod's alpha;
/// `packed`: variational's packed step (VariationalOptions::packed).
void step_benchmark(benchmark::State& state, std::string scheme, double fixed_dt,
                    ShootingGrid grid, VariationalStep rule, double viscosity, bool packed) {
  const auto scene = io::load_scene_from_string(cantilever(viscosity), "bench.yaml");
  const int n = static_cast<int>(state.range(0));
  const bool corrected = grid == ShootingGrid::corrected;  // variational's corrected grid
  const auto problem = corrected ? corrected_grid_problem(DynamicProblem::from_scene(scene), n)
                                 : DynamicProblem::from_scene(scene);
  const double dt = fixed_dt > 0.0 ? fixed_dt : auto_time_step(problem, scheme, n);
  const RestState initial = straight(problem, n);
  auto fresh = [&]() -> std::unique_ptr<Stepper> {
    if (scheme == "implicit-midpoint-collocation")
      return make_implicit_midpoint_collocation(problem, {.nodes = n}, initial);
    if (scheme == "bdf-alpha")  // Till's alpha = -0.2
      return make_bdf_alpha(problem, {{n, 1e-10, 50, grid}, kDefaultBdfAlpha}, initial);
    if (scheme == "variational")
      return make_variational(problem, {n, 1e-12, 20, rule, packed, corrected}, initial);
    return make_implicit_midpoint(problem, {n, 1e-10, 50, grid}, initial);
  };
  // Time steps 10..kWindow of runs from rest, restarted outside the timing: the same window of
  // motion for every N and scheme.
  constexpr int kWindow = 200;
  std::unique_ptr<Stepper> stepper;
  double t = 0.0;
  int in_window = kWindow;
  long iterations = 0, steps = 0, jacobians = 0;
  auto jacobians_of = [](const Stepper* s) {
    const auto* c = dynamic_cast<const ImplicitMidpointCollocationStepper*>(s);
    return c ? c->jacobian_evaluations() : 0L;
  };
  long jacobians_at_window_start = 0;
  for (auto _ : state) {
    if (in_window == kWindow) {
      state.PauseTiming();
      if (stepper) jacobians += jacobians_of(stepper.get()) - jacobians_at_window_start;
      stepper = fresh();
      t = 0.0;
      for (int i = 0; i < 10; ++i, t += dt) stepper->step(t, dt);
      jacobians_at_window_start = jacobians_of(stepper.get());
      in_window = 10;
      state.ResumeTiming();
    }
    const StepStatus s = stepper->step(t, dt);
    t += dt;
    ++in_window;
    iterations += s.iterations;
    ++steps;
    if (!s.ok) state.SkipWithError(s.reason.c_str());
  }
  state.counters["ns_per_node_step"] = benchmark::Counter(
      static_cast<double>(n) * 1e-9, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["real_time_ratio"] = benchmark::Counter(
      dt, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["dt"] = dt;
  if (scheme == "implicit-midpoint-collocation") {
    jacobians += jacobians_of(stepper.get()) - jacobians_at_window_start;
    state.counters["newton_iterations_per_step"] = static_cast<double>(iterations) / std::max(1L, steps);
    state.counters["jacobians_per_step"] = static_cast<double>(jacobians) / std::max(1L, steps);
  } else if (scheme != "variational") {
    state.counters["integrations_per_step"] = static_cast<double>(iterations) / std::max(1L, steps);
  }
}

/// `ida` (the reference scheme): 20 ms of the viscous cantilever from rest, the first 1 ms
/// outside the timing, at the reference tolerances rtol = atol = 1e-10 (IDA chooses its own
/// steps; the counter is the wall time per simulated second).
void ida_benchmark(benchmark::State& state) {
  const auto scene = io::load_scene_from_string(cantilever(300.0), "bench.yaml");
  const auto problem = DynamicProblem::from_scene(scene);
  const int n = static_cast<int>(state.range(0));
  constexpr double kStart = 1e-3, kEnd = 20e-3;
  for (auto _ : state) {
    state.PauseTiming();
    auto stepper = make_ida(problem, {.nodes = n}, straight(problem, n));
    if (!stepper->step(0.0, kStart).ok) state.SkipWithError("ida: the first millisecond failed");
    state.ResumeTiming();
    const StepStatus s = stepper->step(kStart, kEnd - kStart);
    if (!s.ok) state.SkipWithError(s.reason.c_str());
  }
  state.counters["real_time_ratio"] = benchmark::Counter(
      kEnd - kStart, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// The semi-discrete rod's Newton matrix (2/dt) I - df/dy of `ida` and collocation, ledger
/// rows included, at the state 50 ms into the viscous cantilever's release (N nodes, collocation
/// at 1 ms): analytic (semi_discrete_jacobian.cpp) or by coloured finite differences.
void newton_matrix_benchmark(benchmark::State& state, SemiDiscreteRod::JacobianMethod method) {
  const auto scene = io::load_scene_from_string(cantilever(300.0), "bench.yaml");
  const auto problem = DynamicProblem::from_scene(scene);
  const int n = static_cast<int>(state.range(0));
  auto stepper = make_implicit_midpoint_collocation(problem, {.nodes = n}, straight(problem, n));
  for (int i = 0; i < 50; ++i) stepper->step(i * 1e-3, 1e-3);
  const SemiDiscreteRod rod(problem, n, "bench");
  std::vector<SE3> g;
  for (const auto& sample : stepper->centerline()) g.push_back(sample.pose);  // the node poses
  SemiDiscreteRod::Vector y = rod.rest_state(g);
  rod.pack_nodes(g, stepper->velocities(), y);
  auto J = rod.pattern(true);
  for (auto _ : state) {
    rod.newton_matrix(0.05, y, 2e3, 1.0, J, method);
    benchmark::DoNotOptimize(J.valuePtr());
  }
}

const bool registered = [] {
  using Method = SemiDiscreteRod::JacobianMethod;
  for (const auto& [name, method] :
       {std::pair{"newton_matrix/semi-discrete/analytic", Method::automatic},
        std::pair{"newton_matrix/semi-discrete/finite-differences", Method::finite_differences}}) {
    auto* b = benchmark::RegisterBenchmark(name, newton_matrix_benchmark, method);
    for (int n : {20, 100}) b->Arg(n);
    b->Unit(benchmark::kMicrosecond);
  }
  benchmark::RegisterBenchmark("ida/20ms", ida_benchmark)
      ->Arg(20)
      ->Arg(50)
      ->Unit(benchmark::kMillisecond);
  for (const char* scheme : {"variational", "implicit-midpoint", "bdf-alpha"}) {
    auto* b = benchmark::RegisterBenchmark((std::string("step/") + scheme).c_str(), step_benchmark,
                                           std::string(scheme), 0.0, ShootingGrid::euler,
                                           VariationalStep::verlet, 300.0, true);
    for (int n : {10, 20, 50, 100}) b->Arg(n);
    b->Unit(benchmark::kMicrosecond);
  }
  // variational undamped (no corrector pass) and with the thesis' time rule.
  for (const auto& [name, rule, viscosity] :
       {std::tuple{"step/variational/undamped", VariationalStep::verlet, 0.0},
        std::tuple{"step/variational/step=symplectic-euler", VariationalStep::symplectic_euler,
                   300.0}}) {
    auto* b = benchmark::RegisterBenchmark(name, [rule, viscosity](benchmark::State& state) {
      step_benchmark(state, "variational", 0.0, ShootingGrid::euler, rule, viscosity, true);
    });
    for (int n : {10, 20, 50, 100}) b->Arg(n);
    b->Unit(benchmark::kMicrosecond);
  }
  // The general loop of the variational step (VariationalOptions::packed = false), which Kirchhoff
  // rods, cables and actuators take: the packed step's reference.
  auto* loop = benchmark::RegisterBenchmark(
      "step/variational/undamped/general-loop", [](benchmark::State& state) {
        step_benchmark(state, "variational", 0.0, ShootingGrid::euler, VariationalStep::verlet,
                       0.0, false);
      });
  for (int n : {10, 100}) loop->Arg(n);
  loop->Unit(benchmark::kMicrosecond);
  // variational on the corrected grid (solver.grid: corrected): the tip's full-mass (3.42)
  auto* corrected = benchmark::RegisterBenchmark(
      "step/variational/undamped/grid=corrected", [](benchmark::State& state) {
        step_benchmark(state, "variational", 0.0, ShootingGrid::corrected,
                       VariationalStep::verlet, 0.0, true);
      });
  for (int n : {10, 100}) corrected->Arg(n);
  corrected->Unit(benchmark::kMicrosecond);
  // The shooting schemes on the staggered grid (solver.grid: staggered).
  for (const char* scheme : {"implicit-midpoint", "bdf-alpha"}) {
    auto* b = benchmark::RegisterBenchmark(
        (std::string("step/") + scheme + "/grid=staggered").c_str(),
        [scheme](benchmark::State& state) {
          step_benchmark(state, scheme, 0.0, ShootingGrid::staggered, VariationalStep::verlet,
                         300.0, true);
        });
    for (int n : {10, 20, 50, 100}) b->Arg(n);
    b->Unit(benchmark::kMicrosecond);
  }
  // implicit-midpoint-collocation: KINSOL + KLU on the whole rod per step (cost per node-step).
  auto* c = benchmark::RegisterBenchmark("step/implicit-midpoint-collocation", step_benchmark,
                                         std::string("implicit-midpoint-collocation"), 0.0,
                                         ShootingGrid::euler, VariationalStep::verlet, 300.0,
                                         true);
  for (int n : {20, 100}) c->Arg(n);
  c->Unit(benchmark::kMicrosecond);
  // The midpoint rule at fine steps: collocation (no lower time-step bound; fine-dt studies) and
  // implicit-midpoint below single shooting's lower step bound (1.02 ms on this rod): multiple
  // shooting, at N = 20 2, 4 and 16 intervals (docs/dynamics.md "Multiple shooting below the
  // bound"; the last in inverse_broyden.hpp's sparse form).
  struct FineStep {
    const char* name;
    const char* scheme;
    ShootingGrid grid;
  };
  for (const FineStep fine : {FineStep{"implicit-midpoint-collocation",
                                       "implicit-midpoint-collocation", ShootingGrid::euler},
                              FineStep{"implicit-midpoint/grid=staggered", "implicit-midpoint",
                                       ShootingGrid::staggered}})
    for (const auto& [dt_name, dt] : {std::pair{"1ms", 1e-3}, std::pair{"0.1ms", 1e-4},
                                      std::pair{"0.01ms", 1e-5}}) {
      auto* f = benchmark::RegisterBenchmark(
          (std::string("step/") + fine.name + "/dt=" + dt_name).c_str(),
          [fine, dt = dt](benchmark::State& state) {
            step_benchmark(state, fine.scheme, dt, fine.grid, VariationalStep::verlet, 300.0,
                           true);
          });
      for (int n : {20, 100}) f->Arg(n);
      f->Unit(benchmark::kMicrosecond);
    }
  return true;
}();

}  // namespace

RODLAB_BENCHMARK_MAIN()
