#include "report/figures.hpp"

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>

#include "rodlab/io/text_format.hpp"

namespace rodlab::validation {
namespace fs = std::filesystem;
namespace {

/// The last `lines` lines of text.
std::string tail(const std::string& text, int lines) {
  std::size_t pos = text.size();
  if (pos > 0 && text[pos - 1] == '\n') --pos;
  for (int i = 0; i < lines && pos != std::string::npos && pos > 0; ++i)
    pos = text.rfind('\n', pos - 1);
  std::string out = pos == std::string::npos || pos == 0 ? text : text.substr(pos + 1);
  while (!out.empty() && out.back() == '\n') out.pop_back();
  return out;
}

/// The value of the line "rodlab-figures: ..." the script prints first (its libraries).
std::string versions(const std::string& output) {
  const std::string key = "rodlab-figures: ";
  const auto at = output.find(key);
  if (at == std::string::npos) return {};
  const auto end = output.find('\n', at);
  return output.substr(at + key.size(), end == std::string::npos ? std::string::npos
                                                                  : end - at - key.size());
}

}  // namespace

std::vector<std::string> figure_pythons() {
  const char* env = std::getenv("RODLAB_PYTHON");
  if (env != nullptr && *env != '\0') return {env};
  std::vector<std::string> out{"python3"};
  std::error_code ec;
  if (fs::exists("/usr/bin/python3", ec)) out.emplace_back("/usr/bin/python3");
  return out;
}

FiguresStatus run_figure_script(const ValidationReport& report,
                                const std::vector<std::string>& pythons, const fs::path& script,
                                const fs::path& out_dir) {
  FiguresStatus status;
  std::string tried;
  for (const auto& python : pythons) {
    status = run_figure_script(report, python, script, out_dir);
    if (status.state != "unavailable") return status;
    tried += (tried.empty() ? "" : "; ") + python + ": " + status.message;
  }
  if (pythons.size() > 1) status.message = tried;
  return status;
}

FiguresStatus run_figure_script(const ValidationReport& report, const std::string& python,
                                const fs::path& script, const fs::path& out_dir) {
  FiguresStatus status;
  status.command = python + " " + io::shell_quote(script.string()) + " " + io::shell_quote(out_dir.string());
  std::error_code ec;
  for (const auto& d : report.data_sets)
    for (const auto& f : d.figures) fs::remove(out_dir / figure_file(f), ec);
  if (!fs::is_regular_file(script, ec)) {
    status.state = "unavailable";
    status.message = "the figure script " + script.string() + " is missing";
    return status;
  }
  FILE* pipe = ::popen((status.command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {
    status.state = "unavailable";
    status.message = "could not start " + python;
    return status;
  }
  std::string output;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    output.append(buffer.data(), n);
  const int raw = ::pclose(pipe);
  const int code = raw != -1 && WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  if (code == 127) {
    status.state = "unavailable";
    status.message = python + " not found (install python3 and python3-matplotlib, or set "
                     "RODLAB_PYTHON)";
    return status;
  }
  if (code == kFiguresUnavailable) {
    status.state = "unavailable";
    status.message = tail(output, 1) + " (install the Debian packages python3-matplotlib and "
                     "python3-numpy; scripts/bootstrap.sh does)";
    return status;
  }
  std::string missing;
  for (const auto& d : report.data_sets)
    for (const auto& f : d.figures)
      if (!fs::is_regular_file(out_dir / figure_file(f), ec)) missing += " " + f.name;
  if (code != 0 || !missing.empty()) {
    status.state = "failed";
    status.message = "exit status " + std::to_string(code) +
                     (missing.empty() ? "" : "; missing figures:" + missing) + "; output:\n" +
                     tail(output, 15);
    return status;
  }
  status.state = "generated";
  status.message = versions(output);
  return status;
}

}  // namespace rodlab::validation
