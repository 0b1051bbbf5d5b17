#pragma once
// The validation suite as one call (what `rodlab validate` runs): the check families, their data
// sets, the report files and the figures, written into one directory (docs/validation.md).
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "report/report.hpp"

namespace rodlab::validation {

struct SuiteOptions {
  bool full = false;                  ///< --full: also the slow checks
  std::filesystem::path scenes_dir;   ///< the example scenes (*.yaml)
  std::filesystem::path out_dir;      ///< index.html, report.json, report.md, data/, figures/
  std::vector<std::string> only;      ///< families to run; empty: all
  bool figures = true;                ///< run validation/make_figures.py
  std::filesystem::path source_dir;   ///< the source tree (provenance, the figure script)
  std::string command_line;           ///< for provenance
  /// Progress: called before each family runs (ValidationContext::on_family).
  std::function<void(std::string_view family, int done, int total)> on_family;
};

/// Runs the checks and writes the report (atomically, file by file) into options.out_dir.
ValidationReport run_suite(const SuiteOptions& options);

}  // namespace rodlab::validation
