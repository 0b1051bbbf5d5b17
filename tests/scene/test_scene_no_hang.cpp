#define BOOST_TEST_MODULE scene_no_hang
#include <boost/test/unit_test.hpp>

// The loader never hangs (issue #13): inputs on which yaml-cpp's LoadAll loops forever (a stray
// flow indicator: ", x", or a valid document followed by "---" and ","), a device that never
// ends (/dev/zero), a FIFO without a writer, and a file past the size limit are each rejected
// with a located error (exit 2 on the command line), within the time limit of each case.

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "rodlab/io/scene_loader.hpp"

namespace fs = std::filesystem;
namespace utf = boost::unit_test;
using rodlab::io::SceneError;

namespace {

/// The message of the SceneError that `load` throws ("" if none is thrown).
template <class Load>
std::string error_of(Load&& load) {
  try {
    load();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "rodlab-no-hang-XXXXXX").string();
    path = mkdtemp(pattern.data());
  }
  ~TempDir() { fs::remove_all(path); }
};

}  // namespace

BOOST_AUTO_TEST_CASE(stray_comma_is_a_located_syntax_error, *utf::timeout(5)) {
  const auto e = error_of([] { rodlab::io::load_scene_from_string(", x", "s.yaml"); });
  BOOST_TEST(contains(e, "s.yaml:1:1: YAML syntax error: unexpected ','"), e);
  const auto e2 = error_of(
      [] { rodlab::io::load_scene_from_string("schema: rodlab.scene/1\n---\n,", "s.yaml"); });
  BOOST_TEST(contains(e2, "s.yaml:3:1: YAML syntax error"), e2);
}

BOOST_AUTO_TEST_CASE(devices_and_fifos_are_not_read, *utf::timeout(5)) {
  const auto zero = error_of([] { rodlab::io::load_scene("/dev/zero"); });
  BOOST_TEST(contains(zero, "/dev/zero: is not a regular file"), zero);
  TempDir dir;
  const fs::path fifo = dir.path / "scene.yaml";
  BOOST_REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
  const auto e = error_of([&] { rodlab::io::load_scene(fifo.string()); });
  BOOST_TEST(contains(e, "is not a regular file"), e);
}

BOOST_AUTO_TEST_CASE(a_huge_file_is_refused_unread, *utf::timeout(5)) {
  TempDir dir;
  const fs::path big = dir.path / "big.yaml";
  std::ofstream(big) << "schema: rodlab.scene/1\n";
  fs::resize_file(big, (16u << 20) + 1);  // sparse: nothing is written
  const auto e = error_of([&] { rodlab::io::load_scene(big.string()); });
  BOOST_TEST(contains(e, "is 16777217 bytes; a scene file has at most 16777216 bytes"), e);
}
