// Guided Policy Search benchmarks (issue #15 item 4; docs/learning.md "GPS"), at the sizes of
// the rod's reach tasks: the state x (tip, its velocity: n = 6), four cables (m = 4), T = 20
// steps, N = 3 trajectories per condition, 30 conditions per iteration.
//  - lqg_backward: one KL-regularised backward pass (kl_regularised_lqg) on random stable
//    dynamics and a convex cost; the dual step runs it 3-10 times per condition.
//  - kl_step: the whole C-step of one condition (backward, forward, KL, bisection on eta).
//  - dynamics_fit: one condition's fit (3 trajectories) with a prior fitted on 20.
// A GPS iteration on the rod costs 30 x (fit + C-step) plus the S-step (50 epochs over 1800
// samples) and the 1800 plant steps; the plant dominates (docs/learning.md).
// Run: taskset -c 0 build/bin/bench_gps --benchmark_repetitions=5 (one core, idle machine).
#include <benchmark/benchmark.h>

#include "bench_main.hpp"

#include <cstdint>
#include <random>
#include <vector>

#include "rodlab/solvers/learning/linear_gaussian_dynamics.hpp"
#include "rodlab/solvers/learning/trajectory_optimizer.hpp"

namespace {

namespace learning = rodlab::solvers::learning;

constexpr int kN = 6, kM = 4, kT = 20;

Eigen::MatrixXd uniform(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& rng) {
  Eigen::MatrixXd out(rows, cols);
  for (Eigen::Index k = 0; k < out.size(); ++k)
    out.data()[k] = 2.0 * static_cast<double>(rng() >> 11) * 0x1.0p-53 - 1.0;
  return out;
}

/// Random contracting dynamics x+ = A x + B a + c with small noise, and a convex cost.
struct Problem {
  learning::LinearGaussianDynamics dynamics;
  learning::QuadraticCost cost;
  learning::LinearGaussianController reference;
};

Problem problem() {
  std::mt19937_64 rng(1);
  Problem p;
  Eigen::MatrixXd F(kN, kN + kM);
  F << 0.9 * Eigen::MatrixXd::Identity(kN, kN) + 0.05 * uniform(kN, kN, rng),
      0.2 * uniform(kN, kM, rng);
  p.dynamics.F.assign(kT - 1, F);
  p.dynamics.f.assign(kT - 1, 0.01 * uniform(kN, 1, rng));
  p.dynamics.covariance.assign(kT - 1, 1e-4 * Eigen::MatrixXd::Identity(kN, kN));
  p.dynamics.x0_mean = uniform(kN, 1, rng);
  p.dynamics.x0_covariance = 1e-6 * Eigen::MatrixXd::Identity(kN, kN);
  const Eigen::MatrixXd R = uniform(kN + kM, kN + kM, rng);
  p.cost.C.assign(kT, R * R.transpose() + 0.1 * Eigen::MatrixXd::Identity(kN + kM, kN + kM));
  p.cost.c.assign(kT, uniform(kN + kM, 1, rng));
  p.cost.c0.assign(kT, 0.0);
  p.reference =
      learning::LinearGaussianController::constant(kT, kN, Eigen::VectorXd::Zero(kM), 0.1);
  return p;
}

void lqg_backward(benchmark::State& state) {
  const Problem p = problem();
  for (auto _ : state)
    benchmark::DoNotOptimize(learning::kl_regularised_lqg(p.dynamics, p.cost, p.reference, 1.0));
}
BENCHMARK(lqg_backward)->Unit(benchmark::kMicrosecond);

void kl_step(benchmark::State& state) {
  const Problem p = problem();
  for (auto _ : state)
    benchmark::DoNotOptimize(
        learning::kl_constrained_lqg(p.dynamics, p.cost, p.reference, 0.5 * kT, 1.0));
}
BENCHMARK(kl_step)->Unit(benchmark::kMicrosecond);

void dynamics_fit(benchmark::State& state) {
  const Problem p = problem();
  std::mt19937_64 rng(2);
  const auto trajectories = [&](int count) {
    std::vector<Eigen::MatrixXd> X, U;
    for (int i = 0; i < count; ++i) {
      Eigen::MatrixXd x(kN, kT), u = uniform(kM, kT, rng);
      x.col(0) = p.dynamics.x0_mean + 0.01 * uniform(kN, 1, rng);
      for (int t = 0; t + 1 < kT; ++t) {
        Eigen::VectorXd z(kN + kM);
        z << x.col(t), u.col(t);
        x.col(t + 1) = p.dynamics.F[t] * z + p.dynamics.f[t] + 0.01 * uniform(kN, 1, rng);
      }
      X.push_back(x);
      U.push_back(u);
    }
    return std::pair{X, U};
  };
  learning::DynamicsFitter fitter(kN, kM, {});
  const auto [Xp, Up] = trajectories(20);
  fitter.update_prior(Xp, Up);
  const auto [X, U] = trajectories(3);
  for (auto _ : state) benchmark::DoNotOptimize(fitter.fit(X, U));
}
BENCHMARK(dynamics_fit)->Unit(benchmark::kMicrosecond);

}  // namespace

RODLAB_BENCHMARK_MAIN()
