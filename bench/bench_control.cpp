// Control benchmarks (issue #14 item 9; docs/control.md) on scenes/control-cable.yaml (the
// thesis' control robot: Table 2.1 rod, alpha = 300 Pa s, four cables in [0, 0.5] N), the plant
// on implicit-midpoint (staggered grid), N = 20, dt_c = 0.05 s:
//  - mpc_track_step/H: one control step of NLSQ-MPC tracking the middle circle (plan + step of
//    the plant), warm-started as in `rodlab control`, after 20 steps onto the circle; counters: LM iterations, real-time ratio
//    (time per step / dt_c).
//  - linearise_full/M: A, B, C, D of one control step, M = 0 by the implicit function theorem
//    (the scheme's linearised step), M = 1 by central differences (2 (n + m) steps);
//    linearise_directional: one directional derivative (two control steps).
//  - ilqr_iteration/H/M: one iLQR iteration on the rod at horizon H (the linearisation of every
//    stage is its cost), M as above; ilqr_iteration counts real_time_ratio as if one iteration
//    per control step (its time over dt_c).
// Run: build/bin/bench_control --benchmark_repetitions=5 (one core, idle machine).
#include <benchmark/benchmark.h>

#include "bench_main.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/scene/trajectory.hpp"
#include "rodlab/solvers/control/ilqr.hpp"
#include "rodlab/solvers/control/linearisation.hpp"
#include "rodlab/solvers/control/nlsq_mpc.hpp"
#include "rodlab/solvers/control/plant.hpp"
#include "rodlab/solvers/control/plant_ilqr.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::solvers::control;

scene::Scene control_cable() {
  return io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/control-cable.yaml");
}

PlantOptions plant_options() {
  PlantOptions o;
  o.solver.scheme = "implicit-midpoint";
  o.solver.nodes = 20;
  o.dt_control = 0.05;
  return o;
}

/// The plant after `steps` control steps under a fixed tension on the +x cable.
void drive(Plant& plant, int steps) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(plant.input_count());
  u[0] = 0.2;
  plant.set_input(u);
  for (int k = 0; k < steps; ++k) plant.advance();
}

void mpc_track_step(benchmark::State& state) {
  const scene::Scene scene = control_cable();
  Plant plant(scene, plant_options());
  MpcOptions o;
  o.horizon = static_cast<int>(state.range(0));
  NlsqMpc mpc(plant, o);
  const auto& circle = *scene.control->trajectory;
  std::vector<Vector3> targets(o.horizon);
  auto control_step = [&] {
    const double t = plant.time() + plant.dt_control();
    for (int k = 0; k < o.horizon; ++k)
      targets[k] = scene::position(circle, std::fmod(t + k * plant.dt_control(), 4.0));
    const MpcPlan plan = mpc.plan(plant, targets);
    plant.set_input(plan.u);
    plant.advance();
    return plan.iterations;
  };
  for (int k = 0; k < 20; ++k) control_step();  // onto the circle: steady tracking is timed
  double iterations = 0.0;
  long steps = 0;
  for (auto _ : state) {
    iterations += control_step();
    ++steps;
  }
  state.counters["lm_iterations"] = iterations / std::max(1L, steps);
  state.counters["real_time_ratio"] = benchmark::Counter(
      0.05, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(mpc_track_step)->Arg(1)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

JacobianMethod method_of(const benchmark::State& state, int arg) {
  return state.range(arg) == 0 ? JacobianMethod::implicit_function
                               : JacobianMethod::finite_difference;
}

void linearise_full(benchmark::State& state) {
  Plant plant(control_cable(), plant_options());
  drive(plant, 3);
  Linearisation lin(plant, LinearisationOptions{.method = method_of(state, 0)});
  Eigen::MatrixXd A, B, C, D;
  for (auto _ : state) benchmark::DoNotOptimize(lin.jacobians(plant, A, B, C, D).ok);
  state.counters["columns"] = static_cast<double>(A.cols() + B.cols());
}
BENCHMARK(linearise_full)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void linearise_directional(benchmark::State& state) {
  Plant plant(control_cable(), plant_options());
  drive(plant, 3);
  Linearisation lin(plant);
  const Eigen::VectorXd dx = plant.state_scale();
  const Eigen::VectorXd du = Eigen::VectorXd::Constant(plant.input_count(), 0.1);
  StepDerivative d;
  for (auto _ : state) benchmark::DoNotOptimize(lin.directional(plant, dx, du, d).ok);
}
BENCHMARK(linearise_directional)->Unit(benchmark::kMicrosecond);

void ilqr_iteration(benchmark::State& state) {
  const scene::Scene scene = control_cable();
  Plant plant(scene, plant_options());
  drive(plant, 3);
  const int H = static_cast<int>(state.range(0));
  PlantIlqrModel model(plant, H, 0.0, 1.0, method_of(state, 1));
  std::vector<Vector3> targets(H);
  for (int k = 0; k < H; ++k) targets[k] = scene::position(*scene.control->trajectory, 0.05 * (k + 1));
  IlqrOptions o;
  o.max_iterations = 1;
  for (auto _ : state) {
    model.start(targets);
    const IlqrResult r = solve_ilqr(model, std::vector<Eigen::VectorXd>(H, plant.input()), o);
    model.reset();
    benchmark::DoNotOptimize(r.ok);
  }
  state.counters["real_time_ratio"] = benchmark::Counter(
      0.05, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(ilqr_iteration)
    ->Args({5, 0})->Args({10, 0})->Args({20, 0})->Args({5, 1})
    ->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

RODLAB_BENCHMARK_MAIN()
