#pragma once
// Reading YAML nodes with checking (private to rodlab::io). Every reader takes a Field (a node,
// its dotted path and its position), reports what is wrong with it to the Checker, and returns
// std::nullopt when the field is absent or bad; a scene is only built when nothing was reported.
// Absence is reported by Checker::require, never by the value readers, so an optional field
// is simply `if (auto v = c.number(c.child(map, "key"), Range::positive())) out = *v;`.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <cstddef>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/scene/schedule.hpp"

namespace rodlab::io::detail {

/// A node with the dotted path that names it in messages and the position to report it at
/// (a null value is reported at its key; an absent one at its parent map).
struct Field {
  YAML::Node node;
  std::string path;
  YAML::Mark mark;      ///< where problems with the value are reported
  YAML::Mark key_mark;  ///< where its key is (the value's position for list elements)
  bool exists = false;  ///< false when absent

  bool present() const { return exists; }
};

/// An interval a number must lie in; bounds are open or closed, infinite when not given.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() {
    return {0.0, std::numeric_limits<double>::infinity(), false, false};
  }
  static Range at_least(double lo) {
    return {lo, std::numeric_limits<double>::infinity(), false, false};
  }

  bool contains(double x) const;
  /// "must be > 0", "must be >= 0", "must be in (-1, 0.5]".
  std::string requirement() const;
};

/// Which override a field came from: a field whose path is `path` or lies below it is
/// reported against `source` ("--set KEY=VALUE") instead of a file position.
struct OverrideOrigin {
  std::string path;
  std::string source;
};

/// Result of Checker::keys: whether the node is a map (or empty) and how many keys were unknown.
struct KeyCheck {
  bool map = false;
  int unknown = 0;
  explicit operator bool() const { return map; }
};

/// The text of a number for messages: shortest form that reads back exactly ("0.1", "1e-06").
std::string format_number(double x);

/// A node as text for "(got X)": the scalar as written (quoted if it was a quoted string),
/// lists and maps in flow style (shortened when long), "nothing" for an empty value.
std::string describe(const YAML::Node& node);

class Checker {
 public:
  Checker(std::string source, std::vector<OverrideOrigin> origins);

  // -- reporting
  void error(const YAML::Mark& mark, std::string_view path, std::string message);
  void error(const Field& at, std::string message) { error(at.mark, at.path, std::move(message)); }
  std::size_t error_count() const { return diagnostics_.size(); }
  std::vector<SceneDiagnostic> take_diagnostics() { return std::move(diagnostics_); }

  // -- navigation (reports nothing)
  static Field root(const YAML::Node& node);
  /// The value of `key` in a map (first occurrence); absent if the map lacks it or is not a map.
  static Field child(const Field& map, std::string_view key);
  static Field element(const Field& list, std::size_t index);

  // -- structure
  /// True for a map or an empty value (read as an empty map); reports anything else.
  bool is_map(const Field& f);
  /// Checks a map's keys: each must be a plain name, appear once and be one of `allowed`
  /// (`what` names them in messages: "key", "actuator type").
  KeyCheck keys(const Field& map, std::initializer_list<std::string_view> allowed,
                std::string_view what = "key");
  /// The field `key`; reports `key: is required` at the map when it is absent (unless an
  /// unknown key in the map was already reported as a misspelling of it).
  Field require(const Field& map, std::string_view key);
  /// Which one of `options` the map has. Reports two or more present; reports none present
  /// when `required`. nullopt unless exactly one is present.
  std::optional<std::string_view> exactly_one(const Field& map,
                                              std::initializer_list<std::string_view> options,
                                              bool required);
  /// Reports `one of a, b is required` at the map unless it has at least one of `options`.
  bool at_least_one(const Field& map, std::initializer_list<std::string_view> options);
  /// The elements of a list (an empty value reads as an empty list); reports a non-list, and a
  /// list shorter than `min_size`.
  std::optional<std::vector<Field>> list(const Field& f, std::size_t min_size = 0);

