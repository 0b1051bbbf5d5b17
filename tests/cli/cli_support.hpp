#pragma once
// Running the rodlab binary as a user would, for the command-line tests (tests/cli,
// tests/study): a fresh working directory per Sandbox, the exit status and the captured output
// of each run, and the check that bad input exits 2 and writes nothing.
#include <boost/test/unit_test.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>
#include <string>

namespace rodlab::testing::cli {

namespace fs = std::filesystem;

inline std::string read(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A single-quoted shell word.
inline std::string quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

struct Run {
  int status = -1;
  std::string out, err;
};

/// A fresh working directory (work/) for the binary, and a separate place for its captured
/// output, so that "nothing was written" can be checked on work/ alone.
struct Sandbox {
  fs::path root, work;
  explicit Sandbox(const std::string& tag = "cli") {
    static int n = 0;
    root = fs::temp_directory_path() /
           ("rodlab-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(n++));
    fs::remove_all(root);
    work = root / "work";
    fs::create_directories(work);
  }
  ~Sandbox() { fs::remove_all(root); }
  Sandbox(const Sandbox&) = delete;
  Sandbox& operator=(const Sandbox&) = delete;

  /// Runs `rodlab ARGS` in work/; `prefix` goes before the binary (e.g. mpirun ...).
  Run run(const std::string& args, const std::string& prefix = "") const {
    const fs::path out = root / "stdout.txt", err = root / "stderr.txt";
    const std::string command = "cd " + quote(work.string()) + " && " + prefix +
                                quote(RODLAB_BINARY) + " " + args + " >" + quote(out.string()) +
                                " 2>" + quote(err.string());
    const int raw = std::system(command.c_str());
    Run r;
    r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    r.out = read(out);
    r.err = read(err);
    return r;
  }

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(work / name) << text;
  }

  /// The names in work/, recursively.
  std::set<std::string> files() const {
    std::set<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(work))
      out.insert(fs::relative(e.path(), work).string());
    return out;
  }
};

/// Exit status 2, the message contains every `parts`, nothing written in work/.
inline void expect_bad_input(const Sandbox& box, const std::string& args,
                             std::initializer_list<std::string> parts) {
  const auto before = box.files();
  const Run r = box.run(args);
  BOOST_TEST_CONTEXT("rodlab " << args << "\nstderr: " << r.err) {
    BOOST_TEST(r.status == 2);
    for (const auto& p : parts) BOOST_TEST(contains(r.err, p), "stderr names '" << p << "'");
    BOOST_TEST((box.files() == before), "nothing written");
  }
}

}  // namespace rodlab::testing::cli
