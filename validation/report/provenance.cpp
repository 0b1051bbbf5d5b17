#include "report/provenance.hpp"

#include <sys/utsname.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <set>
#include <sstream>

#include <Eigen/Core>
#include <boost/version.hpp>
#include <gsl/gsl_version.h>
#include <nlohmann/json.hpp>
#include <sundials/sundials_config.h>
#if __has_include(<suitesparse/SuiteSparse_config.h>)
#include <suitesparse/SuiteSparse_config.h>
#define RODLAB_HAVE_SUITESPARSE_VERSION 1
#endif
#if __has_include(<suitesparse/klu.h>)
#include <suitesparse/klu.h>
#define RODLAB_HAVE_KLU_VERSION 1
#endif

#include "rodlab/io/text_format.hpp"

namespace rodlab::validation {
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
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ' || s.back() == '\t')) s.pop_back();
  std::size_t i = 0;
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  return s.substr(i);
}

std::string build_type() {
#if defined(RODLAB_BUILD_TYPE)
  if (std::string(RODLAB_BUILD_TYPE).empty()) return "(none)";
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

std::string compiler_flags() {
#if defined(RODLAB_CXX_FLAGS)
  const std::string flags = trimmed(RODLAB_CXX_FLAGS);
  return flags.empty() ? "(none)" : flags;
#else
  return "unknown";
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

/// "model name" of /proc/cpuinfo (distinct models joined) and the number of logical CPUs.
std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::set<std::string> models;
  int count = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("processor", 0) == 0) ++count;
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) models.insert(trimmed(line.substr(colon + 1)));
    }
  }
  std::string out;
  for (const auto& m : models) out += (out.empty() ? "" : "; ") + m;
  if (out.empty()) out = "unknown";
  const long online = ::sysconf(_SC_NPROCESSORS_ONLN);
  if (online > 0) count = static_cast<int>(online);
  if (count > 0) out += " (" + std::to_string(count) + " logical CPUs)";
  return out;
}

/// PRETTY_NAME of /etc/os-release, then the kernel.
std::string os_name() {
  std::string pretty;
  std::ifstream in("/etc/os-release");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("PRETTY_NAME=", 0) != 0) continue;
    pretty = line.substr(12);
    if (pretty.size() >= 2 && pretty.front() == '"' && pretty.back() == '"')
      pretty = pretty.substr(1, pretty.size() - 2);
  }
  struct utsname u {};
  std::string kernel;
  if (::uname(&u) == 0)
    kernel = std::string(u.sysname) + " " + u.release + " " + u.machine;
  if (pretty.empty()) return kernel.empty() ? "unknown" : kernel;
  return kernel.empty() ? pretty : pretty + ", " + kernel;
}

std::string host_name() {
  std::array<char, 256> buffer{};
  if (::gethostname(buffer.data(), buffer.size() - 1) != 0) return "unknown";
  return buffer.data();
}

}  // namespace

Provenance collect_provenance(const std::string& source_dir, const std::string& command_line) {
  Provenance p;
  p.rodlab_version = RODLAB_VERSION;
  const std::string git = "git -C " + io::shell_quote(source_dir) + " ";
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
  p.compiler_flags = compiler_flags();
  p.build_type = build_type();
  p.cpu = cpu_model();
  p.os = os_name();
  p.host = host_name();
  p.date_utc = now_utc();
  p.command_line = command_line;
  const auto v3 = [](long a, long b, long c) {
    return std::to_string(a) + "." + std::to_string(b) + "." + std::to_string(c);
  };
  p.libraries = {
      {"Eigen", v3(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
      {"SUNDIALS", SUNDIALS_VERSION},
#if defined(RODLAB_HAVE_SUITESPARSE_VERSION)
      {"SuiteSparse", v3(SUITESPARSE_MAIN_VERSION, SUITESPARSE_SUB_VERSION,
                         SUITESPARSE_SUBSUB_VERSION)},
#else
      {"SuiteSparse", "unknown"},
#endif
#if defined(RODLAB_HAVE_KLU_VERSION)
      {"KLU", v3(KLU_MAIN_VERSION, KLU_SUB_VERSION, KLU_SUBSUB_VERSION)},
#endif
      {"GSL", GSL_VERSION},
#if defined(RODLAB_YAML_CPP_VERSION)
      {"yaml-cpp", RODLAB_YAML_CPP_VERSION},
#else
      {"yaml-cpp", "unknown"},
#endif
      {"Boost", v3(BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000, BOOST_VERSION % 100)},
      {"nlohmann_json", v3(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                           NLOHMANN_JSON_VERSION_PATCH)},
  };
  return p;
}

}  // namespace rodlab::validation
