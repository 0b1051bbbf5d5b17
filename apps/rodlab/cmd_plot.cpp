// rodlab plot RESULT [--out FILE]: a picture of a result file (static, dynamic, workspace,
// control) or of a convergence or work-precision study, drawn by scripts/rodlab_plot.py with
// matplotlib. This file checks the arguments (exit 2, nothing written) and runs the script.
#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "rodlab/io/result_writer.hpp"
#include "rodlab/io/text_format.hpp"

#include "report/figures.hpp"
#include "command.hpp"
#include "common_options.hpp"
#include "errors.hpp"
#include "exit_status.hpp"

namespace rodlab::cli {
namespace {
namespace fs = std::filesystem;

constexpr std::string_view kStudySchema = "rodlab.study/1";  // every study.json
/// What plot draws: the result schemas, and the kinds of study.
constexpr std::array<std::string_view, 5> kSchemas{
    io::kStaticResultSchema, io::kDynamicResultSchema, io::kWorkspaceResultSchema,
    io::kControlResultSchema, kStudySchema};
constexpr std::array<std::string_view, 2> kStudyKinds{"convergence", "work-precision"};
/// Pictures, then the animations (of a dynamic result's tip only).
constexpr std::array<std::string_view, 3> kPictureExtensions{".png", ".svg", ".pdf"};
constexpr std::array<std::string_view, 2> kAnimationExtensions{".gif", ".mp4"};

constexpr std::array<std::string_view, 1> kPositionals{"RESULT"};
constexpr std::array<OptionSpec, 1> kOptions{OptionSpec{
    "--out", "FILE",
    "the picture: .png, .svg or .pdf; for a dynamic result also an animation of the tip, .gif "
    "or .mp4 (needs ffmpeg); its directory must exist; default: RESULT with .png (a study "
    "directory: DIR/study.png)"}};

template <std::size_t N>
bool one_of(std::string_view value, const std::array<std::string_view, N>& values) {
  return std::find(values.begin(), values.end(), value) != values.end();
}

template <std::size_t N>
std::string listed(const std::array<std::string_view, N>& values) {
  std::vector<std::string> names(values.begin(), values.end());
  return io::join(names);
}

/// The result to draw: its JSON file (a study's study.json when RESULT is its directory), the
/// schema and, for a study, its kind.
struct PlotInput {
  fs::path file;
  std::string schema;
  std::string kind;
};

/// Reads RESULT far enough to know that plot can draw it; nullopt (and the problem recorded)
/// when it cannot: missing, not JSON (a .csv result has no schema), no known schema, or a study
/// of another kind.
std::optional<PlotInput> read_result(OptionReader& reader, const fs::path& result) {
  std::error_code ec;
  const fs::path file = fs::is_directory(result, ec) ? result / "study.json" : result;
  const std::string name = "RESULT " + file.string();
  if (!fs::is_regular_file(file, ec)) {
    reader.problem(name + ": no such file" +
                   (file == result ? "" : " (a study directory holds study.json)"));
    return std::nullopt;
  }
  std::ifstream in(file);
  if (!in) {
    reader.problem(name + ": cannot read it");
    return std::nullopt;
  }
  const auto json = nlohmann::json::parse(in, nullptr, false);  // discarded when not JSON
  if (json.is_discarded()) {
    reader.problem(name + ": not JSON (plot reads JSON result files; a .csv result has no "
                          "schema: write it with --out FILE.json)");
    return std::nullopt;
  }
  PlotInput input{file, json.is_object() ? json.value("schema", std::string()) : "", ""};
  if (!one_of(input.schema, kSchemas)) {
    reader.problem(name + ": not a rodlab result plot can draw (schema '" + input.schema +
                   "'; plot draws " + listed(kSchemas) + ")");
    return std::nullopt;
  }
  if (input.schema == kStudySchema) {
    input.kind = json.value("kind", std::string());
    if (!one_of(input.kind, kStudyKinds)) {
      reader.problem(name + ": a " + (input.kind.empty() ? "study of no kind" : input.kind +
                     " study") + "; plot draws the " + std::string(kStudyKinds[0]) + " and " +
                     std::string(kStudyKinds[1]) + " studies (study control and learning "
                     "draw their own figures into DIR/figures/)");
      return std::nullopt;
    }
  }
  return input;
}

/// --out FILE, or its default beside RESULT; nullopt (and the problem recorded) when its
/// extension is not one plot writes, its directory is missing, it would replace the result,
/// or it asks for an animation of anything but a dynamic result.
std::optional<fs::path> read_out(OptionReader& reader, const fs::path& result,
                                 const std::optional<PlotInput>& input) {
  std::error_code ec;
  const auto text = reader.text("--out");
  fs::path out = text ? fs::path(*text)
                      : (fs::is_directory(result, ec) ? result / "study.png"
                                                      : fs::path(result).replace_extension(".png"));
  const std::string ext = out.extension().string();
  const bool animation = one_of(ext, kAnimationExtensions);
  bool ok = check_out_file_place(reader, out);
  if (!animation && !one_of(ext, kPictureExtensions)) {
    reader.problem("--out: " + out.string() + ": the file must end in " +
                   listed(kPictureExtensions) + " or, for a dynamic result, " +
                   listed(kAnimationExtensions));
    ok = false;
  } else if (animation && input && input->schema != io::kDynamicResultSchema) {
    reader.problem("--out: " + out.string() + ": an animation is drawn from a dynamic result "
                   "only (RESULT is " + input->schema + ")");
    ok = false;
  }
  if (input && fs::exists(out, ec) && fs::equivalent(out, input->file, ec)) {
    reader.problem("--out: " + out.string() + " is RESULT itself");
    ok = false;
  }
  return ok ? std::optional(out) : std::nullopt;
}

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const fs::path result = inv.args.positionals().front();
  const auto input = read_result(reader, result);
  const auto out = read_out(reader, result, input);
  reader.finish();  // every problem above is bad input: exit 2, nothing written

