#pragma once
// main() of every benchmark program: Google Benchmark's, with the heap settings of the `rodlab`
// command line first (rodlab/heap.hpp), so that a benchmark measures what a `rodlab` run does.
#include <benchmark/benchmark.h>

#include "rodlab/heap.hpp"

#define RODLAB_BENCHMARK_MAIN()                                      \
  int main(int argc, char** argv) {                                  \
    rodlab::configure_process_heap();                                \
    benchmark::Initialize(&argc, argv);                              \
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1; \
    benchmark::RunSpecifiedBenchmarks();                             \
    benchmark::Shutdown();                                           \
    return 0;                                                        \
  }
