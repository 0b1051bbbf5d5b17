#include "study_support.hpp"

#include <filesystem>
#include <iostream>

#include "report/figures.hpp"

namespace rodlab::cli {

void draw_study_figures(std::vector<validation::DataSet> data, const std::string& dir) {
  validation::ValidationReport index;
  index.data_sets = std::move(data);
  const auto status = validation::run_figure_script(
      index, validation::figure_pythons(),
      std::filesystem::path(RODLAB_SOURCE_DIR) / "validation" / "make_figures.py", dir);
  std::cout << "figures " << status.state
            << (status.state == "generated" ? ": " + dir + "/figures/"
                                            : " (the study is complete without them)")
            << '\n';
  if (status.state != "generated" && !status.message.empty())
    std::cout << "  " << status.message << '\n';
}

}  // namespace rodlab::cli
