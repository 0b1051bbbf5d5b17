#pragma once
// Messages that keep their numbers, and checked throws (in the spirit of Drake's
// DRAKE_THROW_UNLESS).
//
// std::to_string(double) prints with %f: 2.5e-7 becomes "0.000000". Messages and failure reasons
// are built with rodlab::format instead (fmt; GCC 12 has no std::format), numbers with {:g}
// (%g: 6 significant digits, "2.5e-07") or {:.3g}. The format string is checked at compile time.
//
//   RODLAB_THROW_UNLESS(dt > 0.0, "dynamics: dt must be > 0 (got {:g})", dt);
//
// throws rodlab::CheckFailure, a std::invalid_argument whose what() is the formatted message
// alone (the text users see and tests assert on); the failed condition's source text, file and
// line are carried by the exception for whoever catches it while debugging.

#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

namespace rodlab {

/// fmt::format under rodlab's name.
template <typename... Args>
std::string format(fmt::format_string<Args...> text, Args&&... args) {
  return fmt::format(text, std::forward<Args>(args)...);
}

/// What RODLAB_THROW_UNLESS throws: an invalid argument, with the check that failed.
class CheckFailure : public std::invalid_argument {
 public:
  CheckFailure(const std::string& message, const char* condition, const char* file, int line)
      : std::invalid_argument(message), condition_(condition), file_(file), line_(line) {}

  /// The source text of the condition that did not hold, e.g. "dt > 0.0".
  const char* condition() const noexcept { return condition_; }
  const char* file() const noexcept { return file_; }
  int line() const noexcept { return line_; }

 private:
  const char* condition_;  // string literals (static storage): copying cannot throw
  const char* file_;
  int line_;
};

namespace detail {
[[noreturn]] inline void throw_check_failure(const char* condition, const char* file, int line,
                                             const std::string& message) {
  throw CheckFailure(message, condition, file, line);
}
}  // namespace detail

}  // namespace rodlab

/// Throws rodlab::CheckFailure (a std::invalid_argument) with the message
/// rodlab::format(text, args...) unless `condition` holds. The arguments are evaluated only when
/// the condition fails.
#define RODLAB_THROW_UNLESS(condition, ...)                                                    \
  do {                                                                                         \
    if (!(condition))                                                                          \
      ::rodlab::detail::throw_check_failure(#condition, __FILE__, __LINE__,                    \
                                            ::rodlab::format(__VA_ARGS__));                    \
  } while (false)
