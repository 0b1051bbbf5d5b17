// rodlab validate [--quick|--full] [--out DIR] [--scenes DIR]: the validation suite and its
// report.
#include <array>
#include <filesystem>
#include <iostream>
#include <string>

#include "rodlab/io/atomic_file.hpp"

#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "format.hpp"
#include "validation_checks.hpp"
#include "validation_report.hpp"

namespace rodlab::cli {
namespace {
namespace fs = std::filesystem;

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

constexpr std::string_view kDefaultOut = "out/validation";
constexpr std::array<OptionSpec, 4> kOptions{
    OptionSpec{"--quick", "", "the quick suite (default)"},
    OptionSpec{"--full", "", "the full suite, including the slow checks"},
    OptionSpec{"--out", "DIR", "write DIR/report.json and DIR/report.md (default: out/validation)"},
    OptionSpec{"--scenes", "DIR", "the scenes to check (default: the source tree's scenes/)"}};

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
  reader.finish();

  ValidationReport report;
  report.mode = reader.flag("--full") ? "full" : "quick";
  report.scenes_dir = scenes.string();
  report.provenance = collect_provenance(RODLAB_SOURCE_DIR, inv.command_line);
  report.checks = run_checks(ValidationContext{scenes, report.mode == "full"});

  fs::create_directories(out);
  io::write_file_atomically(out / "report.json", to_json(report));
  io::write_file_atomically(out / "report.md", to_markdown(report));

  for (const auto& c : report.checks) {
    if (c.passed) continue;
    std::cout << "FAIL " << c.name << ": measured " << format_number(c.measured);
    if (c.expected) std::cout << ", expected " << format_number(*c.expected);
    std::cout << " (" << c.reference << ")\n";
    if (!c.detail.empty()) std::cout << indented(c.detail, "     ");
  }
  std::cout << report.passed() << " passed, " << report.failed() << " failed (" << report.mode
            << " suite; report in " << (out / "report.md").string() << ")\n";
  return report.failed() == 0 ? kSolved : kNotConverged;
}

}  // namespace

const Command& validate_command() {
  static const Command command{
      "validate",
      "[--quick|--full] [--out DIR] [--scenes DIR]",
      "run the validation suite; write report.json and report.md",
      "Runs the validation checks: every example scene loads, and derived quantities equal\n"
      "their closed forms. Each check records its measured value, the reference (and where it\n"
      "comes from), the tolerance and pass/fail. Writes DIR/report.json (with provenance: git\n"
      "commit, compiler, build type, date, command line, library versions) and DIR/report.md,\n"
      "atomically, and prints a summary `N passed, M failed`.\n"
      "\n"
      "Exit status: 0 every check passed; 1 some check failed; 2 bad usage (nothing written).\n",
      {},
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
