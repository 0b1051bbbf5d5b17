// rodlab validate [--quick|--full] [--out DIR] [--scenes DIR] [--only FAMILY,...] [--no-figures]:
// the validation suite and its report (docs/validation.md).
#include <algorithm>
#include <array>
#include <filesystem>
#include <iostream>
#include <string>

#include "rodlab/io/text_format.hpp"

#include "checks/check.hpp"
#include "suite.hpp"
#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "progress_line.hpp"

namespace rodlab::cli {
namespace {
namespace fs = std::filesystem;
using validation::check_families;
using validation::CheckFamily;
using validation::scene_files;

/// Every line of `text` prefixed with `indent`, newline-terminated.
std::string indented(const std::string& text, const std::string& indent) {
  std::string out;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = text.find('\n', start);
    out += indent;
    out += text.substr(start, end == std::string::npos ? std::string::npos : end - start);
    out += '\n';
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

std::string family_names() {
  std::vector<std::string> names;
  for (const auto& f : check_families()) names.emplace_back(f.name);
  return io::join(names);
}

constexpr std::string_view kDefaultOut = "out/validation";
constexpr std::array<OptionSpec, 7> kOptions{
    OptionSpec{"--quick", "", "the quick suite (default; at most 5 minutes on 2 cores)"},
    OptionSpec{"--full", "", "the full suite, including the slow checks"},
    OptionSpec{"--out", "DIR",
               "write the report into DIR: index.html, report.json, report.md, data/, figures/ "
               "(default: out/validation)"},
    OptionSpec{"--scenes", "DIR", "the scenes to check (default: the source tree's scenes/)"},
    OptionSpec{"--only", "FAMILY,...", "run only these check families (default: all)"},
    OptionSpec{"--no-figures", "", "do not run validation/make_figures.py"}, kQuietOption};

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  if (reader.flag("--quick") && reader.flag("--full"))
    reader.problem("--quick and --full: give one of them");
  const fs::path out = read_out_dir(reader).value_or(fs::path(kDefaultOut));
  const fs::path scenes = reader.text("--scenes").value_or(RODLAB_SOURCE_DIR "/scenes");
  std::error_code ec;
  if (!fs::is_directory(scenes, ec))
    reader.problem("--scenes: " + scenes.string() + " is not a directory");
  else if (scene_files(scenes).empty())
    reader.problem("--scenes: no *.yaml scene in " + scenes.string());
  std::vector<std::string> only;
  if (const auto names = reader.names("--only")) {
    for (const auto& n : *names) {
      const auto families = check_families();
      if (std::none_of(families.begin(), families.end(),
                       [&](const CheckFamily& f) { return f.name == n; }))
        reader.problem("--only: no check family '" + n + "' (families: " + family_names() + ")");
    }
    only = *names;
  }
  reader.finish();

  validation::SuiteOptions suite;
  suite.full = reader.flag("--full");
  suite.scenes_dir = scenes;
  suite.out_dir = out;
  suite.only = only;
  suite.figures = !reader.flag("--no-figures");
  suite.source_dir = RODLAB_SOURCE_DIR;
  suite.command_line = inv.command_line;
  ProgressLine progress("validate", "families", !reader.flag(kQuietOption.name));
  if (progress.active())
    suite.on_family = [&](std::string_view family, int done, int total) {
      progress.update(done, total, family);
    };
  const validation::ValidationReport report = validation::run_suite(suite);
  progress.finish();

  for (const auto& c : report.checks) {
    if (c.passed) continue;
    std::cout << "FAIL " << c.name << ": measured " << io::format_number(c.measured);
    if (c.expected) std::cout << ", expected " << io::format_number(*c.expected);
    std::cout << " (" << c.reference << ")\n";
    if (!c.detail.empty()) std::cout << indented(c.detail, "     ");
  }
  if (report.figures.state != "generated") {
    std::cout << "figures " << report.figures.state << " (the report is complete without them)\n";
    if (!report.figures.message.empty()) std::cout << indented(report.figures.message, "     ");
  }
  std::cout << report.passed() << " passed, " << report.failed() << " failed (" << report.mode
            << " suite, " << io::format_number(report.wall_time_s) << " s; report in "
            << (out / "index.html").string() << ")\n";
  return report.failed() == 0 ? kSolved : kNotConverged;
}

}  // namespace

const Command& validate_command() {
  static const Command command{
      "validate",
      "[--quick|--full] [--out DIR] [--scenes DIR] [--only FAMILY,...] [--no-figures]",
      "run the validation suite; write index.html, report.json, report.md, data and figures",
      "Runs the validation checks (families: scenes, statics, dynamics, literature, studies,\n"
      "control, learning, extremes; docs/validation.md).\n"
      "Each check records its measured value, the reference (and where it comes from), the\n"
      "tolerance and pass/fail. Writes into DIR, atomically: index.html (one self-contained\n"
      "page with every check and figure), report.json (checks, data sets, figure specs and\n"
      "provenance: git commit, compiler and flags, build type, CPU, OS, date, command line,\n"
      "library versions), report.md, data/*.csv (the numbers behind the figures) and\n"
      "figures/*.svg (drawn by validation/make_figures.py with python3-matplotlib; without it\n"
      "the report says so). Prints each failed check and a summary `N passed, M failed`.\n"
      "--quick (default) takes at most 5 minutes on 2 cores; --full adds the slow checks.\n"
      "\n"
      "Exit status: 0 every check passed; 1 some check failed; 2 bad usage (nothing written).\n"
      "The figures do not change the exit status.\n",
      {},
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
