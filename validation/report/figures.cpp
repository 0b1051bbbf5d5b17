#include "report/figures.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>

#include "rodlab/io/text_format.hpp"

namespace rodlab::validation {
namespace fs = std::filesystem;
namespace {

/// The value of the line "rodlab-figures: ..." the script prints first (its libraries).
std::string versions(const std::string& output) {
  const std::string key = "rodlab-figures: ";
  const auto at = output.find(key);
  if (at == std::string::npos) return {};
  const auto end = output.find('\n', at);
  return output.substr(at + key.size(), end == std::string::npos ? std::string::npos
                                                                  : end - at - key.size());
}

/// The shell command `python script args...`. The interpreter is not quoted: RODLAB_PYTHON may
/// carry its own options.
std::string script_command(const std::string& python, const fs::path& script,
                           const std::vector<std::string>& args) {
  std::string command = python;
  (command += ' ') += io::shell_quote(script.string());
  for (const auto& a : args) (command += ' ') += io::shell_quote(a);
  return command;
}

}  // namespace

std::string output_tail(const std::string& text, int lines) {
  std::size_t pos = text.size();
  if (pos > 0 && text[pos - 1] == '\n') --pos;
  for (int i = 0; i < lines && pos != std::string::npos && pos > 0; ++i)
    pos = text.rfind('\n', pos - 1);
  std::string out = pos == std::string::npos || pos == 0 ? text : text.substr(pos + 1);
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

std::vector<std::string> figure_pythons() {
  const char* env = std::getenv("RODLAB_PYTHON");
  if (env != nullptr && *env != '\0') return {env};
  std::vector<std::string> out{"python3"};
  std::error_code ec;
  if (fs::exists("/usr/bin/python3", ec)) out.emplace_back("/usr/bin/python3");
  return out;
}

ScriptRun run_python_script(const std::string& python, const fs::path& script,
                            const std::vector<std::string>& args) {
  ScriptRun run;
  run.command = script_command(python, script, args);
  FILE* pipe = ::popen((run.command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {  // no shell could be started: as unusable as a missing interpreter
    run.exit_code = 127;
    run.output = "could not start " + python;
    return run;
  }
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    run.output.append(buffer.data(), n);
  const int raw = ::pclose(pipe);
  run.exit_code = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return run;
}

std::string unavailable_reason(const std::string& python, const ScriptRun& run) {
  if (run.exit_code == 127)
    return python + " not found (install python3 and python3-matplotlib, or set RODLAB_PYTHON)";
  if (run.exit_code == kFiguresUnavailable)
    return output_tail(run.output, 1) + " (install the Debian packages python3-matplotlib and "
                                         "python3-numpy; scripts/bootstrap.sh does)";
  return {};
}

ScriptRun run_python_script(const std::vector<std::string>& pythons, const fs::path& script,
                            const std::vector<std::string>& args, std::string& unavailable) {
  ScriptRun run;
  std::string why = "no Python interpreter to try", tried;
  for (const auto& python : pythons) {
    run = run_python_script(python, script, args);
    why = unavailable_reason(python, run);
    if (why.empty()) {
      unavailable.clear();
      return run;
    }
    tried += (tried.empty() ? "" : "; ") + python + ": " + why;
  }
  unavailable = pythons.size() > 1 ? tried : why;
  return run;
}

FiguresStatus run_figure_script(const ValidationReport& report, const std::string& python,
                                const fs::path& script, const fs::path& out_dir) {
  return run_figure_script(report, std::vector<std::string>{python}, script, out_dir);
}

FiguresStatus run_figure_script(const ValidationReport& report,
                                const std::vector<std::string>& pythons, const fs::path& script,
                                const fs::path& out_dir) {
  FiguresStatus status;
  const std::vector<std::string> args{out_dir.string()};
  std::error_code ec;
  for (const auto& d : report.data_sets)
    for (const auto& f : d.figures) fs::remove(out_dir / figure_file(f), ec);
  if (!fs::is_regular_file(script, ec)) {
    status.command =
        script_command(pythons.empty() ? "python3" : pythons.front(), script, args);
    status.state = "unavailable";
    status.message = "the figure script " + script.string() + " is missing";
    return status;
  }
  std::string unavailable;
  const ScriptRun run = run_python_script(pythons, script, args, unavailable);
  status.command = run.command;
  if (!unavailable.empty()) {
    status.state = "unavailable";
    status.message = unavailable;
    return status;
  }
  std::string missing;
  for (const auto& d : report.data_sets)
    for (const auto& f : d.figures)
      if (!fs::is_regular_file(out_dir / figure_file(f), ec)) missing += " " + f.name;
  if (run.exit_code != 0 || !missing.empty()) {
    status.state = "failed";
    status.message = "exit status " + std::to_string(run.exit_code) +
                     (missing.empty() ? "" : "; missing figures:" + missing) + "; output:\n" +
                     output_tail(run.output, 15);
    return status;
  }
  status.state = "generated";
  status.message = versions(run.output);
  return status;
}

}  // namespace rodlab::validation
