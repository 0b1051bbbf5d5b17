#define BOOST_TEST_MODULE kill_during_run
#include <boost/test/unit_test.hpp>

// Atomic results under kill -9 (issue #13 item 7). A long `rodlab dynamic --out FILE` is killed
// with SIGKILL at random moments; after every kill the result file is either absent or complete
// (the JSON parses and holds every output time; the CSV has its header and every row), and the
// only other entries of the directory are rodlab's temporary files `.<name>.tmp-*` (a SIGKILL
// leaves them: nothing can remove them; they are dot-files that rodlab never reads, and a later
// run writes its own). A run to the end, with such leftovers present, then writes the complete
// result. Half of the kills come at random moments of the run, half a random 0-5 ms after the
// run starts writing (the first new file in the directory), so that kills inside the write
// itself are frequent.
//
// Without the temporary file and the rename (lib/src/io/atomic_file.cpp), a kill during the
// write leaves a truncated FILE and the completeness check fails (checked by hand, session 7:
// with the result written in place, the kills into the write left truncated JSON and a CSV cut
// mid-line). The seed is printed so that a
// failure can be reproduced (RODLAB_KILL_SEED=<seed>).

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace fs = std::filesystem;
namespace utf = boost::unit_test;
using namespace rodlab::testing::cli;
using Clock = std::chrono::steady_clock;

namespace {

// The cantilever released straight under gravity, variational scheme, 10^5 steps of which
// every fifth is recorded: 20001 output times, a result of 6 MB, about a second (Release).
// Under AddressSanitizer (-DRODLAB_SANITIZE=ON) the run is ten times slower (and more on a
// loaded machine), so it is 25 times shorter there: 801 output times, the same kind of write.
#if defined(__SANITIZE_ADDRESS__)
constexpr const char* kEndTime = "0.04";
constexpr std::size_t kOutputTimes = 801;
#else
constexpr const char* kEndTime = "1.0";
constexpr std::size_t kOutputTimes = 20001;
#endif

std::string scene() {
  return std::string(R"(schema: rodlab.scene/1
name: long-run
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000}
tip:
  free: {}
loads:
  gravity: [-9.81, 0, 0]
dynamics: {t_end: )") +
         kEndTime + R"(, dt: 1.0e-5, initial: straight, output_every: 5, scheme: variational}
solver: {nodes: 20}
)";
}

/// Starts `rodlab dynamic scene.yaml --out NAME` in `dir`, its output discarded.
pid_t start_run(const fs::path& dir, const std::string& name) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(127);
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    ::execl(RODLAB_BINARY, RODLAB_BINARY, "dynamic", "scene.yaml", "--out", name.c_str(),
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

/// Number of output times in a complete JSON result; fails the test if it is not complete.
std::size_t check_complete_json(const fs::path& file) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(read(file));
  } catch (const nlohmann::json::exception& e) {
    BOOST_ERROR(file << " is not complete JSON: " << e.what());
    return 0;
  }
  BOOST_TEST(j.value("schema", "") == "rodlab.dynamic-result/1");
  BOOST_TEST(j.value("converged", false));
  const std::size_t n = j["series"]["t"].size();
  BOOST_TEST(j["series"]["tip_position"].size() == n);
  BOOST_TEST(j["series"]["energy"]["total"].size() == n);
  BOOST_TEST(j.contains("final"));
  return n;
}

/// A complete CSV result: the header, `rows` rows of 11 numbers, a final newline.
void check_complete_csv(const fs::path& file, std::size_t rows) {
  const std::string text = read(file);
  BOOST_TEST(text.starts_with("t,tip_x,tip_y,tip_z,kinetic,strain,gravity,dissipated,work_in,"
                              "total,max_det_deviation\n"));
  BOOST_TEST(text.ends_with("\n"), file << " ends mid-line");
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);
  std::size_t n = 0, short_rows = 0;
  while (std::getline(lines, line)) {
    ++n;
    if (std::count(line.begin(), line.end(), ',') != 10) ++short_rows;
  }
  BOOST_TEST(short_rows == 0u);
  BOOST_TEST(n == rows, file << " has " << n << " rows of " << rows);
}

