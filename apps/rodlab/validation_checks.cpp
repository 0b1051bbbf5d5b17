#include "validation_checks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>

namespace rodlab::cli {
namespace fs = std::filesystem;

double Check::relative_error() const {
  if (!expected) return 0.0;
  const double diff = std::abs(measured - *expected);
  return *expected == 0.0 ? diff : diff / std::abs(*expected);
}

Check relative_check(std::string name, double measured, double expected, double tolerance,
                     std::string reference) {
  Check c;
  c.name = std::move(name);
  c.measured = measured;
  c.expected = expected;
  c.tolerance = tolerance;
  c.reference = std::move(reference);
  c.passed = std::isfinite(measured) && c.relative_error() <= tolerance;
  return c;
}

Check boolean_check(std::string name, bool ok, std::string reference, std::string detail) {
  Check c;
  c.name = std::move(name);
  c.measured = ok ? 1.0 : 0.0;
  c.expected = 1.0;
  c.tolerance = 0.0;
  c.reference = std::move(reference);
  c.passed = ok;
  c.detail = std::move(detail);
  return c;
}

std::span<const CheckFamily> check_families() {
  // Add a family here (and its function in its own file).
  static const std::array<CheckFamily, 2> families{{
      {"scenes", "example scenes load; derived quantities equal their closed forms", &scene_checks},
      {"statics", "statics schemes on the thesis's 2.7 problems and closed forms", &statics_checks},
  }};
  return families;
}

std::vector<Check> run_checks(const ValidationContext& context) {
  std::vector<Check> all;
  for (const auto& family : check_families()) {
    std::vector<Check> checks;
    try {
      checks = family.run(context);
    } catch (const std::exception& e) {
      checks = {boolean_check(std::string(family.name) + " family runs", false,
                              "runs without an exception", e.what())};
    }
    for (auto& c : checks) {
      c.family = std::string(family.name);
      all.push_back(std::move(c));
    }
  }
  return all;
}

std::vector<fs::path> scene_files(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace rodlab::cli
