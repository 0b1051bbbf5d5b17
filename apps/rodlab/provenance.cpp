#include "provenance.hpp"

#include <array>
#include <cstdio>
#include <ctime>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "format.hpp"

namespace rodlab::cli {
namespace {

/// stdout of a shell command, or nullopt when it fails.
std::optional<std::string> capture(const std::string& command) {
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return std::nullopt;
  std::string out;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) out.append(buffer.data(), n);
  if (::pclose(pipe) != 0) return std::nullopt;
  return out;
}

std::string trimmed(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

std::string build_type() {
#if defined(RODLAB_BUILD_TYPE)
  return RODLAB_BUILD_TYPE;
#else
#if defined(NDEBUG) && defined(__OPTIMIZE__)
  return "Release (inferred: optimised, NDEBUG)";
#elif !defined(NDEBUG) && !defined(__OPTIMIZE__)
  return "Debug (inferred: unoptimised, assertions on)";
#elif defined(__OPTIMIZE__)
  return "optimised, assertions on";
#else
  return "unoptimised, NDEBUG";
#endif
#endif
}

std::string now_utc() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buffer;
}

}  // namespace

Provenance collect_provenance(const std::string& source_dir, const std::string& command_line) {
  Provenance p;
  p.rodlab_version = RODLAB_VERSION;
  const std::string git = "git -C " + shell_quote(source_dir) + " ";
  const auto commit = capture(git + "rev-parse HEAD 2>/dev/null");
  p.git_commit = commit ? trimmed(*commit) : "unknown";
  if (commit) {
    if (const auto status = capture(git + "status --porcelain 2>/dev/null"))
      p.git_dirty = !trimmed(*status).empty();
  }
#if defined(__clang__)
  p.compiler = "clang " __clang_version__;
#elif defined(__GNUC__)
  p.compiler = "GCC " __VERSION__;
#else
  p.compiler = __VERSION__;
#endif
  p.build_type = build_type();
  p.date_utc = now_utc();
  p.command_line = command_line;
  p.libraries = {
      {"Eigen", std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) +
                    "." + std::to_string(EIGEN_MINOR_VERSION)},
      {"nlohmann_json", std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
                            std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." +
                            std::to_string(NLOHMANN_JSON_VERSION_PATCH)},
  };
  return p;
}

}  // namespace rodlab::cli
