// Neural-network benchmarks (issue #15 item 2; docs/learning.md "Neural networks"), a 10-64-64-4
// network (DDPG's actor size: 10 inputs, two hidden layers of 64, 4 outputs):
//  - train_step<Scalar>/A: one supervised training step on a batch of 64: forward pass, MSE and
//    its gradient, backward pass, Adam. A = 0: tanh hidden layers, 1: relu; identity output.
//  - infer<Scalar>/A: one single-sample forward pass (infer(), the real-time control path).
//  - ddpg_update/P: one DDPG update (ddpg.hpp: critic and actor steps, soft target updates) with
//    the defaults (64-64 relu actor and critic, batch 64) on 10 observations and 4 actions, from
//    a replay buffer of 10 000 random transitions. P = 0: float64, 1: float32.
// The issue quotes 24-33 us per training step (float32 Eigen, 64-64, batch 64) and 0.3 us per
// inference.
// Run: taskset -c 0 build/bin/bench_learning --benchmark_repetitions=5 (one core, idle machine).
#include <benchmark/benchmark.h>

#include "bench_main.hpp"

#include <cstdint>
#include <random>

#include "rodlab/solvers/learning/adam.hpp"
#include "rodlab/solvers/learning/ddpg.hpp"
#include "rodlab/solvers/learning/loss.hpp"
#include "rodlab/solvers/learning/mlp.hpp"
#include "rodlab/solvers/learning/replay_buffer.hpp"

namespace {

namespace learning = rodlab::solvers::learning;

template <class Scalar>
using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

template <class Scalar>
Matrix<Scalar> uniform(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Matrix<Scalar> out(rows, cols);
  for (Eigen::Index k = 0; k < out.size(); ++k)
    out.data()[k] = static_cast<Scalar>(2.0 * static_cast<double>(rng() >> 11) * 0x1.0p-53 - 1.0);
  return out;
}

template <class Scalar>
learning::Mlp<Scalar> actor(const benchmark::State& state) {
  return learning::Mlp<Scalar>(learning::MlpConfig{
      .sizes = {10, 64, 64, 4},
      .hidden = state.range(0) == 0 ? learning::Activation::tanh : learning::Activation::relu,
      .output = learning::Activation::identity,
      .seed = 1});
}

template <class Scalar>
void train_step(benchmark::State& state) {
  learning::Mlp<Scalar> net = actor<Scalar>(state);
  const Matrix<Scalar> X = uniform<Scalar>(10, 64, 2), T = uniform<Scalar>(4, 64, 3);
  learning::MlpWorkspace<Scalar> ws;
  Matrix<Scalar> dloss_dy;
  typename learning::Mlp<Scalar>::Vector gradient(net.parameter_count());
  learning::Adam<Scalar> adam(net.parameter_count(), {.learning_rate = 1e-4});
  for (auto _ : state) {
    benchmark::DoNotOptimize(learning::mse_loss(net.forward(X, ws), T, &dloss_dy));
    gradient.setZero();
    net.backward(ws, dloss_dy, &gradient);
    adam.step(net.parameters(), gradient);
    benchmark::ClobberMemory();
  }
  state.counters["samples_per_s"] =
      benchmark::Counter(64.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK_TEMPLATE(train_step, float)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(train_step, double)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

template <class Scalar>
void infer(benchmark::State& state) {
  learning::Mlp<Scalar> net = actor<Scalar>(state);
  const typename learning::Mlp<Scalar>::Vector x = uniform<Scalar>(10, 1, 4).col(0);
  typename learning::Mlp<Scalar>::Vector y(4);
  for (auto _ : state) {
    net.infer(x, y);
    benchmark::DoNotOptimize(y.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK_TEMPLATE(infer, float)->Arg(0)->Arg(1)->Unit(benchmark::kNanosecond);
BENCHMARK_TEMPLATE(infer, double)->Arg(0)->Arg(1)->Unit(benchmark::kNanosecond);

void ddpg_update(benchmark::State& state) {
  learning::DdpgOptions o;
  o.precision = state.range(0) == 0 ? learning::Precision::float64 : learning::Precision::float32;
  learning::Ddpg ddpg(10, 4, o);
  learning::ReplayBuffer buffer(10, 4, 10000);
  const Matrix<double> S = uniform<double>(10, 10000, 5), A = uniform<double>(4, 10000, 6),
                       R = uniform<double>(1, 10000, 7);
  for (Eigen::Index k = 0; k < S.cols(); ++k) {
    const Eigen::VectorXd s = S.col(k), a = A.col(k), s2 = 0.9 * S.col(k);
    buffer.add({s.data(), 10}, {a.data(), 4}, R(0, k), {s2.data(), 10}, k % 50 == 0);
  }
  for (auto _ : state) {
    ddpg.update(buffer);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(ddpg_update)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

}  // namespace

RODLAB_BENCHMARK_MAIN()
