#pragma once
// Writing a file so that readers see either the old content or the complete new content,
// never a half-written file: the content goes to a uniquely named temporary file in the
// target's directory, is flushed and fsync'ed, and is then renamed over the target
// (rename(2) is atomic within one file system). Every result and report file of rodlab is
// written this way.
#include <filesystem>
#include <string_view>

namespace rodlab::io {

/// Writes `content` to `path` atomically. The new file gets the default permissions
/// (0666 minus the umask). On any failure (missing directory, target is a directory, disk
/// full, ...) the temporary file is removed, the target is left as it was, and
/// std::system_error is thrown naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

}  // namespace rodlab::io
