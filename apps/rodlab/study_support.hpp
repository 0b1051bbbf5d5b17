#pragma once
// What the study kinds with their own options share (study_control.cpp, study_learning.cpp):
// checking a list option's names and drawing a study's figures.
#include <algorithm>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

#include "checks/check.hpp"
#include "options.hpp"

namespace rodlab::cli {

/// Records a problem for every name of the list option `option` that is not one of `allowed`.
void check_names(OptionReader& reader, std::string_view option, const auto& allowed) {
  const auto names = reader.names(option);
  if (!names) return;
  for (const auto& n : *names)
    if (std::find(std::begin(allowed), std::end(allowed), n) == std::end(allowed)) {
      std::string list;
      for (const std::string_view a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      reader.problem(std::string(option) + ": unknown '" + n + "'; choose from " + list);
    }
}

/// The figures of a study's directory (figures.json), when python3 with matplotlib is there;
/// prints what happened.
void draw_study_figures(std::vector<validation::DataSet> data, const std::string& dir);

}  // namespace rodlab::cli
