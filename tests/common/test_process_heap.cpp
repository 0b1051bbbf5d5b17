#define BOOST_TEST_MODULE common_process_heap
#include <boost/test/unit_test.hpp>

// The heap settings of rodlab's programs (rodlab/heap.hpp, issue #17 item 5): after
// configure_process_heap, a solve's work arrays come from heap memory advised for transparent
// huge pages, and freed blocks stay in the process. References: the kernel's own accounts,
// /proc/self/smaps (the mapping's VmFlags, "hg" = MADV_HUGEPAGE) and getrusage's minor page
// faults (a fresh 4 MB block on 4 kB pages costs 1024 of them).
#include <sys/resource.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "rodlab/heap.hpp"

namespace {

constexpr std::size_t kBlock = 4u << 20;
constexpr long kSmallPages = kBlock / 4096;

long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

/// The VmFlags line of the mapping of /proc/self/smaps that contains `address`.
std::string vm_flags_at(const void* address) {
  const auto a = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream range(line);
    if (line.find(':') == std::string::npos || line.find(':') > 20) {  // a mapping's header
      if (range >> std::hex >> lo >> dash >> hi && dash == '-') inside = lo <= a && a < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line;
  }
  return {};
}

/// The kernel's transparent huge page mode ("always", "madvise", "never"), empty when the kernel
/// has none (then madvise(MADV_HUGEPAGE) fails and nothing is advised).
std::string huge_page_mode() {
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string text;
  std::getline(mode, text);
  const auto open = text.find('['), close = text.find(']');
  return open == std::string::npos || close == std::string::npos
             ? std::string()
             : text.substr(open + 1, close - open - 1);
}

/// Under AddressSanitizer malloc is the sanitizer's own (make sanitize): the settings do not apply.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kGlibcMalloc = false;
#else
constexpr bool kGlibcMalloc = true;
#endif

struct Configured {
  Configured() { rodlab::configure_process_heap(); }
};

}  // namespace

BOOST_GLOBAL_FIXTURE(Configured);

BOOST_AUTO_TEST_CASE(work_arrays_come_from_huge_page_memory) {
  if (!kGlibcMalloc) return;
  auto* block = static_cast<char*>(std::malloc(kBlock));
  BOOST_REQUIRE(block);
  const std::string flags = vm_flags_at(block), mode = huge_page_mode();
  BOOST_TEST_MESSAGE("block at " << static_cast<void*>(block) << ": " << flags << "; THP mode '"
                                 << mode << "'");
  if (mode.empty()) {
    BOOST_TEST_MESSAGE("this kernel has no transparent huge pages: nothing to check");
    std::free(block);
    return;
  }
  BOOST_TEST(flags.find(" hg") != std::string::npos, "advised for huge pages: " << flags);
  if (mode == "never") {
    BOOST_TEST_MESSAGE("transparent huge pages are off on this machine: fault count not checked");
    std::free(block);
    return;
  }
  const long before = minor_faults();
  std::memset(block, 1, kBlock);
  const long faults = minor_faults() - before;
  BOOST_TEST_MESSAGE("first touch of 4 MB: " << faults << " minor faults");
  // 4 kB pages: 1024. Huge pages: 2-3 (and the 4 kB pages of a boundary, if any).
  BOOST_TEST(faults < kSmallPages / 4);
  std::free(block);
}

BOOST_AUTO_TEST_CASE(freed_blocks_stay_in_the_process) {
  if (!kGlibcMalloc) return;
  auto* block = static_cast<char*>(std::malloc(kBlock));
  BOOST_REQUIRE(block);
  std::memset(block, 1, kBlock);
  std::free(block);
  const long before = minor_faults();
  auto* again = static_cast<char*>(std::malloc(kBlock));
  BOOST_REQUIRE(again);
  std::memset(again, 2, kBlock);
  const long faults = minor_faults() - before;
  // Returned to the system (mmap'ed, or the heap trimmed), the block would fault in again.
  BOOST_TEST(faults < 16, "touching the reused block took " << faults << " minor faults");
  std::free(again);
}

BOOST_AUTO_TEST_CASE(a_second_call_is_harmless) {
  rodlab::configure_process_heap();
  auto* block = static_cast<double*>(std::malloc(kBlock));
  BOOST_REQUIRE(block);
  for (std::size_t i = 0; i < kBlock / sizeof(double); ++i) block[i] = static_cast<double>(i);
  const std::size_t last = kBlock / sizeof(double) - 1;
  BOOST_TEST(block[last] == static_cast<double>(last));
  std::free(block);
}
