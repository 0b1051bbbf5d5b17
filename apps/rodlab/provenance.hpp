#pragma once
// Where a report came from: enough to reproduce it (architecture guide: reports are built
// from what the code measured, never from hand-copied numbers, and say how).
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace rodlab::cli {

struct Provenance {
  std::string rodlab_version;
  std::string git_commit;         ///< "unknown" without git or outside a work tree
  std::optional<bool> git_dirty;  ///< uncommitted changes; nullopt when unknown
  std::string compiler;           ///< __VERSION__
  std::string build_type;
  std::string date_utc;  ///< ISO 8601, e.g. 2024-05-01T12:00:00Z
  std::string command_line;
  std::vector<std::pair<std::string, std::string>> libraries;  ///< name, version
};

/// Asks git about `source_dir` (RODLAB_SOURCE_DIR) and the build about itself.
Provenance collect_provenance(const std::string& source_dir, const std::string& command_line);

}  // namespace rodlab::cli
