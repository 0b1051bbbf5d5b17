// libFuzzer target: the input is a scene file's text, checked as `rodlab check` does
// (check_path.hpp says what counts as a finding). Seeds: scenes/ and tests/data/scenes/.
#include <cstddef>
#include <cstdint>
#include <string>

#include "check_path.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  rodlab::fuzz::check_like_the_cli(text, {});
  return 0;
}