  const fs::path script = fs::path(RODLAB_SOURCE_DIR) / "scripts" / "rodlab_plot.py";
  std::error_code ec;
  if (!fs::is_regular_file(script, ec)) {
    std::cerr << "rodlab plot: error: the plot script " << script.string()
              << " is missing (rodlab plot runs it from the source tree)\n";
    return kFailed;
  }
  std::string unavailable;
  const auto run = validation::run_python_script(
      validation::figure_pythons(), script, {input->file.string(), out->string()}, unavailable);
  if (!unavailable.empty()) {
    std::cerr << "rodlab plot: error: cannot draw " << out->string() << ": " << unavailable
              << '\n';
    return kFailed;
  }
  if (run.exit_code != 0 || !fs::is_regular_file(*out, ec)) {
    std::cerr << "rodlab plot: error: drawing " << out->string() << " failed (" << run.command
              << ": exit status " << run.exit_code << "):\n"
              << validation::output_tail(run.output, 15) << '\n';
    return kFailed;
  }
  std::cout << "figure written to " << out->string() << '\n';
  return kSolved;
}

}  // namespace

const Command& plot_command() {
  static const Command command{
      "plot",
      "RESULT [--out FILE]",
      "draw a result file or a study with matplotlib: shape, tip, energies, point cloud",
      "Draws RESULT, a JSON result file of rodlab or a study (its directory or study.json),\n"
      "with matplotlib (scripts/rodlab_plot.py, run by $RODLAB_PYTHON, else python3, else\n"
      "/usr/bin/python3):\n"
      "  static result     the rod's centreline in 3D, equal axes, base and tip marked;\n"
      "  dynamic result    the tip's coordinates and the energies against t, and in 3D the\n"
      "                    final centreline with the tip's trajectory; --out X.gif or X.mp4\n"
      "                    animates the tip along its trajectory (a dynamic result holds the\n"
      "                    tip's series and the final centreline only: the shape does not move);\n"
      "  workspace result  the converged tips as a point cloud in 3D, coloured by curvature;\n"
      "  control result    the tip and the target against t (x, y, z), and the tip error;\n"
      "  study             convergence: error against ds or dt, log-log, with the expected\n"
      "                    orders' slopes; work-precision: error against median wall time with\n"
      "                    the Pareto front.\n"
      "The arguments are checked before anything runs. The figure is written atomically.\n"
      "\n"
      "Exit status: 0 the figure is written; 1 it could not be drawn (no python3 with\n"
      "matplotlib, .mp4 without ffmpeg, the script failed; the message says which);\n"
      "2 bad input or usage (nothing is written).\n",
      kPositionals,
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
