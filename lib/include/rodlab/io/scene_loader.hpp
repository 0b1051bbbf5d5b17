#pragma once
// Reading and checking scene files (schema rodlab.scene/1, docs/scene-reference.md).
// Every problem found is reported as `file:line:col: field.path: what is wrong (got X)`;
// values that came from a --set override are reported against that override instead of a
// file position. Loading never writes anything.
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "rodlab/scene/scene.hpp"

namespace rodlab::io {

/// One problem in a scene: where, which field, what is wrong.
struct SceneDiagnostic {
  std::string source;  ///< file path, or "--set KEY=VALUE" for an override
  int line = 0;        ///< 1-based; 0 when unknown (e.g. the file cannot be opened)
  int column = 0;      ///< 1-based; 0 when unknown
  std::string field;   ///< dotted path, e.g. rod.material.E or actuators.0.cable.tension
  std::string message; ///< e.g. "must be > 0 (got -1)"

  /// "source:line:col: field: message" (line/col omitted when 0, field when empty).
  std::string to_string() const;
};

/// Thrown for any bad scene input; what() is all diagnostics, one per line.
class SceneError : public std::runtime_error {
 public:
  explicit SceneError(std::vector<SceneDiagnostic> diagnostics);
  const std::vector<SceneDiagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<SceneDiagnostic> diagnostics_;
};

/// A --set KEY=VALUE override: KEY is a dotted path (sequence elements by index, e.g.
/// actuators.0.cable.tension), VALUE is parsed as YAML (so [0, 0, -9.81] is a list).
struct Override {
  std::string path;
  std::string value;
  std::string text;  ///< the original KEY=VALUE, for messages
};

/// Splits "KEY=VALUE"; throws SceneError (source "--set") when there is no '=' or KEY is empty.
Override parse_override(std::string_view key_equals_value);

/// Reads, overrides and checks a scene file. Throws SceneError listing every problem found.
scene::Scene load_scene(const std::string& path, std::span<const Override> overrides = {});

/// The same from YAML text (source_name is used in messages); for tests and tools.
scene::Scene load_scene_from_string(const std::string& yaml_text, const std::string& source_name,
                                    std::span<const Override> overrides = {});

}  // namespace rodlab::io
