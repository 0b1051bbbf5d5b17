// Lie group kernels: exp / log on SO(3) and SE(3), dexp and dexp^-1 (matrix, apply and the q = 2
// truncated series of rkmk-rk4), composition and the coadjoint. Each call reads its inputs from
// pre-generated arrays of random twists and group elements (fixed seed, |omega| uniform in
// [0, pi), |nu| in [1e-3, 10)), cycling through 1024 entries so that nothing is constant-folded;
// results go through benchmark::DoNotOptimize. Reported time is ns per call.
//
//   build/bin/bench_lie --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include "bench_main.hpp"

#include <cmath>
#include <cstddef>
#include <numbers>
#include <random>
#include <vector>

#include "rodlab/lie/se3.hpp"
#include "rodlab/lie/so3.hpp"

namespace {

using namespace rodlab::lie;

constexpr std::size_t kCount = 1024;  // power of two: index with a mask
constexpr std::size_t kMask = kCount - 1;

struct Inputs {
  std::vector<Vector6> twists;   // xi = [omega; nu]
  std::vector<Vector6> vectors;  // arguments y of dexp_apply & co., wrenches of coAd_apply
  std::vector<SO3> rotations;
  std::vector<SE3> transforms;
};

const Inputs& inputs() {
  static const Inputs in = [] {
    std::mt19937 gen(20240611u);
    std::uniform_real_distribution<double> unit(-1.0, 1.0), angle(0.0, std::numbers::pi),
        log_mag(-3.0, 1.0);
    auto direction = [&] {
      Vector3 v;
      do v = Vector3(unit(gen), unit(gen), unit(gen));
      while (v.norm() < 1e-3 || v.norm() > 1.0);
      return Vector3(v.normalized());
    };
    Inputs s;
    for (std::size_t i = 0; i < kCount; ++i) {
      const Vector3 w = angle(gen) * direction();
      const Vector3 nu = std::pow(10.0, log_mag(gen)) * direction();
      s.twists.push_back(se3::join(w, nu));
      s.vectors.push_back(se3::join(direction(), direction()));
      s.rotations.push_back(SO3::exp(w));
      s.transforms.push_back(SE3::exp(s.twists.back()));
    }
    return s;
  }();
  return in;
}

/// Runs op(i) on input index i = 0, 1, 2, ... (mod kCount), keeping every result alive.
template <class Op>
void run(benchmark::State& state, const Op& op) {
  std::size_t i = 0;
  for (auto _ : state) {
    auto result = op(i & kMask);
    benchmark::DoNotOptimize(result);
    ++i;
  }
  benchmark::ClobberMemory();
  state.SetItemsProcessed(state.iterations());
}

void SO3_exp(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return SO3::exp(in.twists[i].head<3>()); });
}
void SO3_log(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return in.rotations[i].log(); });
}
void SE3_exp(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return SE3::exp(in.twists[i]); });
}
void SE3_log(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return in.transforms[i].log(); });
}
void se3_dexp_matrix(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return se3::dexp(in.twists[i]); });
}
void se3_dexp_inv_matrix(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return se3::dexp_inv(in.twists[i]); });
}
void se3_dexp_apply(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return se3::dexp_apply(in.twists[i], in.vectors[i]); });
}
void se3_dexp_inv_apply(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return se3::dexp_inv_apply(in.twists[i], in.vectors[i]); });
}
void se3_dexp_inv_series_apply_q2(benchmark::State& state) {
  const auto& in = inputs();
  run(state,
      [&](std::size_t i) { return se3::dexp_inv_series_apply(in.twists[i], in.vectors[i], 2); });
}
void SE3_compose(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return in.transforms[i] * in.transforms[(i + 1) & kMask]; });
}
void SE3_coAd_apply(benchmark::State& state) {
  const auto& in = inputs();
  run(state, [&](std::size_t i) { return in.transforms[i].coAd_apply(in.vectors[i]); });
}

}  // namespace

BENCHMARK(SO3_exp);
BENCHMARK(SO3_log);
BENCHMARK(SE3_exp);
BENCHMARK(SE3_log);
BENCHMARK(se3_dexp_matrix);
BENCHMARK(se3_dexp_inv_matrix);
BENCHMARK(se3_dexp_apply);
BENCHMARK(se3_dexp_inv_apply);
BENCHMARK(se3_dexp_inv_series_apply_q2);
BENCHMARK(SE3_compose);
BENCHMARK(SE3_coAd_apply);

RODLAB_BENCHMARK_MAIN()
