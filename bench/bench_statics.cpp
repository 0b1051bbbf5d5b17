// Statics benchmarks on the gravity cantilever (thesis Table 2.1 rod, gravity along -x, rod
// along +z): one complete static solve per available scheme, and one RK4 shooting integration
// (the hot path of shooting); and kinsol on scenes/muscle.yaml at N = 100, whose muscle length
// is an extra unknown (the Jacobian's bordered form). Run: build/bin/bench_statics
// --benchmark_repetitions=5
#include <benchmark/benchmark.h>

#include "bench_main.hpp"

#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/schemes.hpp"
#include "rodlab/solvers/statics/rkmk.hpp"
#include "rodlab/solvers/statics/shooting.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

#include "reference/reference_rods.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::solvers::statics;

StaticProblem gravity_cantilever(rod::ModelKind kind) {
  const rod::RodModel model = validation::reference::table21_model(kind);
  StaticProblem problem(model, lie::SE3::identity());
  problem.set_gravity(loads::Gravity(model, lie::Vector3(-9.81, 0, 0)));
  return problem;
}

int nodes_for(std::string_view scheme) { return scheme == "chebyshev" ? 24 : 100; }

/// Repeated solves of the problem, with the nodes and the last solve's Newton iterations.
void run_solves(benchmark::State& state, const StaticProblem& problem,
                const StaticSolveOptions& options) {
  int iterations = 0;
  for (auto _ : state) {
    const auto r = solve_static(problem, options);
    iterations = r.iterations;
    benchmark::DoNotOptimize(r.centerline.back().pose);
  }
  state.counters["nodes"] = options.nodes;
  state.counters["newton_iterations"] = iterations;
}

void solve_benchmark(benchmark::State& state, std::string scheme, rod::ModelKind kind) {
  run_solves(state, gravity_cantilever(kind), {scheme, nodes_for(scheme), 1e-10, 50});
}

void one_integration(benchmark::State& state) {
  const StaticProblem problem = gravity_cantilever(rod::ModelKind::cosserat);
  const int nodes = static_cast<int>(state.range(0));
  Vector6 Lambda0 = rigid_base_wrench(problem, nodes - 1);
  for (auto _ : state) {
    const auto end = shoot(problem, RkmkMethod::rk4, nodes, Lambda0);
    benchmark::DoNotOptimize(end.tip.g);
    Lambda0[0] += 1e-30;  // defeat hoisting
  }
  state.counters["ns_per_step"] = benchmark::Counter(
      static_cast<double>(nodes - 1), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(one_integration)->Arg(100);

void kinsol_muscle(benchmark::State& state) {
  const auto scene = io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/muscle.yaml");
  const StaticProblem problem = StaticProblem::from_scene(scene);
  run_solves(state, problem, {"kinsol", 100, 1e-10, 50});
  state.counters["extra_unknowns"] = problem.extra_unknowns();
}
BENCHMARK(kinsol_muscle)->Unit(benchmark::kMicrosecond);

const bool registered = [] {
  for (const auto& s : solvers::all_schemes()) {
    if (s.problem != solvers::Problem::statics) continue;
    for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
      const std::string name = "static_solve/" + std::string(s.name) +
                               (kind == rod::ModelKind::kirchhoff ? "/kirchhoff" : "/cosserat");
      benchmark::RegisterBenchmark(name.c_str(), solve_benchmark, std::string(s.name), kind)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  return true;
}();

}  // namespace

RODLAB_BENCHMARK_MAIN()
