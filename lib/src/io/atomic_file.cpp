#include "rodlab/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <random>
#include <string>
#include <system_error>

namespace rodlab::io {
namespace {

[[noreturn]] void throw_errno(int error, const std::string& what) {
  throw WriteError(error, std::generic_category(), what);
}

std::filesystem::path directory_of(const std::filesystem::path& target) {
  return target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
}

/// "cannot write PATH", and the directory when it is gone (removed while rodlab ran, say):
/// ENOENT alone would not say which part of the path is missing.
std::string cannot_write(const std::filesystem::path& target, int error) {
  std::string what = "cannot write " + target.string();
  std::error_code ec;
  if (error == ENOENT && !std::filesystem::is_directory(directory_of(target), ec))
    what += " (the directory " + directory_of(target).string() + " does not exist)";
  return what;
}

/// Closes and removes the temporary file unless released (after a successful rename).
class TempFile {
 public:
  TempFile(int fd, std::filesystem::path path) : fd_(fd), path_(std::move(path)) {}
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    close();
    if (!path_.empty()) ::unlink(path_.c_str());
  }

  int fd() const { return fd_; }
  const std::filesystem::path& path() const { return path_; }

  /// Returns 0 or the errno of a failed close(2) (which may report a deferred write error).
  int close() {
    if (fd_ < 0) return 0;
    const int rc = ::close(fd_);
    fd_ = -1;
    return rc == 0 ? 0 : errno;
  }
  void release() { path_.clear(); }

 private:
  int fd_;
  std::filesystem::path path_;
};

/// Creates "<dir>/.<name>.tmp-<pid>-<counter>-<random>" exclusively (O_EXCL), so that two
/// writers, in this process or another, never share a temporary file.
TempFile create_temp_next_to(const std::filesystem::path& target) {
  static std::atomic<unsigned long> counter{0};
  std::random_device device;
  const std::filesystem::path dir = directory_of(target);
  std::string stem = ".";  // (appending, not "." + ...: GCC 12 -Wrestrict false positive)
  stem += target.filename().string();
  stem += ".tmp-";
  stem += std::to_string(::getpid());
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::filesystem::path candidate =
        dir / (stem + "-" + std::to_string(counter++) + "-" + std::to_string(device()));
    const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) return TempFile(fd, candidate);
    if (const int error = errno; error != EEXIST) throw_errno(error, cannot_write(target, error));
  }
  throw_errno(EEXIST, "cannot write " + target.string() + ": no unique temporary name");
}

void write_all(int fd, std::string_view content, const std::filesystem::path& target) {
  while (!content.empty()) {
    const ssize_t n = ::write(fd, content.data(), content.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw_errno(errno, "cannot write " + target.string());
    }
    content.remove_prefix(static_cast<std::size_t>(n));
  }
}

/// Makes the rename itself durable; failure here does not undo a completed write.
void sync_directory(const std::filesystem::path& target) {
  const int fd = ::open(directory_of(target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  if (path.empty() || !path.has_filename())
    throw_errno(EINVAL, "cannot write '" + path.string() + "': not a file name");
  TempFile temp = create_temp_next_to(path);
  write_all(temp.fd(), content, path);
  if (::fsync(temp.fd()) != 0) throw_errno(errno, "cannot write " + path.string());
  if (const int error = temp.close(); error != 0)
    throw_errno(error, "cannot write " + path.string());
  if (::rename(temp.path().c_str(), path.c_str()) != 0) {
    const int error = errno;
    throw_errno(error, cannot_write(path, error));
  }
  temp.release();
  sync_directory(path);
}

}  // namespace rodlab::io
