#pragma once
// The progress line of a long run (docs/cli.md "Progress"): on standard error when it is a
// terminal, redrawn in place at most five times a second,
//
//   dynamic  1200/5000 steps  24 %  elapsed 3.1 s  left ~9.8 s  t = 0.24 s, dt = 2e-4 s
//
// and erased when the run ends, so that what the command prints after it (the summary) is as
// without it. Nothing at all when standard error is not a terminal (a log file, a pipe, a
// study's child process) or with --quiet: results and exit status never depend on it.
#include <chrono>
#include <string>
#include <string_view>

namespace rodlab::cli {

class ProgressLine {
 public:
  /// `label` starts the line; `unit` names what is counted ("steps", "runs", "checks").
  /// Disabled unless `enabled` and standard error is a terminal.
  ProgressLine(std::string label, std::string unit, bool enabled);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool active() const { return active_; }
  /// `done` of `total` (total 0: unknown, no estimate of the time left); `detail` ends the
  /// line (the current step size, case or check). Drawn when 0.2 s have passed since the last
  /// drawing, and at done == total.
  void update(long done, long total, std::string_view detail = {});
  /// Erases the line (also done by the destructor).
  void finish();

  /// The line's text (tested without a terminal).
  static std::string text(std::string_view label, std::string_view unit, long done, long total,
                          double elapsed_s, std::string_view detail);

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_, unit_;
  bool active_ = false;
  bool drawn_ = false;
  std::size_t width_ = 0;  ///< of the last line drawn, to erase it
  Clock::time_point start_, last_;
};

}  // namespace rodlab::cli
