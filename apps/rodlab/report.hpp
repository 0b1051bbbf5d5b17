#pragma once
// A report of named quantities in titled sections, rendered either as aligned text (units on
// every number, %.6g) or as JSON (full precision, units in a separate "units" object). It is
// the one formatter behind `rodlab check` and `rodlab check --json`: both print the same
// Report, so the two can never disagree.
#include <string>
#include <variant>
#include <vector>

namespace rodlab::cli {

using ReportValue = std::variant<std::string, double, long long, bool, std::vector<double>,
                                 std::vector<std::string>>;

struct ReportItem {
  std::string key;     ///< JSON key within the section
  std::string label;   ///< what it is, in words
  std::string symbol;  ///< formula or symbol ("A", "sqrt(E/rho)"); empty for none
  ReportValue value;
  std::string unit;  ///< SI unit; empty for dimensionless or text
  /// For a vector of numbers printed one component per line: their labels, formulas and
  /// units (otherwise the vector prints on one line as [a, b, c] with `unit`). Component i
  /// prints as: label, "symbol[i] = formula", "=", value, unit.
  std::vector<std::string> component_labels = {};
  std::vector<std::string> component_formulas = {};
  std::vector<std::string> component_units = {};
};

struct ReportSection {
  std::string key;    ///< JSON key
  std::string title;  ///< text heading
  std::vector<ReportItem> items;
};

struct Report {
  std::string schema;  ///< e.g. rodlab.check/1 (JSON only)
  std::vector<ReportSection> sections;
};

/// Text: each section's title, then one aligned row per item: label, symbol, "=", value, unit.
std::string render_text(const Report& report);
/// JSON: {"schema": ..., "<section>": {"<key>": value, ...}, ..., "units": {"<section>.<key>":
/// unit}}.
std::string render_json(const Report& report);

}  // namespace rodlab::cli
