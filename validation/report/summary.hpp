#pragma once
// What the report leads with (docs/validation.md "The report"): the headline checks grouped by
// topic (observed orders, agreement with the references, energy, structure drift, the classic
// benchmarks, the recommended schemes), taken from the checks' own numbers (Check::topic),
// never hand-typed;
// and the order of the families, those with many routine checks (the scenes' section
// properties) folded away after the rest.
#include <string>
#include <string_view>
#include <vector>

#include "report/report.hpp"

namespace rodlab::validation {

struct SummaryTopic {
  std::string_view key;    ///< Check::topic
  std::string_view title;  ///< heading in the report
};

inline constexpr SummaryTopic kSummaryTopics[] = {
    {"order", "Observed orders of accuracy"},
    {"reference", "Agreement with the references (KINSOL, IDA)"},
    {"energy", "Energy: conservation, dissipation and the ledger"},
    {"structure", "Structure: det R and orthogonality drift"},
    {"literature", "Classic benchmarks of the literature (worst case of each)"},
    {"recommend", "Recommended schemes (`rodlab study recommend`, verified)"},
};

/// A family with more checks than this is folded away and placed after the others.
inline constexpr long kFoldAbove = 40;

/// The reference of a headline check; for a recommendation, what was recommended too.
std::string summary_note(const Check& check);

/// The checks of a topic, in report order.
std::vector<const Check*> topic_checks(const ValidationReport& report, std::string_view topic);

long family_check_count(const ValidationReport& report, const std::string& family);
bool folded(const ValidationReport& report, const std::string& family);

/// The families in the order the report shows them: the folded ones last.
std::vector<FamilyInfo> report_order(const ValidationReport& report);

/// Families that have checks but are not listed (a hand-made report), in order of appearance.
std::vector<std::string> unlisted_families(const ValidationReport& report);

}  // namespace rodlab::validation
