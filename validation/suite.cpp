#include "suite.hpp"

#include <algorithm>
#include <chrono>

#include "rodlab/io/atomic_file.hpp"
#include "rodlab/io/text_format.hpp"

#include "checks/check.hpp"
#include "report/figures.hpp"

namespace rodlab::validation {
namespace fs = std::filesystem;

ValidationReport run_suite(const SuiteOptions& options) {
  ValidationReport report;
  report.mode = options.full ? "full" : "quick";
  report.scenes_dir = options.scenes_dir.string();
  report.provenance = collect_provenance(options.source_dir.string(), options.command_line);
  const auto& only = options.only;
  for (const auto& f : check_families())
    if (only.empty() || std::find(only.begin(), only.end(), f.name) != only.end())
      report.families.push_back({std::string(f.name), std::string(f.description)});
  DataSink sink;
  const auto start = std::chrono::steady_clock::now();
  report.checks = run_checks(
      ValidationContext{options.scenes_dir, options.full, &sink, {}, options.on_family}, only);
  report.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report.data_sets = std::move(sink.data_sets);

  const fs::path& out = options.out_dir;
  fs::create_directories(out / "data");
  fs::create_directories(out / "figures");
  for (const auto& d : report.data_sets) io::write_file_atomically(out / data_file(d), d.to_csv());
  // report.json first: the figure script reads the figure specs from it.
  const fs::path script = options.source_dir / "validation" / "make_figures.py";
  const auto pythons = figure_pythons();
  report.figures.command = pythons.front() + " " + io::shell_quote(script.string()) + " " +
                           io::shell_quote(out.string());
  io::write_file_atomically(out / "report.json", to_json(report));
  if (!options.figures) {
    report.figures.state = "skipped";
    report.figures.message = "--no-figures";
  } else {
    report.figures = run_figure_script(report, pythons, script, out);
  }
  io::write_file_atomically(out / "report.json", to_json(report));
  io::write_file_atomically(out / "report.md", to_markdown(report));
  io::write_file_atomically(out / "index.html", to_html(report, out));
  return report;
}

}  // namespace rodlab::validation
