#include "overrides.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <limits>
#include <optional>

#include "rodlab/check.hpp"

namespace rodlab::io {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

bool is_index(std::string_view segment) {
  return !segment.empty() && std::all_of(segment.begin(), segment.end(), [](char ch) {
    return std::isdigit(static_cast<unsigned char>(ch)) != 0;
  });
}

std::vector<std::string> split_path(std::string_view path) {
  std::vector<std::string> segments;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = path.find('.', start);
    segments.emplace_back(
        trim(path.substr(start, dot == std::string_view::npos ? dot : dot - start)));
    if (dot == std::string_view::npos) return segments;
    start = dot + 1;
  }
}

std::string join_path(const std::string& parent, const std::string& segment) {
  return parent.empty() ? segment : parent + "." + segment;
}

/// One segment of an override path: moves `current` (at `path`) to its child `segment`, or,
/// when `value` is given, sets that child to it. An empty `current` first becomes a map
/// (`created`). Returns what is wrong when the segment cannot be followed. An index segment is
/// normalised ("00" -> "0").
std::optional<std::string> step(YAML::Node& current, const std::string& path, std::string& segment,
                                const YAML::Node* value, bool& created) {
  const std::string parent = path.empty() ? std::string("the scene") : path;
  const auto got = [&] { return " (got " + detail::describe(current) + ")"; };
  YAML::Node child;
  if (is_index(segment)) {
    std::size_t index = 0;
    const auto [ptr, ec] = std::from_chars(segment.data(), segment.data() + segment.size(), index);
    if (ec == std::errc() && ptr == segment.data() + segment.size())
      segment = std::to_string(index);
    else
      index = std::numeric_limits<std::size_t>::max();
    if (!current.IsSequence())
      return parent + " is not a list, so it has no element " + segment + got();
    if (index >= current.size())
      return rodlab::format("no such element: {} has {} entries (got index {})", parent,
                            current.size(), segment);
    if (value)
      current[index] = *value;
    else
      child.reset(current[index]);
  } else {
    if (current.IsScalar())
      return parent + " is a single value, so it has no field " + segment + got();
    if (current.IsSequence())
      return parent + " is a list, indexed by number, so it has no field " + segment + got();
    if (!current.IsDefined() || current.IsNull()) {
      current = YAML::Node(YAML::NodeType::Map);
      created = true;
    }
    if (value)
      current[segment] = *value;
    else
      child.reset(current[segment]);
  }
  if (!value) current.reset(child);
  return std::nullopt;
}

}  // namespace

Override parse_override(std::string_view key_equals_value) {
  const std::string text(key_equals_value);
  const std::size_t eq = key_equals_value.find('=');
  const auto fail = [&](const std::string& message) {
    throw SceneError(
        {SceneDiagnostic{"--set", 0, 0, "", rodlab::format("{} (got {})", message, text)}});
  };
  if (eq == std::string_view::npos) fail("expected KEY=VALUE, e.g. rod.material.E=2e6");
  const std::string_view key = trim(key_equals_value.substr(0, eq));
  if (key.empty()) fail("the KEY in KEY=VALUE is empty");
  return Override{std::string(key), std::string(key_equals_value.substr(eq + 1)), text};
}

namespace detail {

std::string override_source(const Override& o) {
  return "--set " + (o.text.empty() ? o.path + "=" + o.value : o.text);
}

std::vector<OverrideOrigin> apply_overrides(YAML::Node& root, std::span<const Override> overrides,
                                            std::vector<SceneDiagnostic>& diagnostics) {
  std::vector<OverrideOrigin> origins;
  for (const Override& o : overrides) {
    const std::string source = override_source(o);
    const auto fail = [&](const std::string& field, const std::string& message) {
      diagnostics.push_back(SceneDiagnostic{source, 0, 0, field, message});
    };

    std::vector<std::string> segments = split_path(o.path);
    if (std::any_of(segments.begin(), segments.end(), [](const auto& s) { return s.empty(); })) {
      const std::string example = "e.g. actuators.0.cable.tension";
      fail("", "KEY must be a dotted path of names and list indices, " + example + " (got " +
                   o.path + ")");
      continue;
    }
    YAML::Node value;
    try {
      value = YAML::Load(o.value);
    } catch (const YAML::Exception& e) {
      fail(o.path, "the value is not valid YAML: " + e.msg + " (got " + o.value + ")");
      continue;
    }

    YAML::Node current;  // rebound with reset(): assigning would overwrite the node itself
    current.reset(root);
    std::string path;  // of `current`
    for (std::size_t i = 0; i < segments.size(); ++i) {
      const bool last = i + 1 == segments.size();
      bool created = false;
      const auto problem = step(current, path, segments[i], last ? &value : nullptr, created);
      if (created) origins.push_back({path, source});
      if (problem) {
        fail(join_path(path, segments[i]), *problem);
        break;
      }
      path = join_path(path, segments[i]);
      if (last) origins.push_back({path, source});
    }
  }
  return origins;
}

}  // namespace detail
}  // namespace rodlab::io
