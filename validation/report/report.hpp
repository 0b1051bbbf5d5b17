#pragma once
// The validation report, built only from the Check records, the data sets and the provenance:
//   report.json  schema rodlab.validation-report/1: summary, provenance, families, checks, data
//                sets with their figure specs, and the state of the figures;
//   report.md    the same as Markdown tables, with links to the figures;
//   index.html   one self-contained page (inline CSS, figures embedded as base64 data: URIs),
//                which still works when moved alone.
#include <filesystem>
#include <string>
#include <vector>

#include "report/provenance.hpp"
#include "checks/check.hpp"

namespace rodlab::validation {

inline constexpr const char* kValidationReportSchema = "rodlab.validation-report/1";
/// A directory's figures without a report (a study's figures.json): its data sets and specs.
inline constexpr const char* kFigureIndexSchema = "rodlab.figures/1";

struct FamilyInfo {
  std::string name, description;
};

/// What happened to the figures (validation/make_figures.py).
struct FiguresStatus {
  std::string state = "not-run";  ///< generated | unavailable | failed | skipped | not-run
  std::string message;            ///< why, or the plotting library's version
  std::string command;            ///< the command that (re)generates them
};

struct ValidationReport {
  std::string mode;  ///< "quick" or "full"
  std::string scenes_dir;
  std::vector<FamilyInfo> families;  ///< the families that ran, in report order
  std::vector<Check> checks;
  std::vector<DataSet> data_sets;
  FiguresStatus figures;
  Provenance provenance;
  double wall_time_s = 0.0;  ///< of the checks

  std::size_t passed() const;
  std::size_t failed() const { return checks.size() - passed(); }
};

/// Relative paths inside the output directory.
std::string data_file(const DataSet& data);       ///< data/NAME.csv
std::string figure_file(const FigureSpec& figure);  ///< figures/NAME.svg

std::string to_json(const ValidationReport& report);
/// figures.json (schema rodlab.figures/1): the data sets and their figure specs, as report.json
/// lists them, for make_figures.py in a directory that has no report (a study's).
std::string figure_index_json(const std::vector<DataSet>& data_sets);
std::string to_markdown(const ValidationReport& report);
/// The page; figures are read from out_dir / figure_file(...) and embedded (a missing figure
/// is named as missing, with the reason from report.figures).
std::string to_html(const ValidationReport& report, const std::filesystem::path& out_dir);

/// RFC 4648 base64.
std::string base64(std::string_view bytes);
/// Text with & < > " escaped for HTML.
std::string html_escape(std::string_view text);

}  // namespace rodlab::validation
