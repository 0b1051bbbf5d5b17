// Entry points: read the YAML, apply --set overrides, check every section, build the Scene.
#include "rodlab/io/scene_loader.hpp"

#include <algorithm>
#include <cstdint>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "rodlab/check.hpp"

#include "overrides.hpp"
#include "scene_readers.hpp"
#include "yaml_documents.hpp"

namespace rodlab::io {
namespace {

/// A scene is a few kilobytes; this bounds what a mistaken path can make the loader read.
constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;

std::string join_lines(const std::vector<SceneDiagnostic>& diagnostics) {
  std::string out;
  for (const auto& d : diagnostics) {
    if (!out.empty()) out += '\n';
    out += d.to_string();
  }
  return out;
}

[[noreturn]] void fail(const std::string& source, int line, int column,
                       const std::string& message) {
  throw SceneError({SceneDiagnostic{source, line, column, "", message}});
}

/// File problems in the order of their position, then override problems in the order the
/// overrides were given.
void sort_diagnostics(std::vector<SceneDiagnostic>& diagnostics, const std::string& source,
                      std::span<const Override> overrides) {
  const auto rank = [&](const SceneDiagnostic& d) {
    if (d.source == source) return std::tuple(0, d.line, d.column);
    std::size_t k = 0;
    while (k < overrides.size() && detail::override_source(overrides[k]) != d.source) ++k;
    return std::tuple(1 + static_cast<int>(k), 0, 0);
  };
  std::stable_sort(diagnostics.begin(), diagnostics.end(),
                   [&](const auto& a, const auto& b) { return rank(a) < rank(b); });
}

scene::Scene read_scene(detail::Checker& c, const detail::Field& root,
                        const std::string& source_name) {
  using detail::Checker;
  using detail::Field;
  scene::Scene s;
  c.keys(root,
         {"schema", "name", "rod", "base", "tip", "loads", "actuators", "dynamics", "solver",
          "control", "learning"});

  const Field schema = c.require(root, "schema");
  if (auto text = c.text(schema); text && *text != scene::kSceneSchema)
    c.error(schema, std::string("must be ") + scene::kSceneSchema +
                        ", the schema this version of rodlab reads (got " +
                        detail::describe(schema.node) + ")");

  const Field name = Checker::child(root, "name");
  s.name = std::filesystem::path(source_name).stem().string();
  if (auto text = c.text(name)) {
    if (text->empty())
      c.error(name, "must not be empty");
    else
      s.name = *text;
  }

  s.rod = detail::read_rod(c, c.require(root, "rod"));
  s.base = detail::read_base(c, Checker::child(root, "base"));
  if (auto tip = detail::read_tip(c, c.require(root, "tip"))) s.tip = *tip;
  s.loads = detail::read_loads(c, Checker::child(root, "loads"));
  const std::optional<double> length =
      s.rod.length > 0.0 ? std::optional<double>(s.rod.length) : std::nullopt;
  const Field actuators = Checker::child(root, "actuators");
  s.actuators = detail::read_actuators(c, actuators, length);
  if (const Field dynamics = Checker::child(root, "dynamics"); dynamics.present())
    s.dynamics = detail::read_dynamics(c, dynamics);
  s.solver = detail::read_solver(c, Checker::child(root, "solver"));
  if (const Field control = Checker::child(root, "control"); control.present())
    s.control = detail::read_control(c, control, actuators, s.actuators);
  if (const Field learning = Checker::child(root, "learning"); learning.present())
    s.learning = detail::read_learning(c, learning);

  if (c.error_count() == 0) {
    // Safety net: the rod model checks its own arguments; nothing above should let it throw.
    try {
      (void)s.rod.to_model();
    } catch (const std::invalid_argument& e) {
      c.error(Checker::child(root, "rod"), e.what());
    }
  }
  return s;
}

}  // namespace

std::string SceneDiagnostic::to_string() const {
  std::string out = source;
  if (line > 0)
    out += column > 0 ? rodlab::format(":{}:{}", line, column) : rodlab::format(":{}", line);
  out += ": ";
  if (!field.empty()) out += field + ": ";
  out += message;
  return out;
}

SceneError::SceneError(std::vector<SceneDiagnostic> diagnostics)
    : std::runtime_error(join_lines(diagnostics)), diagnostics_(std::move(diagnostics)) {}

scene::Scene load_scene_from_string(const std::string& yaml_text, const std::string& source_name,
                                    std::span<const Override> overrides) {
  detail::YamlDocuments documents;
  try {
    documents = detail::read_documents(yaml_text);
  } catch (const YAML::Exception& e) {
    const bool at = !e.mark.is_null();
    fail(source_name, at ? e.mark.line + 1 : 0, at ? e.mark.column + 1 : 0,
         "YAML syntax error: " + e.msg);
  }
  if (documents.count == 0 || (documents.count == 1 && documents.first.IsNull()))
    fail(source_name, 0, 0, "the scene is empty");
  if (documents.count > 1) {
    const YAML::Mark m = documents.starts[1];
    fail(source_name, m.line + 1, m.column + 1,
         rodlab::format("a scene is a single YAML document (got {} documents separated by ---)",
                        documents.count));
  }
  YAML::Node root = documents.first;
  if (!root.IsMap()) {
    const YAML::Mark m = root.Mark();
    fail(source_name, m.line + 1, m.column + 1,
         "a scene must be a map of sections (schema, rod, tip, ...) (got " +
             detail::describe(root) + ")");
  }

  std::vector<SceneDiagnostic> diagnostics;
  auto origins = detail::apply_overrides(root, overrides, diagnostics);
  detail::Checker checker(source_name, std::move(origins));
  scene::Scene scene = read_scene(checker, detail::Checker::root(root), source_name);
  for (auto& d : checker.take_diagnostics()) diagnostics.push_back(std::move(d));
  if (!diagnostics.empty()) {
    sort_diagnostics(diagnostics, source_name, overrides);
    throw SceneError(std::move(diagnostics));
  }
  scene.source_path = source_name;
  return scene;
}

scene::Scene load_scene(const std::string& path, std::span<const Override> overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, 0, 0, "is a directory, not a scene file");
  // Read only regular files of bounded size: a device (/dev/zero) or a FIFO without a writer
  // would be read, or waited on, forever.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    fail(path, 0, 0, "is not a regular file (a device, FIFO or socket); a scene is a YAML file");
  if (const auto size = std::filesystem::file_size(path, ec); !ec && size > kMaxSceneBytes)
    fail(path, 0, 0,
         rodlab::format("is {} bytes; a scene file has at most {} bytes", size, kMaxSceneBytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, 0, 0, std::string("cannot open the scene file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad())
    fail(path, 0, 0, std::string("cannot read the scene file: ") + std::strerror(errno));
  return load_scene_from_string(text.str(), path, overrides);
}

}  // namespace rodlab::io
