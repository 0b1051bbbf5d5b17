#define BOOST_TEST_MODULE atomic_file
#include <boost/test/unit_test.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "rodlab/io/atomic_file.hpp"

namespace fs = std::filesystem;
using rodlab::io::write_file_atomically;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    static int n = 0;
    path = fs::temp_directory_path() /
           ("rodlab-atomic-file-" + std::to_string(::getpid()) + "-" + std::to_string(n++));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }

  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(path)) ++n;
    return n;
  }
};

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

BOOST_AUTO_TEST_CASE(writes_the_content_and_leaves_no_temporary_file) {
  TempDir dir;
  const std::string content =
      std::string("line 1\nline 2\n") + std::string(100000, 'x') + '\0' + "end";
  write_file_atomically(dir.path / "out.json", content);
  BOOST_TEST(read(dir.path / "out.json") == content);
  BOOST_TEST(dir.entries() == 1u);  // only out.json: no temporary left behind
}

BOOST_AUTO_TEST_CASE(writes_an_empty_file) {
  TempDir dir;
  write_file_atomically(dir.path / "empty.csv", "");
  BOOST_TEST(fs::exists(dir.path / "empty.csv"));
  BOOST_TEST(fs::file_size(dir.path / "empty.csv") == 0u);
  BOOST_TEST(dir.entries() == 1u);
}

BOOST_AUTO_TEST_CASE(overwriting_replaces_the_whole_file) {
  TempDir dir;
  const fs::path target = dir.path / "r.csv";
  write_file_atomically(target, std::string(5000, 'a'));
  write_file_atomically(target, "short\n");
  BOOST_TEST(read(target) == "short\n");
  BOOST_TEST(dir.entries() == 1u);
}

BOOST_AUTO_TEST_CASE(a_missing_directory_throws_and_creates_nothing) {
  TempDir dir;
  const fs::path target = dir.path / "missing" / "r.json";
  BOOST_CHECK_THROW(write_file_atomically(target, "{}"), std::system_error);
  BOOST_TEST(!fs::exists(dir.path / "missing"));
  BOOST_TEST(dir.entries() == 0u);
}

BOOST_AUTO_TEST_CASE(a_directory_as_target_throws_and_leaves_no_temporary_file) {
  TempDir dir;
  fs::create_directory(dir.path / "r.json");
  try {
    write_file_atomically(dir.path / "r.json", "{}");
    BOOST_FAIL("expected std::system_error");
  } catch (const std::system_error& e) {
    BOOST_TEST(std::string(e.what()).find("r.json") != std::string::npos);  // names the path
  }
  BOOST_TEST(fs::is_directory(dir.path / "r.json"));
  BOOST_TEST(fs::is_empty(dir.path / "r.json"));
  BOOST_TEST(dir.entries() == 1u);  // the directory itself, no temporary file
}

BOOST_AUTO_TEST_CASE(a_failed_write_keeps_the_old_content) {
  TempDir dir;
  const fs::path target = dir.path / "keep.json";
  write_file_atomically(target, "old\n");
  // A read-only directory makes creating the temporary file fail (unless we are root, who
  // may write anyway; then the write simply succeeds and there is nothing to check).
  fs::permissions(dir.path, fs::perms::owner_read | fs::perms::owner_exec);
  bool threw = false;
  try {
    write_file_atomically(target, "new\n");
  } catch (const std::system_error&) {
    threw = true;
  }
  fs::permissions(dir.path, fs::perms::owner_all);
  BOOST_TEST(read(target) == (threw ? "old\n" : "new\n"));
  BOOST_TEST(dir.entries() == 1u);
}

BOOST_AUTO_TEST_CASE(a_path_without_file_name_throws) {
  TempDir dir;
  BOOST_CHECK_THROW(write_file_atomically(dir.path / "", "x"), std::system_error);
  BOOST_CHECK_THROW(write_file_atomically("", "x"), std::system_error);
  BOOST_TEST(dir.entries() == 0u);
}

BOOST_AUTO_TEST_CASE(a_relative_path_is_written_in_the_working_directory) {
  TempDir dir;
  const fs::path old = fs::current_path();
  fs::current_path(dir.path);
  write_file_atomically("plain.csv", "a,b\n");
  fs::current_path(old);
  BOOST_TEST(read(dir.path / "plain.csv") == "a,b\n");
  BOOST_TEST(dir.entries() == 1u);
}
