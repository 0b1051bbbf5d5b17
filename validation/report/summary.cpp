#include "report/summary.hpp"

#include <algorithm>

namespace rodlab::validation {

std::string summary_note(const Check& check) {
  if (check.topic == "recommend" && !check.detail.empty())
    return check.reference + "; " + check.detail;
  return check.reference;
}

std::vector<const Check*> topic_checks(const ValidationReport& report, std::string_view topic) {
  std::vector<const Check*> out;
  for (const auto& c : report.checks)
    if (c.topic == topic) out.push_back(&c);
  return out;
}

long family_check_count(const ValidationReport& report, const std::string& family) {
  return static_cast<long>(std::count_if(report.checks.begin(), report.checks.end(),
                                         [&](const Check& c) { return c.family == family; }));
}

bool folded(const ValidationReport& report, const std::string& family) {
  return family_check_count(report, family) > kFoldAbove;
}

std::vector<FamilyInfo> report_order(const ValidationReport& report) {
  std::vector<FamilyInfo> out = report.families;
  std::stable_partition(out.begin(), out.end(),
                        [&](const FamilyInfo& f) { return !folded(report, f.name); });
  return out;
}

std::vector<std::string> unlisted_families(const ValidationReport& report) {
  std::vector<std::string> out;
  for (const auto& c : report.checks)
    if (std::none_of(report.families.begin(), report.families.end(),
                     [&](const FamilyInfo& f) { return f.name == c.family; }) &&
        std::find(out.begin(), out.end(), c.family) == out.end())
      out.push_back(c.family);
  return out;
}

}  // namespace rodlab::validation
