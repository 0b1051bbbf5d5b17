#include "rodlab/io/text_table.hpp"

#include <algorithm>

namespace rodlab::io {
namespace {

/// Display width of UTF-8 text (code points; every character rodlab prints is one column).
std::size_t width(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(
      s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

}  // namespace

std::string TextTable::render() const {
  std::vector<std::size_t> widths;
  for (const auto& row : rows_) {
    if (row.verbatim) continue;
    if (widths.size() < row.cells.size()) widths.resize(row.cells.size(), 0);
    for (std::size_t c = 0; c < row.cells.size(); ++c)
      widths[c] = std::max(widths[c], width(row.cells[c]));
  }
  std::string out;
  for (const auto& row : rows_) {
    std::string line;
    if (row.verbatim && row.cells.empty()) {  // a rule: dashes under each column
      for (std::size_t c = 0; c < widths.size(); ++c) {
        if (c > 0) line += "  ";
        line.append(widths[c], '-');
      }
    } else if (row.verbatim) {
      line = row.cells.front();
    } else {
      for (std::size_t c = 0; c < row.cells.size(); ++c) {
        if (c > 0) line += "  ";
        const std::string& cell = row.cells[c];
        const std::size_t pad = widths[c] - width(cell);
        const bool right = c < align_.size() && align_[c] == Align::right;
        if (right) line.append(pad, ' ');
        line += cell;
        if (!right) line.append(pad, ' ');
      }
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line;
    out += '\n';
  }
  return out;
}

}  // namespace rodlab::io
