#pragma once
// The validation report: report.json (schema rodlab.validation-report/1: checks, summary,
// provenance) and report.md (the same as tables), built only from the Check records.
#include <string>
#include <vector>

#include "provenance.hpp"
#include "validation_checks.hpp"

namespace rodlab::cli {

inline constexpr const char* kValidationReportSchema = "rodlab.validation-report/1";

struct ValidationReport {
  std::string mode;  ///< "quick" or "full"
  std::string scenes_dir;
  std::vector<Check> checks;
  Provenance provenance;

  std::size_t passed() const;
  std::size_t failed() const { return checks.size() - passed(); }
};

std::string to_json(const ValidationReport& report);
std::string to_markdown(const ValidationReport& report);

}  // namespace rodlab::cli
