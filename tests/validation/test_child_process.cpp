#define BOOST_TEST_MODULE validation_child_process
#include <boost/test/unit_test.hpp>

// validation/studies/child_process: how the extremes family tells a crash, a hang and an exit
// status apart (reference: what /bin/sh is told to do). A hang is killed at its time limit.
#include <csignal>
#include <filesystem>
#include <string>

#include <unistd.h>

#include "studies/child_process.hpp"

namespace {

namespace fs = std::filesystem;
using rodlab::validation::study::run_child;

fs::path err_file() {
  return fs::temp_directory_path() / ("rodlab-child-" + std::to_string(::getpid()) + ".err");
}

}  // namespace

BOOST_AUTO_TEST_CASE(exit_status_and_stderr) {
  const auto r = run_child({"/bin/sh", "-c", "echo oops >&2; exit 3"}, 10.0, err_file());
  BOOST_TEST(r.exit_code == 3);
  BOOST_TEST(r.signal == 0);
  BOOST_TEST(!r.timed_out);
  BOOST_TEST(r.stderr_text == "oops\n");
  fs::remove(err_file());
}

BOOST_AUTO_TEST_CASE(a_crash_is_its_signal) {
  const auto r = run_child({"/bin/sh", "-c", "kill -SEGV $$"}, 10.0, err_file());
  BOOST_TEST(r.exit_code == -1);
  BOOST_TEST(r.signal == SIGSEGV);
  BOOST_TEST(!r.timed_out);
  fs::remove(err_file());
}

BOOST_AUTO_TEST_CASE(a_hang_is_killed_at_the_limit) {
  const auto r = run_child({"/bin/sleep", "30"}, 0.3, err_file());
  BOOST_TEST(r.timed_out);
  BOOST_TEST(r.signal == SIGKILL);
  BOOST_TEST(r.wall_time_s >= 0.3);
  BOOST_TEST(r.wall_time_s < 5.0);
  fs::remove(err_file());
}

BOOST_AUTO_TEST_CASE(a_missing_program_throws) {
  BOOST_CHECK_THROW(run_child({"/nonexistent/rodlab"}, 1.0, err_file()), std::runtime_error);
  fs::remove(err_file());
}
