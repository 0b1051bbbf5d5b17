#pragma once
// Runs validation/make_figures.py, which draws every figure of a report (figures/*.svg) from
// its CSV data and the figure specs in report.json, with matplotlib. The figures are optional:
// without python3 or matplotlib the report says so and everything else is still written; the
// exit status of `rodlab validate` depends on the checks only. The interpreter search and the
// script runner are also those of `rodlab plot` (scripts/rodlab_plot.py).
#include <filesystem>
#include <string>
#include <vector>

#include "report/report.hpp"

namespace rodlab::validation {

/// Exit status of make_figures.py when matplotlib or numpy cannot be imported.
inline constexpr int kFiguresUnavailable = 3;

/// The interpreters to try, in order: $RODLAB_PYTHON alone if set; else "python3" (on PATH)
/// and then Debian's /usr/bin/python3 (where python3-matplotlib installs, when PATH's python3
/// is another one, e.g. pyenv's).
std::vector<std::string> figure_pythons();

/// One run of a Python script (run_python_script).
struct ScriptRun {
  std::string command;  ///< the shell command that ran
  int exit_code = -1;   ///< 127: the interpreter was not found; -1: it did not exit normally
  std::string output;   ///< its standard output and standard error, interleaved
};

/// Runs `python script args...` (script and args shell-quoted) and collects its output.
ScriptRun run_python_script(const std::string& python, const std::filesystem::path& script,
                            const std::vector<std::string>& args);

/// Why a run found no usable interpreter, with what to install: the interpreter was not found
/// (exit 127), or the script could not import matplotlib or numpy (kFiguresUnavailable). Empty
/// when the interpreter was usable, whatever else happened.
std::string unavailable_reason(const std::string& python, const ScriptRun& run);

/// Runs the script with each interpreter of `pythons` in turn until one is usable, and returns
/// that run. When none is, returns the last run and sets `unavailable` to why (one reason, or
/// "python: reason; ..." for several interpreters); otherwise `unavailable` is cleared.
ScriptRun run_python_script(const std::vector<std::string>& pythons,
                            const std::filesystem::path& script,
                            const std::vector<std::string>& args, std::string& unavailable);

/// The last `lines` lines of `text` (a script's output in a message).
std::string output_tail(const std::string& text, int lines);

/// Runs `python script out_dir` (out_dir holds report.json and data/), and says what happened:
/// generated (exit 0 and every figure file exists), unavailable (no interpreter, or the script
/// exits with kFiguresUnavailable), failed (anything else, with the tail of its output).
/// Removes the report's figure files first, so that a failed run leaves no stale figures.
FiguresStatus run_figure_script(const ValidationReport& report, const std::string& python,
                                const std::filesystem::path& script,
                                const std::filesystem::path& out_dir);
/// The same with each interpreter in turn until one is not "unavailable".
FiguresStatus run_figure_script(const ValidationReport& report,
                                const std::vector<std::string>& pythons,
                                const std::filesystem::path& script,
                                const std::filesystem::path& out_dir);

}  // namespace rodlab::validation
