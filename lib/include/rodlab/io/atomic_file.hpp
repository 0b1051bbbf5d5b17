#pragma once
// Writing a file so that readers see either the old content or the complete new content,
// never a half-written file: the content goes to a uniquely named temporary file in the
// target's directory, is flushed and fsync'ed, and is then renamed over the target
// (rename(2) is atomic within one file system). Every result and report file of rodlab is
// written this way.
//
// A SIGKILL (or a crash, or a power cut) between creating the temporary file and the rename
// leaves that temporary file behind: `.<name>.tmp-<pid>-<n>-<random>`, a dot-file next to the
// target, never a partial <name>. rodlab does not read such files and does not remove them (it
// cannot tell a stale one from one another writer is still filling); delete them at leisure.
#include <filesystem>
#include <string_view>
#include <system_error>

namespace rodlab::io {

/// A file could not be written: what() is "cannot write PATH: <reason>" (e.g. "No space left
/// on device"), with the directory named when it is missing; code() is the errno.
class WriteError : public std::system_error {
 public:
  using std::system_error::system_error;
};

/// Writes `content` to `path` atomically. The new file gets the default permissions
/// (0666 minus the umask). On any failure (missing directory, target is a directory, disk
/// full, ...) the temporary file is removed, the target is left as it was, and WriteError is
/// thrown naming the path (and the directory, when that is what is missing).
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace rodlab::io
