// Inverse statics benchmarks (solvers/control/inverse_statics.hpp) on scenes/cable-driven.yaml
// (Table 2.1 rod, 4 cables at 4 mm, tensions in [0, 0.5] N, chebyshev N = 24):
//  - inverse_statics_solve: one solve for the first target drawn with seed 1, from the middle of
//    the box (0.25 N each); counters: updates (Jacobian evaluations), statics solves, time per
//    update.
//  - inverse_statics_tracking: one control update of a controller tracking a circle of radius
//    1 cm in the static workspace (200 points per turn), warm-started from the last inputs and
//    equilibrium; counters: updates per control step, time per update [s].
//  - chebyshev_tracker_warm_solve / _tip_jacobian: the two parts of an update;
//    chebyshev_cold_solve: the same statics from scratch.
// Run: build/bin/bench_inverse_statics --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include "bench_main.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/control/inverse_statics.hpp"
#include "rodlab/solvers/control/static_targets.hpp"
#include "rodlab/solvers/statics/chebyshev_tracker.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::solvers;

scene::Scene cable_driven() { return io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/cable-driven.yaml"); }

void inverse_statics_solve(benchmark::State& state) {
  const scene::Scene scene = cable_driven();
  const auto targets = control::sample_static_targets(scene, {"chebyshev", 24, 1e-10, 50}, 1, 1);
  control::InverseStatics solver(scene);
  const Eigen::VectorXd middle = Eigen::VectorXd::Constant(solver.inputs(), 0.25);
  control::InverseStaticsResult r;
  for (auto _ : state) {
    r = solver.solve(targets.tips.at(0), middle);
    benchmark::DoNotOptimize(r.u.data());
  }
  state.counters["updates"] = r.updates;
  state.counters["statics_solves"] = r.statics_solves;
  state.counters["reached"] = r.reached;
  state.counters["s_per_update"] = benchmark::Counter(
      r.updates, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(inverse_statics_solve)->Unit(benchmark::kMicrosecond);

void inverse_statics_tracking(benchmark::State& state) {
  const scene::Scene scene = cable_driven();
  control::InverseStatics solver(scene);
  const double radius = 0.01, height = 0.097;
  int step = 0, updates = 0, steps = 0, missed = 0;
  for (auto _ : state) {
    const double angle = 2.0 * std::numbers::pi * (step++ % 200) / 200.0;
    const auto r = solver.solve(lie::Vector3(radius * std::cos(angle), radius * std::sin(angle), height));
    updates += r.updates;
    ++steps;
    if (!r.reached) ++missed;
  }
  state.counters["updates_per_step"] = static_cast<double>(updates) / steps;
  state.counters["missed"] = missed;
  state.counters["s_per_update"] = benchmark::Counter(
      updates, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(inverse_statics_tracking)->Unit(benchmark::kMicrosecond);

void chebyshev_tracker_warm_solve(benchmark::State& state) {
  statics::ChebyshevTracker tracker(statics::StaticProblem::from_scene(cable_driven()), {24, 1e-10, 50, 0});
  double u[2][4] = {{0.2, 0.05, 0.1, 0.4}, {0.21, 0.05, 0.1, 0.39}};
  const double steps[4] = {5e-7, 5e-7, 5e-7, 5e-7};
  statics::ChebyshevTracker::TipJacobian J;
  tracker.solve(u[0]);
  tracker.tip_jacobian(steps, J);
  int i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(tracker.solve(u[++i % 2]));
  state.counters["newton_iterations"] = tracker.iterations();
}
BENCHMARK(chebyshev_tracker_warm_solve)->Unit(benchmark::kMicrosecond);

void chebyshev_tracker_tip_jacobian(benchmark::State& state) {
  statics::ChebyshevTracker tracker(statics::StaticProblem::from_scene(cable_driven()), {24, 1e-10, 50, 0});
  const double u[4] = {0.2, 0.05, 0.1, 0.4};
  const double steps[4] = {5e-7, 5e-7, 5e-7, 5e-7};
  statics::ChebyshevTracker::TipJacobian J;
  tracker.solve(u);
  for (auto _ : state) {
    tracker.tip_jacobian(steps, J);
    benchmark::DoNotOptimize(J.data());
  }
}
BENCHMARK(chebyshev_tracker_tip_jacobian)->Unit(benchmark::kMicrosecond);

/// For comparison with the warm solve: the same statics solved from scratch.
void chebyshev_cold_solve(benchmark::State& state) {
  scene::Scene scene = cable_driven();
  const double u[4] = {0.2, 0.05, 0.1, 0.4};
  for (int k = 0; k < 4; ++k) std::get<scene::Cable>(scene.actuators[k]).tension = scene::ScalarSchedule(u[k]);
  const auto problem = statics::StaticProblem::from_scene(scene);
  for (auto _ : state) benchmark::DoNotOptimize(statics::solve_chebyshev(problem, {24, 1e-10, 50, 0}));
}
BENCHMARK(chebyshev_cold_solve)->Unit(benchmark::kMicrosecond);

}  // namespace

RODLAB_BENCHMARK_MAIN()
