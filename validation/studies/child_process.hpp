#pragma once
// Runs a program as a child process under a hard time limit (posix_spawn, waitpid polling,
// SIGKILL at the limit): how the extremes family runs `rodlab` on inputs that might crash or
// hang, so that a crash or a hang is a finding, not the end of the suite.
#include <filesystem>
#include <string>
#include <vector>

namespace rodlab::validation::study {

struct ChildOutcome {
  int exit_code = -1;       ///< the exit status when the child exited normally, else -1
  int signal = 0;           ///< the signal that ended it (SIGKILL after a time-out), else 0
  bool timed_out = false;   ///< killed at the time limit
  double wall_time_s = 0.0;
  std::string stderr_text;  ///< its standard error (the first 64 KiB)
};

/// Runs argv[0] (a path) with arguments argv[1..], stdin and stdout on /dev/null, stderr captured
/// through `stderr_file`; kills it (SIGKILL) after `time_limit_s` seconds. Throws
/// std::runtime_error when the child cannot be started.
ChildOutcome run_child(const std::vector<std::string>& argv, double time_limit_s,
                       const std::filesystem::path& stderr_file);

/// The running program's own executable (/proc/self/exe).
std::filesystem::path own_executable();

}  // namespace rodlab::validation::study
