#pragma once
// Aligned plain-text columns: the one formatter behind every table rodlab prints
// (`check`, `schemes`, `validate`, result summaries). Cells are padded to the widest cell of
// their column, columns are separated by two spaces, trailing blanks are trimmed.
#include <string>
#include <vector>

namespace rodlab::io {

class TextTable {
 public:
  enum class Align { left, right };

  /// Column alignments; columns not listed are left-aligned.
  explicit TextTable(std::vector<Align> align = {}) : align_(std::move(align)) {}

  void add_row(std::vector<std::string> cells) { rows_.push_back({std::move(cells), false}); }
  /// A line printed as is, outside the columns (e.g. a section heading); it does not widen
  /// any column.
  void add_line(std::string text) { rows_.push_back({{std::move(text)}, true}); }
  /// A rule: dashes under every column.
  void add_rule() { rows_.push_back({{}, true}); }

  std::string render() const;

 private:
  struct Row {
    std::vector<std::string> cells;
    bool verbatim;
  };
  std::vector<Align> align_;
  std::vector<Row> rows_;
};

}  // namespace rodlab::io
