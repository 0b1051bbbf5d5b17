// libFuzzer target: the input is a list of --set KEY=VALUE overrides, one a line, applied to a
// valid scene that sets every field (tests/data/scenes/good/full.yaml) and checked as
// `rodlab check --set ...` does (check_path.hpp says what counts as a finding).
// Seeds: fuzz/corpus/overrides/.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "check_path.hpp"

namespace {

std::string base_scene;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::ifstream in(RODLAB_SOURCE_DIR "/tests/data/scenes/good/full.yaml");
  std::ostringstream text;
  text << in.rdbuf();
  base_scene = text.str();
  if (base_scene.empty()) {
    std::fprintf(stderr, "fuzz_overrides: cannot read tests/data/scenes/good/full.yaml\n");
    std::abort();
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string input(reinterpret_cast<const char*>(data), size);
  std::vector<rodlab::io::Override> overrides;
  std::istringstream lines(input);
  for (std::string line; std::getline(lines, line);) {
    try {
      overrides.push_back(rodlab::io::parse_override(line));
    } catch (const rodlab::io::SceneError&) {
      return 0;  // no '=' or an empty key: a usage error on the command line
    }
  }
  rodlab::fuzz::check_like_the_cli(base_scene, overrides);
  return 0;
}
