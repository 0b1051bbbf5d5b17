#include "report.hpp"

#include <nlohmann/json.hpp>

#include "rodlab/io/text_format.hpp"
#include "rodlab/io/text_table.hpp"

#include "overloaded.hpp"

namespace rodlab::cli {
namespace {

std::string with_unit(std::string value, const std::string& unit) {
  return unit.empty() ? value : value + " " + unit;
}

/// One aligned row: label, symbol, "=" (when there is a symbol), value with unit.
void add_row(io::TextTable& table, const std::string& label, const std::string& symbol,
             const std::string& value, const std::string& unit) {
  table.add_row({"  " + label, symbol, symbol.empty() ? "" : "=", with_unit(value, unit)});
}

void add_item_rows(io::TextTable& table, const ReportItem& item) {
  const auto row = [&](const std::string& value) {
    add_row(table, item.label, item.symbol, value, item.unit);
  };
  std::visit(Overloaded{
                 [&](const std::string& v) { row(v); },
                 [&](double v) { row(io::format_number(v)); },
                 [&](long long v) { row(std::to_string(v)); },
                 [&](bool v) { row(v ? "yes" : "no"); },
                 [&](const std::vector<double>& v) {
                   if (item.component_labels.size() != v.size()) {
                     row(io::format_vector(Eigen::Map<const Eigen::VectorXd>(
                         v.data(), static_cast<Eigen::Index>(v.size()))));
                     return;
                   }
                   for (std::size_t i = 0; i < v.size(); ++i) {
                     std::string symbol = item.symbol + "[" + std::to_string(i) + "]";
                     if (i < item.component_formulas.size())
                       (symbol += " = ") += item.component_formulas[i];
                     add_row(table, item.component_labels[i], symbol, io::format_number(v[i]),
                             i < item.component_units.size() ? item.component_units[i] : item.unit);
                   }
                 },
                 [&](const std::vector<std::string>& v) {
                   if (v.empty()) add_row(table, item.label, "", "none", "");
                   for (std::size_t i = 0; i < v.size(); ++i)
                     add_row(table, i == 0 ? item.label : std::string(), "", v[i], "");
                 },
             },
             item.value);
}

}  // namespace

std::string render_text(const Report& report) {
  io::TextTable table;
  for (const auto& section : report.sections) {
    table.add_line(section.title);
    for (const auto& item : section.items) add_item_rows(table, item);
  }
  return table.render();
}

std::string render_json(const Report& report) {
  nlohmann::ordered_json json;
  json["schema"] = report.schema;
  nlohmann::ordered_json units = nlohmann::ordered_json::object();
  for (const auto& section : report.sections) {
    nlohmann::ordered_json object = nlohmann::ordered_json::object();
    for (const auto& item : section.items) {
      std::visit([&](const auto& v) { object[item.key] = v; }, item.value);
      const std::string name = section.key + "." + item.key;
      if (!item.component_units.empty())
        units[name] = item.component_units;
      else if (!item.unit.empty())
        units[name] = item.unit;
    }
    json[section.key] = std::move(object);
  }
  json["units"] = std::move(units);
  return json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

}  // namespace rodlab::cli
