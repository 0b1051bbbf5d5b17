#pragma once
// Counts heap allocations in a window of a test: malloc itself is replaced for the whole test
// program (glibc supports replacing it and exports the original as __libc_malloc), so
// allocations through operator new (std::vector, std::string) and through Eigen's
// aligned_malloc (which calls std::malloc directly, never operator new) are both seen; calloc
// and realloc are not counted (nothing under test uses them). Include it in exactly one file
// of a test program.
//
// Under AddressSanitizer the replacement would hand ASan memory it did not allocate, so it is
// left out there: available() is false and the tests that need it say so and skip the count.
#include <atomic>
#include <cstddef>
#include <cstdlib>

#if defined(__SANITIZE_ADDRESS__)
#define RODLAB_COUNT_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RODLAB_COUNT_ALLOCATIONS 0
#endif
#endif
#ifndef RODLAB_COUNT_ALLOCATIONS
#define RODLAB_COUNT_ALLOCATIONS 1
#endif

namespace rodlab::test {

inline std::atomic<bool> counting_allocations{false};
inline std::atomic<long> allocations{0};

/// Counts the mallocs between its construction and count().
class AllocationCounter {
 public:
  AllocationCounter() {
    allocations = 0;
    counting_allocations = true;
  }
  ~AllocationCounter() { counting_allocations = false; }
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;
  long count() const { return allocations.load(); }
  static constexpr bool available() { return RODLAB_COUNT_ALLOCATIONS != 0; }
};

}  // namespace rodlab::test

#if RODLAB_COUNT_ALLOCATIONS
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) noexcept {
  if (rodlab::test::counting_allocations.load(std::memory_order_relaxed))
    ++rodlab::test::allocations;
  return __libc_malloc(size);
}
#endif
