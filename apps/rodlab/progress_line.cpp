#include "progress_line.hpp"

#include <cmath>
#include <cstdio>
#include <unistd.h>

#include <fmt/format.h>

#include "rodlab/io/text_format.hpp"

namespace rodlab::cli {
namespace {

constexpr double kRedrawEvery = 0.2;  // [s]

/// 3.1 s, 2 min 5 s, 1 h 2 min.
std::string duration(double s) {
  if (s < 60.0) return io::format_number(std::round(s * 10.0) / 10.0) + " s";
  const long total = std::lround(s);
  if (total < 3600) return fmt::format("{} min {} s", total / 60, total % 60);
  return fmt::format("{} h {} min", total / 3600, (total % 3600) / 60);
}

}  // namespace

ProgressLine::ProgressLine(std::string label, std::string unit, bool enabled)
    : label_(std::move(label)), unit_(std::move(unit)),
      active_(enabled && ::isatty(STDERR_FILENO) == 1), start_(Clock::now()), last_(start_) {}

ProgressLine::~ProgressLine() { finish(); }

std::string ProgressLine::text(std::string_view label, std::string_view unit, long done,
                               long total, double elapsed_s, std::string_view detail) {
  std::string line = fmt::format("{}  {}", label, done);
  if (total > 0) {
    line += fmt::format("/{} {}  {} %", total, unit, 100 * done / total);
  } else {
    line += fmt::format(" {}", unit);
  }
  line += "  elapsed " + duration(elapsed_s);
  if (total > 0 && done > 0 && done < total)
    line += "  left ~" + duration(elapsed_s * static_cast<double>(total - done) / done);
  if (!detail.empty()) line += fmt::format("  {}", detail);
  return line;
}

void ProgressLine::update(long done, long total, std::string_view detail) {
  if (!active_) return;
  const auto now = Clock::now();
  if (drawn_ && std::chrono::duration<double>(now - last_).count() < kRedrawEvery &&
      !(total > 0 && done >= total))
    return;
  last_ = now;
  const std::string line =
      text(label_, unit_, done, total, std::chrono::duration<double>(now - start_).count(), detail);
  // back to the line's start, the new text, blanks over what is left of the old one
  const std::size_t pad = width_ > line.size() ? width_ - line.size() : 0;
  std::fprintf(stderr, "\r%s%*s", line.c_str(), static_cast<int>(pad), "");
  std::fflush(stderr);
  width_ = line.size();
  drawn_ = true;
}

void ProgressLine::finish() {
  if (!active_ || !drawn_) return;
  std::fprintf(stderr, "\r%*s\r", static_cast<int>(width_), "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace rodlab::cli
