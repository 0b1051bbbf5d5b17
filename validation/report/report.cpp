#include "report/report.hpp"

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "rodlab/io/text_format.hpp"

#include "report/summary.hpp"

namespace rodlab::validation {
namespace {
namespace fs = std::filesystem;

using Json = nlohmann::ordered_json;

Json provenance_json(const Provenance& p) {
  Json libraries = Json::object();
  for (const auto& [name, version] : p.libraries) libraries[name] = version;
  return Json{{"rodlab_version", p.rodlab_version},
              {"git_commit", p.git_commit},
              {"git_dirty", p.git_dirty ? Json(*p.git_dirty) : Json(nullptr)},
              {"compiler", p.compiler},
              {"compiler_flags", p.compiler_flags},
              {"build_type", p.build_type},
              {"cpu", p.cpu},
              {"os", p.os},
              {"host", p.host},
              {"date_utc", p.date_utc},
              {"command_line", p.command_line},
              {"libraries", libraries}};
}

Json figure_json(const FigureSpec& f) {
  return Json{{"name", f.name},
              {"file", figure_file(f)},
              {"kind", f.kind},
              {"x", f.x},
              {"y", f.y},
              {"series", f.series},
              {"title", f.title},
              {"xlabel", f.xlabel},
              {"ylabel", f.ylabel},
              {"caption", f.caption},
              {"reference_slopes", f.reference_slopes},
              {"style", f.style},
              {"absolute", f.absolute},
              {"select", f.select}};
}

/// The data sets with their figure specs (what validation/make_figures.py reads).
Json data_sets_json(const std::vector<DataSet>& sets) {
  Json out = Json::array();
  for (const auto& d : sets) {
    Json figs = Json::array();
    for (const auto& f : d.figures) figs.push_back(figure_json(f));
    out.push_back(Json{{"name", d.name},
                       {"family", d.family},
                       {"file", data_file(d)},
                       {"description", d.description},
                       {"columns", d.columns},
                       {"rows", d.rows.size()},
                       {"figures", figs}});
  }
  return out;
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
std::string short_number(double v) { return io::format_number(v); }

std::string git_text(const Provenance& p) {
  return p.git_commit +
         (p.git_dirty ? (*p.git_dirty ? " (uncommitted changes)" : " (clean)") : "");
}

/// (label, value) rows of the provenance, in report order.
std::vector<std::pair<std::string, std::string>> provenance_rows(const ValidationReport& r) {
  const Provenance& p = r.provenance;
  std::vector<std::pair<std::string, std::string>> rows{
      {"rodlab", p.rodlab_version},     {"git commit", git_text(p)},
      {"compiler", p.compiler},         {"compiler flags", p.compiler_flags},
      {"build type", p.build_type},     {"CPU", p.cpu},
      {"OS", p.os},                     {"host", p.host},
      {"date (UTC)", p.date_utc},       {"command", p.command_line}};
  for (const auto& [name, version] : p.libraries) rows.emplace_back(name, version);
  rows.emplace_back("scenes", r.scenes_dir);
  rows.emplace_back("wall time of the checks", io::format_number(r.wall_time_s) + " s");
  return rows;
}

std::string figures_text(const FiguresStatus& f) {
  std::string out = f.state;
  if (!f.message.empty()) out += ": " + f.message;
  return out;
}

std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

constexpr const char* kCss = R"(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:0 auto;max-width:1200px;padding:1em 2em;color:#222;line-height:1.4}
h1{margin-bottom:.2em}h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:1.8em}
table{border-collapse:collapse;margin:.6em 0;font-size:.9em;width:100%}
th,td{border:1px solid #ccc;padding:.25em .5em;text-align:left;vertical-align:top}
th{background:#f2f2f2}td.num{font-family:ui-monospace,monospace;white-space:nowrap;text-align:right}
tr.fail td{background:#fde8e8}.pass{color:#1a7f37;font-weight:bold}.fail{color:#c62828;font-weight:bold}
.summary{font-size:1.3em;padding:.5em .8em;border-radius:6px;display:inline-block}
.summary.ok{background:#e6f4ea}.summary.bad{background:#fde8e8}
table.prov td:first-child{white-space:nowrap;font-weight:bold;width:14em}
figure{margin:1em 0;padding:.5em;border:1px solid #eee;display:inline-block;max-width:100%;vertical-align:top}
figure img{max-width:100%;height:auto}figcaption{font-size:.9em;color:#444;max-width:760px}
.note{color:#555;font-size:.9em}.detail{color:#555;font-size:.85em}code{background:#f5f5f5;padding:0 .2em}
)";

}  // namespace

std::size_t ValidationReport::passed() const {
  return static_cast<std::size_t>(
      std::count_if(checks.begin(), checks.end(), [](const Check& c) { return c.passed; }));
}

std::string data_file(const DataSet& data) { return "data/" + data.name + ".csv"; }
std::string figure_file(const FigureSpec& figure) { return "figures/" + figure.name + ".svg"; }

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
    if (!c.topic.empty()) j["topic"] = c.topic;
    checks.push_back(std::move(j));
  }
  Json families = Json::array();
  for (const auto& f : r.families) {
    const auto n = std::count_if(r.checks.begin(), r.checks.end(),
                                 [&](const Check& c) { return c.family == f.name; });
    const auto ok = std::count_if(r.checks.begin(), r.checks.end(), [&](const Check& c) {
      return c.family == f.name && c.passed;
    });
    families.push_back(
        Json{{"name", f.name}, {"description", f.description}, {"checks", n}, {"passed", ok}});
  }
  Json data_sets = data_sets_json(r.data_sets);
  Json figures = Json::array();
  for (const auto& d : r.data_sets)
    for (const auto& f : d.figures)
      figures.push_back(Json{{"name", f.name}, {"file", figure_file(f)}, {"data_set", d.name},
                             {"caption", f.caption}});
  Json json{{"schema", kValidationReportSchema},
            {"mode", r.mode},
            {"scenes_dir", r.scenes_dir},
            {"summary",
             Json{{"checks", r.checks.size()}, {"passed", r.passed()}, {"failed", r.failed()},
                  {"wall_time_s", r.wall_time_s}}},
            {"provenance", provenance_json(r.provenance)},
            {"families", families},
            {"checks", checks},
            {"data_sets", data_sets},
            {"figures", Json{{"state", r.figures.state},
                             {"message", r.figures.message},
                             {"command", r.figures.command},
                             {"files", figures}}}};
  return json.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

std::string figure_index_json(const std::vector<DataSet>& data_sets) {
  const Json json{{"schema", kFigureIndexSchema}, {"data_sets", data_sets_json(data_sets)}};
  return json.dump(2, ' ', false, Json::error_handler_t::replace);
}

namespace {

/// The headline checks by topic (report/summary.hpp).
std::string markdown_summary(const ValidationReport& r) {
  std::string out = "\n## Summary\n";
  for (const auto& topic : kSummaryTopics) {
    const auto checks = topic_checks(r, topic.key);
    if (checks.empty()) continue;
    out += "\n### " + std::string(topic.title) + "\n\n| result | check | measured | reference |\n"
           "|---|---|---|---|\n";
    for (const Check* c : checks)
      out += "| " + std::string(c->passed ? "pass" : "**FAIL**") + " | " + cell(c->name) + " | " +
             short_number(c->measured) + " | " + cell(summary_note(*c)) + " |\n";
  }
  return out;
}

}  // namespace

std::string to_markdown(const ValidationReport& r) {
  std::string out = "# rodlab validation report\n\n";
  out += "**" + std::to_string(r.passed()) + " passed, " + std::to_string(r.failed()) +
         " failed** (" + r.mode + " suite, " + std::to_string(r.checks.size()) + " checks)\n\n";
  out += "| provenance | |\n|---|---|\n";
  for (const auto& [label, value] : provenance_rows(r)) {
    if (label == "command")
      out += "| command | `" + cell(value) + "` |\n";
    else
      out += "| " + cell(label) + " | " + cell(value) + " |\n";
  }
  out += "| figures | " + cell(figures_text(r.figures)) + " |\n";
  out += markdown_summary(r);

  for (const auto& family : report_order(r)) {
    out += "\n## " + family.name + "\n\n" + family.description + "\n";
    out += "\n| result | check | measured | expected | rel. error | tolerance | reference |\n";
    out += "|---|---|---|---|---|---|---|\n";
    for (const auto& c : r.checks) {
      if (c.family != family.name) continue;
      out += "| " + std::string(c.passed ? "pass" : "**FAIL**") + " | " + cell(c.name) + " | " +
             short_number(c.measured) + " | " + (c.expected ? short_number(*c.expected) : "") +
             " | " + short_number(c.relative_error()) + " | " + short_number(c.tolerance) + " | " +
             cell(c.reference) + (c.detail.empty() ? "" : "<br>" + cell(c.detail)) + " |\n";
    }
    bool any = false;
    for (const auto& d : r.data_sets) {
      if (d.family != family.name) continue;
      if (!any) out += "\n";
      any = true;
      if (!d.table.empty()) out += d.table + "\n";
      for (const auto& f : d.figures)
        out += "![" + cell(f.title) + "](" + figure_file(f) + ")\n\n*" + f.caption +
               "* (data: [" + data_file(d) + "](" + data_file(d) + "))\n\n";
      if (d.figures.empty())
        out += "Data: [" + data_file(d) + "](" + data_file(d) + ") — " + d.description + "\n\n";
    }
  }
  // Checks of families not listed (a hand-made report).
  bool orphan_header = false;
  for (const auto& c : r.checks) {
    if (std::any_of(r.families.begin(), r.families.end(),
                    [&](const FamilyInfo& f) { return f.name == c.family; }))
      continue;
    if (!orphan_header) {
      out += "\n## other checks\n\n| result | check | measured | expected | reference |\n"
             "|---|---|---|---|---|\n";
      orphan_header = true;
    }
    out += "| " + std::string(c.passed ? "pass" : "**FAIL**") + " | " + cell(c.name) + " | " +
           short_number(c.measured) + " | " + (c.expected ? short_number(*c.expected) : "") +
           " | " + cell(c.reference) + " |\n";
  }
  if (!r.figures.command.empty())
    out += "\nRegenerate the figures from the data: `" + r.figures.command + "`\n";
  return out;
}

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::string html_escape(std::string_view text) { return io::xml_escape(text); }

namespace {

std::string e(std::string_view s) { return html_escape(s); }

std::string html_head(const ValidationReport& r) {
  std::string out =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>rodlab validation report</title>\n<style>";
  out += kCss;
  out += "</style>\n</head>\n<body>\n<h1>rodlab validation report</h1>\n";
  const bool ok = r.failed() == 0;
  out += "<p class=\"summary " + std::string(ok ? "ok" : "bad") + "\"><span class=\"" +
         (ok ? "pass" : "fail") + "\">" + std::to_string(r.passed()) + " passed, " +
         std::to_string(r.failed()) + " failed</span> &mdash; " + e(r.mode) + " suite, " +
         std::to_string(r.checks.size()) + " checks, " + std::to_string(r.families.size()) +
         " families</p>\n";
  out += "<p class=\"note\">This page is self-contained: the figures are embedded. The numbers "
         "behind them are in <code>data/*.csv</code> next to it, every check with full precision "
         "in <code>report.json</code>; <code>report.md</code> has the same tables.</p>\n";
  return out;
}

std::string html_contents(const ValidationReport& r) {
  std::string out = "<ul>\n<li><a href=\"#summary\">summary</a></li>\n";
  for (const auto& f : report_order(r)) {
    const auto n = std::count_if(r.checks.begin(), r.checks.end(),
                                 [&](const Check& c) { return c.family == f.name; });
    const auto bad = std::count_if(r.checks.begin(), r.checks.end(), [&](const Check& c) {
      return c.family == f.name && !c.passed;
    });
    out += "<li><a href=\"#family-" + e(f.name) + "\">" + e(f.name) + "</a>: " +
           std::to_string(n) + " checks" +
           (bad ? ", <span class=\"fail\">" + std::to_string(bad) + " failed</span>" : "") +
           "</li>\n";
  }
  return out + "<li><a href=\"#provenance\">provenance</a></li>\n</ul>\n";
}

/// Failed checks first, so a reader sees them without scrolling.
std::string html_failed(const ValidationReport& r) {
  if (r.failed() == 0) return "";
  std::string out = "<h2>Failed checks</h2>\n<ul>\n";
  for (const auto& c : r.checks)
    if (!c.passed)
      out += "<li><span class=\"fail\">FAIL</span> [" + e(c.family) + "] " + e(c.name) +
             ": measured " + e(io::format_number(c.measured)) +
             (c.expected ? ", expected " + e(io::format_number(*c.expected)) : "") + " (" +
             e(c.reference) + ")" + (c.detail.empty() ? "" : " &mdash; " + e(c.detail)) +
             "</li>\n";
  return out + "</ul>\n";
}

/// What a reader cites: the headline checks by topic, then links to every figure.
std::string html_summary(const ValidationReport& r) {
  std::string out = "<h2 id=\"summary\">Summary</h2>\n";
  for (const auto& topic : kSummaryTopics) {
    const auto checks = topic_checks(r, topic.key);
    if (checks.empty()) continue;
    out += "<h3>" + e(topic.title) + "</h3>\n<table>\n<tr><th>result</th><th>check</th>"
           "<th>measured</th><th>reference</th></tr>\n";
    for (const Check* c : checks)
      out += std::string("<tr") + (c->passed ? "" : " class=\"fail\"") + "><td class=\"" +
             (c->passed ? "pass\">pass" : "fail\">FAIL") + "</td><td>" + e(c->name) +
             "</td><td class=\"num\">" + e(io::format_number(c->measured)) + "</td><td>" +
             e(summary_note(*c)) + "</td></tr>\n";
    out += "</table>\n";
  }
  std::string figures;
  for (const auto& d : r.data_sets)
    for (const auto& fig : d.figures)
      figures += "<li><a href=\"#figure-" + e(fig.name) + "\">" + e(fig.title) + "</a></li>\n";
  if (!figures.empty()) out += "<h3>Figures</h3>\n<ul>\n" + figures + "</ul>\n";
  return out;
}

std::string html_check_rows(const ValidationReport& r, const std::string& family) {
  std::string t =
      "<table>\n<tr><th>result</th><th>check</th><th>measured</th><th>expected</th>"
      "<th>rel. error</th><th>tolerance</th><th>reference</th></tr>\n";
  for (const auto& c : r.checks) {
    if (c.family != family) continue;
    t += std::string("<tr") + (c.passed ? "" : " class=\"fail\"") + "><td class=\"" +
         (c.passed ? "pass\">pass" : "fail\">FAIL") + "</td><td>" + e(c.name) +
         "</td><td class=\"num\">" + e(io::format_number(c.measured)) + "</td><td class=\"num\">" +
         (c.expected ? e(io::format_number(*c.expected)) : "") + "</td><td class=\"num\">" +
         e(io::format_number(c.relative_error())) + "</td><td class=\"num\">" +
         e(io::format_number(c.tolerance)) + "</td><td>" + e(c.reference) +
         (c.detail.empty() ? "" : "<br><span class=\"detail\">" + e(c.detail) + "</span>") +
         "</td></tr>\n";
  }
  return t + "</table>\n";
}

std::string html_figures(const ValidationReport& r, const std::string& family,
                         const fs::path& out_dir) {
  std::string out;
  for (const auto& d : r.data_sets) {
    if (d.family != family) continue;
    if (!d.table.empty()) out += "<pre>" + e(d.table) + "</pre>\n";
    for (const auto& fig : d.figures) {
      const auto svg = read_file(out_dir / figure_file(fig));
      out += "<figure id=\"figure-" + e(fig.name) + "\">\n";
      if (svg)
        out += "<img alt=\"" + e(fig.title) + "\" src=\"data:image/svg+xml;base64," +
               base64(*svg) + "\">\n";
      else
        out += "<p class=\"fail\">figure " + e(figure_file(fig)) + " missing (figures " +
               e(figures_text(r.figures)) + ")</p>\n";
      out += "<figcaption><b>" + e(fig.title) + ".</b> " + e(fig.caption) + " Data: <code>" +
             e(data_file(d)) + "</code>.</figcaption>\n</figure>\n";
    }
    if (d.figures.empty())
      out += "<p class=\"note\">Data: <code>" + e(data_file(d)) + "</code> &mdash; " +
             e(d.description) + "</p>\n";
  }
  return out;
}

/// A family's section: its checks (folded away when there are many), then its figures.
std::string html_family(const ValidationReport& r, const FamilyInfo& f, const fs::path& out_dir) {
  std::string out = "<h2 id=\"family-" + e(f.name) + "\">" + e(f.name) + "</h2>\n<p>" +
                    e(f.description) + "</p>\n";
  const std::string rows = html_check_rows(r, f.name);
  if (folded(r, f.name))
    out += "<details><summary>" + std::to_string(family_check_count(r, f.name)) +
           " checks</summary>\n" + rows + "</details>\n";
  else
    out += rows;
  return out + html_figures(r, f.name, out_dir);
}

std::string html_provenance(const ValidationReport& r) {
  std::string out = "<h2 id=\"provenance\">Provenance</h2>\n<table class=\"prov\">\n";
  for (const auto& [label, value] : provenance_rows(r))
    out += "<tr><td>" + e(label) + "</td><td>" +
           (label == "command" ? "<code>" + e(value) + "</code>" : e(value)) + "</td></tr>\n";
  out += "<tr><td>figures</td><td>" + e(figures_text(r.figures)) + "</td></tr>\n";
  if (!r.figures.command.empty())
    out += "<tr><td>regenerate figures</td><td><code>" + e(r.figures.command) +
           "</code></td></tr>\n";
  return out + "</table>\n";
}

}  // namespace

std::string to_html(const ValidationReport& r, const fs::path& out_dir) {
  std::string out = html_head(r) + html_contents(r) + html_failed(r) + html_summary(r);
  for (const auto& f : report_order(r)) out += html_family(r, f, out_dir);
  for (const auto& family : unlisted_families(r))  // checks of families not listed (by hand)
    out += "<h2>" + e(family) + "</h2>\n" + html_check_rows(r, family);
  return out + html_provenance(r) + "</body>\n</html>\n";
}

}  // namespace rodlab::validation
