#pragma once
// The heap settings of rodlab's programs: the command line (apps/rodlab/main.cpp) and the
// benchmarks (bench/bench_main.hpp), so that a benchmark measures what a `rodlab` run does.
//
// Large blocks (dense Newton matrices, sparse Jacobians and their KLU factors: 180 kB for
// chebyshev at N = 24, 2.9 MB for kinsol at N = 100) come from the heap and stay there after
// free, instead of fresh mmap'ed pages for every allocation: glibc adapts its mmap threshold
// only after a first free and trims the heap top back to the system, so every solve paid a
// page fault per page of its work arrays. Measured (docs/statics.md "Cold and warm solves"):
// one `rodlab static` kinsol N = 100, 11.2 -> 7.5 ms; repeated solves in bench_statics, 6.8 ->
// 5.5 ms. Not called by the library or the Python module: the process is the caller's.
#include <malloc.h>

namespace rodlab {

inline void keep_freed_memory() {
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
}

}  // namespace rodlab
