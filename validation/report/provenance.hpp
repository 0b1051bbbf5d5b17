#pragma once
// Where a report came from: enough to reproduce it (architecture guide: reports are built
// from what the code measured, never from hand-copied numbers, and say how).
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rodlab::validation {

struct Provenance {
  std::string rodlab_version;
  std::string git_commit;         ///< "unknown" without git or outside a work tree
  std::optional<bool> git_dirty;  ///< uncommitted changes; nullopt when unknown
  std::string compiler;           ///< __VERSION__
  std::string compiler_flags;     ///< CMAKE_CXX_FLAGS + the build type's flags, at configure time
  std::string build_type;
  std::string cpu;   ///< model name from /proc/cpuinfo, with the number of logical CPUs
  std::string os;    ///< PRETTY_NAME of /etc/os-release and the kernel (uname -srm)
  std::string host;  ///< host name
  std::string date_utc;  ///< ISO 8601, e.g. 2024-05-01T12:00:00Z
  std::string command_line;
  std::vector<std::pair<std::string, std::string>> libraries;  ///< name, version
};

/// Asks git about `source_dir` (RODLAB_SOURCE_DIR), the system about itself (/proc/cpuinfo,
/// /etc/os-release, uname) and the build about itself (compile-time versions of the libraries).
Provenance collect_provenance(const std::string& source_dir, const std::string& command_line);

/// The provenance keys of report.json, in order (the unit tests check they are all there).
inline constexpr const char* kProvenanceKeys[] = {
    "rodlab_version", "git_commit", "git_dirty", "compiler", "compiler_flags", "build_type",
    "cpu", "os", "host", "date_utc", "command_line", "libraries"};

}  // namespace rodlab::validation