  // -- values
  std::optional<double> number(const Field& f, const Range& range = Range::any());
  std::optional<int> integer(const Field& f, int min);
  std::optional<std::string> text(const Field& f);
  /// The index of the option the field names; reports "must be one of a, b, c (got x)".
  std::optional<std::size_t> choice(const Field& f, std::span<const std::string_view> options);
  std::optional<std::size_t> choice(const Field& f,
                                    std::initializer_list<std::string_view> options) {
    return choice(f, std::span<const std::string_view>(options.begin(), options.size()));
  }
  /// true or false, spelled so (YAML's yes/no/on/off are reported, not guessed).
  std::optional<bool> boolean(const Field& f) {
    const auto k = choice(f, {"false", "true"});
    return k ? std::optional<bool>(*k == 1) : std::nullopt;
  }
  /// A list of exactly `size` numbers, each in `range`.
  std::optional<Eigen::VectorXd> numbers(const Field& f, Eigen::Index size,
                                         const Range& range = Range::any());
  template <int N>
  std::optional<Eigen::Matrix<double, N, 1>> vector(const Field& f,
                                                    const Range& range = Range::any()) {
    auto v = numbers(f, N, range);
    if (!v) return std::nullopt;
    return Eigen::Matrix<double, N, 1>(*v);
  }
  /// A 3x3 matrix as a list of three rows of three numbers.
  std::optional<Eigen::Matrix3d> matrix3(const Field& f);

  /// A constant (read by read_value) or {steps: [[t, v], ...]} / {ramp: [[t, v], ...]}.
  template <class Value, class ReadValue>
  std::optional<scene::Schedule<Value>> schedule(const Field& f, ReadValue read_value);

 private:
  struct ScheduleEntries {
    bool steps = false;
    bool ok = true;
    std::vector<std::pair<double, Field>> entries;  ///< (time, value field)
  };
  /// The structure and the times of a schedule map; values are left to the caller.
  std::optional<ScheduleEntries> schedule_entries(const Field& f);

  std::string source_;
  std::vector<OverrideOrigin> origins_;
  /// Paths that an unknown key was taken for a misspelling of ("did you mean length?"):
  /// require() and at_least_one() do not report them missing as well.
  std::vector<std::string> suggested_;
  bool was_suggested(const std::string& path) const;
  /// The override a field came from, or nullptr if it is the file's.
  const OverrideOrigin* origin_of(std::string_view path) const;
  std::vector<SceneDiagnostic> diagnostics_;
};

template <class Value, class ReadValue>
std::optional<scene::Schedule<Value>> Checker::schedule(const Field& f, ReadValue read_value) {
  if (!f.present()) return std::nullopt;
  if (!f.node.IsMap()) {
    std::optional<Value> v = read_value(f);
    if (!v) return std::nullopt;
    return scene::Schedule<Value>(*v);
  }
  auto se = schedule_entries(f);
  if (!se) return std::nullopt;
  std::vector<std::pair<double, Value>> points;
  bool ok = se->ok;
  for (const auto& [t, value_field] : se->entries) {
    std::optional<Value> v = read_value(value_field);
    if (v)
      points.emplace_back(t, *v);
    else
      ok = false;
  }
  if (!ok) return std::nullopt;
  using Kind = typename scene::Schedule<Value>::Kind;
  return scene::Schedule<Value>(se->steps ? Kind::steps : Kind::ramp, std::move(points));
}

/// "a, b, c".
std::string join(std::span<const std::string_view> names);
inline std::string join(std::initializer_list<std::string_view> names) {
  return join(std::span<const std::string_view>(names.begin(), names.size()));
}

/// Whether a scalar reads as a number (finite or not); lets callers accept a keyword instead.
bool looks_like_number(const YAML::Node& node);

}  // namespace rodlab::io::detail
