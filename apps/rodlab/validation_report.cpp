#include "validation_report.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "format.hpp"

namespace rodlab::cli {
namespace {

using Json = nlohmann::ordered_json;

Json provenance_json(const Provenance& p) {
  Json libraries = Json::object();
  for (const auto& [name, version] : p.libraries) libraries[name] = version;
  return Json{{"rodlab_version", p.rodlab_version},
              {"git_commit", p.git_commit},
              {"git_dirty", p.git_dirty ? Json(*p.git_dirty) : Json(nullptr)},
              {"compiler", p.compiler},
              {"build_type", p.build_type},
              {"date_utc", p.date_utc},
              {"command_line", p.command_line},
              {"libraries", libraries}};
}

/// Markdown table cells must not contain '|' or line breaks.
std::string cell(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n')
      out += "<br>";
    else
      out += c;
  }
  return out;
}

/// %.6g for reading; the JSON report has the full values.
std::string short_number(double v) { return format_number(v); }

}  // namespace

std::size_t ValidationReport::passed() const {
  return static_cast<std::size_t>(
      std::count_if(checks.begin(), checks.end(), [](const Check& c) { return c.passed; }));
}

std::string to_json(const ValidationReport& r) {
  Json checks = Json::array();
  for (const auto& c : r.checks) {
    Json j{{"family", c.family}, {"name", c.name}, {"measured", c.measured}};
    j["expected"] = c.expected ? Json(*c.expected) : Json(nullptr);
    j["relative_error"] = c.relative_error();
    j["tolerance"] = c.tolerance;
    j["reference"] = c.reference;
    j["passed"] = c.passed;
    if (!c.detail.empty()) j["detail"] = c.detail;
    checks.push_back(std::move(j));
  }
  Json json{{"schema", kValidationReportSchema},
            {"mode", r.mode},
            {"scenes_dir", r.scenes_dir},
            {"summary",
             Json{{"checks", r.checks.size()}, {"passed", r.passed()}, {"failed", r.failed()}}},
            {"provenance", provenance_json(r.provenance)},
            {"checks", checks}};
  return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string to_markdown(const ValidationReport& r) {
  const Provenance& p = r.provenance;
  std::string out = "# rodlab validation report\n\n";
  out += "**" + std::to_string(r.passed()) + " passed, " + std::to_string(r.failed()) +
         " failed** (" + r.mode + " suite, " + std::to_string(r.checks.size()) + " checks)\n\n";
  out += "| provenance | |\n|---|---|\n";
  out += "| rodlab | " + cell(p.rodlab_version) + " |\n";
  out += "| git commit | " + cell(p.git_commit) +
         (p.git_dirty ? (*p.git_dirty ? " (uncommitted changes)" : " (clean)") : "") + " |\n";
  out += "| compiler | " + cell(p.compiler) + " |\n";
  out += "| build type | " + cell(p.build_type) + " |\n";
  out += "| date (UTC) | " + cell(p.date_utc) + " |\n";
  out += "| command | `" + cell(p.command_line) + "` |\n";
  for (const auto& [name, version] : p.libraries)
    out += "| " + cell(name) + " | " + cell(version) + " |\n";
  out += "| scenes | " + cell(r.scenes_dir) + " |\n";

  out += "\n| result | check | measured | expected | rel. error | tolerance | reference |\n";
  out += "|---|---|---|---|---|---|---|\n";
  for (const auto& c : r.checks) {
    out += "| " + std::string(c.passed ? "pass" : "**FAIL**") + " | " + cell(c.name) + " | " +
           short_number(c.measured) + " | " + (c.expected ? short_number(*c.expected) : "") +
           " | " + short_number(c.relative_error()) + " | " + short_number(c.tolerance) + " | " +
           cell(c.reference) + (c.detail.empty() ? "" : "<br>" + cell(c.detail)) + " |\n";
  }
  return out;
}

}  // namespace rodlab::cli