/// Every entry of `dir` is scene.yaml, a result or a temporary file of a result; returns the
/// number of temporary files.
int check_only_results_and_temporaries(const fs::path& dir) {
  int temporaries = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.starts_with(".result.json.tmp-") || f.starts_with(".result.csv.tmp-")) ++temporaries;
    else BOOST_TEST((f == "scene.yaml" || f == "result.json" || f == "result.csv"),
                    "unexpected file " << f);
  }
  return temporaries;
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

/// Waits until the run `pid` creates a file in `dir` (its temporary result file, or the result
/// itself if it were written in place), then waits `extra` more; false if the run ended first.
bool wait_for_writing(pid_t pid, const fs::path& dir, std::chrono::microseconds extra) {
  const std::size_t before = entries(dir);
  while (entries(dir) == before) {
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  std::this_thread::sleep_for(extra);
  return true;
}

unsigned seed() {
  if (const char* s = std::getenv("RODLAB_KILL_SEED")) return static_cast<unsigned>(std::stoul(s));
  return std::random_device{}();
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_killed_run_leaves_no_partial_result, *utf::timeout(300)) {
  Sandbox box("kill");
  box.write("scene.yaml", scene());

  // The reference: a run to the end, timed, whose result is complete.
  const auto start = Clock::now();
  const int status = wait_for(start_run(box.work, "reference.json"));
  const double duration = std::chrono::duration<double>(Clock::now() - start).count();
  BOOST_REQUIRE_MESSAGE(WIFEXITED(status) && WEXITSTATUS(status) == 0,
                        "the uninterrupted run succeeds (status " << status << ")");
  const std::size_t rows = check_complete_json(box.work / "reference.json");
  BOOST_REQUIRE(rows == kOutputTimes);
  fs::remove(box.work / "reference.json");
  BOOST_TEST_MESSAGE("uninterrupted run: " << duration << " s, " << rows << " output times");

  const unsigned s = seed();
  BOOST_TEST_MESSAGE("RODLAB_KILL_SEED=" << s);
  std::mt19937 random(s);
  std::uniform_real_distribution<double> anywhere(0.02, 1.0);
  std::uniform_int_distribution<int> into_the_write(0, 5000);  // microseconds
  int killed_with_file = 0, killed_without = 0, killed_writing = 0, temporaries = 0;
  for (int k = 0; k < 10; ++k) {
    const std::string name = k % 2 == 0 ? "result.json" : "result.csv";
    // Kills 0-4 at a random moment of the run; kills 5-9 a random 0-5 ms after the first file
    // of the write appears (serialising takes longer than writing: a kill at a random moment
    // seldom falls inside the write itself).
    const double delay = duration * anywhere(random);
    const std::chrono::microseconds extra(into_the_write(random));
    BOOST_TEST_CONTEXT("kill " << k << ", --out " << name << ", "
                               << (k < 5 ? "after " + std::to_string(delay) + " s"
                                         : std::to_string(extra.count()) +
                                               " us into the write")) {
      const pid_t pid = start_run(box.work, name);
      if (k < 5)
        std::this_thread::sleep_for(std::chrono::duration<double>(delay));
      else
        BOOST_TEST(wait_for_writing(pid, box.work, extra), "the run was still going");
      ::kill(pid, SIGKILL);
      wait_for(pid);
      const fs::path file = box.work / name;
      if (fs::exists(file)) {
        ++killed_with_file;
        if (name.ends_with(".json")) BOOST_TEST(check_complete_json(file) == rows);
        else check_complete_csv(file, rows);
        fs::remove(file);
      } else {
        ++killed_without;
      }
      const int now = check_only_results_and_temporaries(box.work);
      if (now > temporaries) ++killed_writing;  // the kill left a temporary file
      temporaries = now;
    }
  }
  BOOST_TEST_MESSAGE("kills: " << killed_without << " with no result file (" << killed_writing
                               << " of them while it was being written: a temporary file was "
                               << "left), " << killed_with_file << " after it was complete");

  // Leftover temporary files do not disturb a later run to the same name.
  for (const std::string name : {"result.json", "result.csv"}) {
    BOOST_REQUIRE(WIFEXITED(wait_for(start_run(box.work, name))));
    if (name.ends_with(".json")) BOOST_TEST(check_complete_json(box.work / name) == rows);
    else check_complete_csv(box.work / name, rows);
  }
}
