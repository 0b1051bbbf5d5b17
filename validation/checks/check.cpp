#include "checks/check.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rodlab::validation {
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

Check upper_bound_check(std::string name, double measured, double bound, std::string reference) {
  Check c;
  c.name = std::move(name);
  c.measured = measured;
  c.expected = bound;
  c.tolerance = 0.0;
  c.reference = std::move(reference);
  c.passed = std::isfinite(measured) && measured <= bound;
  c.detail = "passes when measured <= " + [&] {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", bound);
    return std::string(buffer);
  }();
  return c;
}

Check range_check(std::string name, double measured, double lo, double hi, std::string reference) {
  Check c = relative_check(std::move(name), measured, 0.5 * (lo + hi),
                           (hi - lo) / std::abs(lo + hi), std::move(reference));
  c.passed = std::isfinite(measured) && measured >= lo && measured <= hi;
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "passes when %.6g <= measured <= %.6g", lo, hi);
  c.detail = buffer;
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

namespace {
std::string number_text(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}
}  // namespace

Cell::Cell(double v) : text(number_text(v)) {}
Cell::Cell(int v) : text(std::to_string(v)) {}
Cell::Cell(long v) : text(std::to_string(v)) {}

void DataSet::add_row(std::vector<Cell> row) {
  if (row.size() != columns.size())
    throw std::logic_error("data set " + name + ": a row of " + std::to_string(row.size()) +
                           " cells for " + std::to_string(columns.size()) + " columns");
  rows.push_back(std::move(row));
}

std::string DataSet::to_csv() const {
  auto quoted = [](const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) {
      if (c == '"') out += '"';
      out += c;
    }
    return out + "\"";
  };
  std::string out;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) out += ',';
    out += quoted(columns[i]);
  }
  out += '\n';
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out += ',';
      out += row[i].numeric ? row[i].text : quoted(row[i].text);
    }
    out += '\n';
  }
  return out;
}

void ValidationContext::emit(DataSet data) const {
  if (sink == nullptr) return;
  data.family = sink->current_family;
  sink->data_sets.push_back(std::move(data));
}

std::vector<fs::path> scene_files(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".yaml") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

Check with_topic(Check check, std::string topic) {
  check.topic = std::move(topic);
  return check;
}

}  // namespace rodlab::validation
