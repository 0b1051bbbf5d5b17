#pragma once
// The heap settings of rodlab's programs: the command line (apps/rodlab/main.cpp) and the
// benchmarks (bench/bench_main.hpp), so that a benchmark measures what a `rodlab` run does.
// Not called by the library or the Python module: the process is the caller's.
//
// 1. Large blocks (dense Newton matrices, sparse Jacobians and their KLU factors: 180 kB for
//    chebyshev at N = 24, about 3 MB for kinsol at N = 100) come from the heap and stay there
//    after free, instead of fresh mmap'ed pages for every allocation: glibc adapts its mmap
//    threshold only after a first free and trims the heap top back to the system, so every
//    solve paid a page fault per page of its work arrays (one `rodlab static` kinsol N = 100,
//    11.2 -> 7.5 ms; docs/statics.md "Cold and warm solves").
// 2. The heap grows in 64 MB steps of address space whose 2 MB-aligned part is advised for
//    transparent huge pages (MADV_HUGEPAGE; the kernel's default mode, "madvise", serves them
//    only where asked), and the heap's top is moved to the first 2 MB boundary, so that the
//    work arrays a solve allocates come from there. A first touch of a 4 kB page costs about
//    1.8 us on the machines we measure on (a kernel entry and the page's zeroing); a 2 MB page
//    costs 60-240 us once for 512 of them. kinsol N = 100 touched ~780 fresh pages in a solve,
//    about 1.4 ms of its 3.73 ms; with huge pages 2.55 ms (docs/statics.md). The address space is
//    reserved, not used: resident memory grows by what is touched, in 2 MB steps. Where the
//    kernel has huge pages off, or the allocator is not glibc's brk heap (sanitizers), nothing
//    changes but the mallopt settings.
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>

namespace rodlab {

inline void configure_process_heap() {
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, 64 << 20);
  constexpr std::uintptr_t kHugePage = 2u << 20, kFirstBlock = 1u << 20;
  // A block from the top chunk: the heap grows by it and the pad.
  void* first = std::malloc(kFirstBlock);
  if (!first) return;
  const auto at = reinterpret_cast<std::uintptr_t>(first);
  const auto top = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t boundary = (at + kFirstBlock + kHugePage - 1) & ~(kHugePage - 1);
  if (at > top || top < boundary + kHugePage) {  // not the brk heap, or it did not grow
    std::free(first);
    return;
  }
  madvise(reinterpret_cast<void*>(boundary), top - boundary, MADV_HUGEPAGE);
  // Extended in place into the top chunk up to the boundary and kept (address space only; its
  // pages are never touched): the blocks allocated next start on a huge page.
  void* kept = std::realloc(first, boundary - at - 2 * sizeof(std::size_t));
  (void)kept;
}

}  // namespace rodlab
