#include "yaml_checker.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numeric>

#include "rodlab/check.hpp"

namespace rodlab::io::detail {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

/// Optimal string alignment distance (Levenshtein with transpositions), case-insensitive.
std::size_t edit_distance(std::string_view a_in, std::string_view b_in) {
  const std::string a = lower(a_in), b = lower(b_in);
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  }
  return d[a.size()][b.size()];
}

/// The allowed name closest to a misspelt one, if it is close (at most 2 edits, fewer than its
/// length).
std::optional<std::string_view> suggestion(std::string_view name,
                                           std::span<const std::string_view> allowed) {
  std::optional<std::string_view> best;
  std::size_t best_d = 3;
  for (std::string_view a : allowed) {
    const std::size_t d = edit_distance(name, a);
    if (d < best_d && d < a.size()) {
      best_d = d;
      best = a;
    }
  }
  return best;
}

bool quoted_string(const YAML::Node& n) {
  return n.Tag() == "!" || n.Tag() == "tag:yaml.org,2002:str";
}

enum class Parse { ok, not_a_number, non_finite, out_of_range };

/// A YAML number: decimal or exponent form with an optional sign, or .inf / .nan (non-finite).
std::pair<Parse, double> parse_number(std::string_view text) {
  std::string_view body = text;
  if (!body.empty() && (body.front() == '+' || body.front() == '-')) body.remove_prefix(1);
  const std::string special = lower(body);
  if (special == ".inf" || special == ".nan" || special == "inf" || special == "nan" ||
      special == "infinity")
    return {Parse::non_finite, 0.0};
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) return {Parse::out_of_range, 0.0};
  if (ec != std::errc() || ptr != text.data() + text.size() || text.empty())
    return {Parse::not_a_number, 0.0};
  return {Parse::ok, value};
}

bool within(std::string_view path, std::string_view prefix) {
  return path == prefix ||
         (path.size() > prefix.size() && path.starts_with(prefix) && path[prefix.size()] == '.');
}

/// A map, or an empty value read as one.
bool map_like(const Field& f) { return f.exists && (f.node.IsMap() || f.node.IsNull()); }

std::string sub_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

}  // namespace

bool Range::contains(double x) const {
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

std::string Range::requirement() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return "must be in " + std::string(lo_open ? "(" : "[") + format_number(lo) + ", " +
           format_number(hi) + (hi_open ? ")" : "]");
  if (has_lo) return std::string("must be ") + (lo_open ? "> " : ">= ") + format_number(lo);
  if (has_hi) return std::string("must be ") + (hi_open ? "< " : "<= ") + format_number(hi);
  return "must be a number";
}

std::string format_number(double x) {
  std::array<char, 32> buf{};
  const auto [ptr, ec] = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  return ec == std::errc() ? std::string(buf.data(), ptr) : std::string("?");
}

std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsScalar()) return quoted_string(node) ? "\"" + node.Scalar() + "\"" : node.Scalar();
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << node;
  std::string text = out.c_str();
  std::replace(text.begin(), text.end(), '\n', ' ');
  constexpr std::size_t kMax = 60;
  if (text.size() > kMax) text = text.substr(0, kMax - 3) + "...";
  return text;
}

std::string join(std::span<const std::string_view> names) {
  std::string out;
  for (std::string_view n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

Checker::Checker(std::string source, std::vector<OverrideOrigin> origins)
    : source_(std::move(source)), origins_(std::move(origins)) {}

void Checker::error(const YAML::Mark& mark, std::string_view path, std::string message) {
  SceneDiagnostic d;
  d.field = std::string(path);
  d.message = std::move(message);
  if (const OverrideOrigin* origin = origin_of(path)) {
    d.source = origin->source;
  } else {
    d.source = source_;
    if (!mark.is_null()) {
      d.line = mark.line + 1;
      d.column = mark.column + 1;
    }
  }
  diagnostics_.push_back(std::move(d));
}

const OverrideOrigin* Checker::origin_of(std::string_view path) const {
  // The latest override that covers the path is where the value came from.
  const auto origin = std::find_if(origins_.rbegin(), origins_.rend(),
                                   [&](const OverrideOrigin& o) { return within(path, o.path); });
  return origin == origins_.rend() ? nullptr : &*origin;
}

Field Checker::root(const YAML::Node& node) { return {node, "", node.Mark(), node.Mark(), true}; }

Field Checker::child(const Field& map, std::string_view key) {
  const std::string path = sub_path(map.path, key);
  if (map.exists && map.node.IsMap()) {
    // Range-for keeps each (key, value) alive; `it->first` would be a dangling temporary.
    for (const auto& pair : map.node) {
      if (pair.first.IsScalar() && pair.first.Scalar() == key) {
        const YAML::Mark key_mark = pair.first.Mark();
        const YAML::Mark mark = pair.second.IsNull() ? key_mark : pair.second.Mark();
        return {pair.second, path, mark, key_mark, true};
      }
    }
  }
  return {YAML::Node(), path, map.mark, map.mark, false};
}

Field Checker::element(const Field& list, std::size_t index) {
  const YAML::Node n = list.node[index];
  const YAML::Mark mark = n.IsNull() ? list.mark : n.Mark();
  return {n, sub_path(list.path, std::to_string(index)), mark, mark, true};
}

bool Checker::was_suggested(const std::string& path) const {
  return std::find(suggested_.begin(), suggested_.end(), path) != suggested_.end();
}

bool Checker::is_map(const Field& f) {
  if (!f.exists) return false;
  if (map_like(f)) return true;
  error(f, "must be a map (got " + describe(f.node) + ")");
  return false;
}

KeyCheck Checker::keys(const Field& map, std::initializer_list<std::string_view> allowed,
                       std::string_view what) {
  KeyCheck result;
  if (!is_map(map)) return result;
  result.map = true;
  if (map.node.IsNull()) return result;
  std::vector<std::pair<std::string, YAML::Mark>> seen;
  for (const auto& pair : map.node) {
    const YAML::Node& key = pair.first;
    if (!key.IsScalar()) {
      error(key.Mark(), map.path, "keys must be plain names (got " + describe(key) + ")");
      ++result.unknown;
      continue;
    }
    const std::string& name = key.Scalar();
    const std::string path = sub_path(map.path, name);
    const auto first =
        std::find_if(seen.begin(), seen.end(), [&](const auto& s) { return s.first == name; });
    if (first != seen.end()) {
      // Lines inside an override's VALUE would be misleading: say where only for the file.
      const bool in_file = !first->second.is_null() && !origin_of(path);
      error(key.Mark(), path,
            in_file ? rodlab::format("duplicate key (first given at line {})",
                                     first->second.line + 1)
                    : std::string("duplicate key"));
      continue;
    }
    seen.emplace_back(name, key.Mark());
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    ++result.unknown;
    if (name == "<<") {
      error(key.Mark(), path, "YAML merge keys are not supported; write the fields out");
      continue;
    }
    std::string message = "unknown " + std::string(what);
    if (const auto near = suggestion(name, {allowed.begin(), allowed.size()})) {
      message += " (did you mean " + std::string(*near) + "?)";
      suggested_.push_back(sub_path(map.path, *near));
    }
    message += "; valid " + std::string(what) + "s: " + join(allowed);
    error(key.Mark(), path, std::move(message));
  }
  return result;
}

Field Checker::require(const Field& map, std::string_view key) {
  Field f = child(map, key);
  if (!f.exists && map_like(map) && !was_suggested(f.path)) error(map.mark, f.path, "is required");
  return f;
}

std::optional<std::string_view> Checker::exactly_one(
    const Field& map, std::initializer_list<std::string_view> options, bool required) {
  if (!map_like(map)) return std::nullopt;
  std::vector<std::string_view> given;
  for (std::string_view o : options)
    if (child(map, o).exists) given.push_back(o);
  if (given.size() == 1) return given.front();
  if (given.empty()) {
    if (required) at_least_one(map, options);
    return std::nullopt;
  }
  std::string got;
  for (std::size_t i = 0; i < given.size(); ++i)
    got += (i == 0 ? "" : i + 1 == given.size() ? " and " : ", ") + std::string(given[i]);
  const Field second = child(map, given[1]);
  error(second.key_mark, second.path, "give only one of " + join(options) + " (got " + got + ")");
  return std::nullopt;
}

bool Checker::at_least_one(const Field& map, std::initializer_list<std::string_view> options) {
  if (!map_like(map)) return false;
  const auto has = [&](std::string_view o) { return child(map, o).exists; };
  if (std::any_of(options.begin(), options.end(), has)) return true;
  const auto misspelt = [&](std::string_view o) { return was_suggested(sub_path(map.path, o)); };
  if (!std::any_of(options.begin(), options.end(), misspelt))
    error(map.mark, map.path, "one of " + join(options) + " is required");
  return false;
}

std::optional<std::vector<Field>> Checker::list(const Field& f, std::size_t min_size) {
  if (!f.exists) return std::nullopt;
  if (!f.node.IsSequence() && !f.node.IsNull()) {
    error(f, "must be a list (got " + describe(f.node) + ")");
    return std::nullopt;
  }
  const std::size_t n = f.node.IsNull() ? 0 : f.node.size();
  if (n < min_size) {
    error(f, min_size == 1 ? std::string("must not be empty")
                           : rodlab::format("must have at least {} entries (got {})", min_size, n));
    return std::nullopt;
  }
  std::vector<Field> items;
  items.reserve(n);
  for (std::size_t i = 0; i < n; ++i) items.push_back(element(f, i));
  return items;
}

std::optional<double> Checker::number(const Field& f, const Range& range) {
  if (!f.exists) return std::nullopt;
  const std::string got = " (got " + describe(f.node) + ")";
  if (!f.node.IsScalar()) {
    error(f, "must be a number" + got);
    return std::nullopt;
  }
  if (quoted_string(f.node)) {
    error(f, "must be a number, not a quoted string" + got);
    return std::nullopt;
  }
  const auto [status, value] = parse_number(f.node.Scalar());
  switch (status) {
    case Parse::not_a_number:
      error(f, "must be a number" + got);
      return std::nullopt;
    case Parse::non_finite:
      error(f, "must be a finite number" + got);
      return std::nullopt;
    case Parse::out_of_range:
      error(f, "is out of the range of double precision" + got);
      return std::nullopt;
    case Parse::ok:
      break;
  }
  if (!range.contains(value)) {
    error(f, range.requirement() + got);
    return std::nullopt;
  }
  return value;
}

std::optional<int> Checker::integer(const Field& f, int min) {
  const auto v = number(f);
  if (!v) return std::nullopt;
  const std::string got = " (got " + describe(f.node) + ")";
  if (*v != std::floor(*v)) {
    error(f, "must be an integer" + got);
    return std::nullopt;
  }
  if (*v < min) {
    error(f, rodlab::format("must be >= {}{}", min, got));
    return std::nullopt;
  }
  if (*v > std::numeric_limits<int>::max()) {
    error(f, rodlab::format("must be <= {}{}", std::numeric_limits<int>::max(), got));
    return std::nullopt;
  }
  return static_cast<int>(*v);
}

std::optional<std::string> Checker::text(const Field& f) {
  if (!f.exists) return std::nullopt;
  if (!f.node.IsScalar()) {
    error(f, "must be a text (got " + describe(f.node) + ")");
    return std::nullopt;
  }
  return f.node.Scalar();
}

bool looks_like_number(const YAML::Node& node) {
  return node.IsScalar() && !quoted_string(node) &&
         parse_number(node.Scalar()).first != Parse::not_a_number;
}

std::optional<std::size_t> Checker::choice(const Field& f,
                                           std::span<const std::string_view> options) {
  if (!f.exists) return std::nullopt;
  if (f.node.IsScalar()) {
    const auto it = std::find(options.begin(), options.end(), f.node.Scalar());
    if (it != options.end()) return static_cast<std::size_t>(it - options.begin());
  }
  std::string message = "must be one of " + join(options) + " (got " + describe(f.node);
  if (f.node.IsScalar())
    if (const auto near = suggestion(f.node.Scalar(), options))
      message += "; did you mean " + std::string(*near) + "?";
  error(f, message + ")");
  return std::nullopt;
}

std::optional<Eigen::VectorXd> Checker::numbers(const Field& f, Eigen::Index size,
                                                const Range& range) {
  if (!f.exists) return std::nullopt;
  if (!f.node.IsSequence() || static_cast<Eigen::Index>(f.node.size()) != size) {
    error(f, rodlab::format("must be a list of {} numbers (got {})", size, describe(f.node)));
    return std::nullopt;
  }
  Eigen::VectorXd v(size);
  bool ok = true;
  for (Eigen::Index i = 0; i < size; ++i) {
    const auto x = number(element(f, static_cast<std::size_t>(i)), range);
    if (x)
      v[i] = *x;
    else
      ok = false;
  }
  if (!ok) return std::nullopt;
  return v;
}

std::optional<Eigen::Matrix3d> Checker::matrix3(const Field& f) {
  if (!f.exists) return std::nullopt;
  if (!f.node.IsSequence() || f.node.size() != 3) {
    error(f, "must be a 3x3 matrix, a list of 3 rows of 3 numbers (got " + describe(f.node) + ")");
    return std::nullopt;
  }
  Eigen::Matrix3d m;
  bool ok = true;
  for (int r = 0; r < 3; ++r) {
    const auto row = vector<3>(element(f, static_cast<std::size_t>(r)));
    if (row)
      m.row(r) = row->transpose();
    else
      ok = false;
  }
  if (!ok) return std::nullopt;
  return m;
}

std::optional<Checker::ScheduleEntries> Checker::schedule_entries(const Field& f) {
  const KeyCheck kc = keys(f, {"steps", "ramp"});
  const auto which = exactly_one(f, {"steps", "ramp"}, kc.unknown == 0);
  if (!which) return std::nullopt;
  ScheduleEntries se;
  se.steps = *which == "steps";
  const auto items = list(child(f, *which), 1);
  if (!items) return std::nullopt;
  std::optional<std::pair<double, std::string>> previous;  // (time, as written)
  for (const Field& entry : *items) {
    if (!entry.node.IsSequence() || entry.node.size() != 2) {
      error(entry, "must be a [time, value] pair (got " + describe(entry.node) + ")");
      se.ok = false;
      continue;
    }
    const Field time = element(entry, 0);
    const auto t = number(time, Range::non_negative());
    if (!t) {
      se.ok = false;
      continue;
    }
    if (previous && *t < previous->first) {
      error(time.mark, entry.path,
            "times must not decrease (got " + time.node.Scalar() + " after " + previous->second +
                ")");
      se.ok = false;
    } else if (previous && se.steps && *t == previous->first) {
      error(time.mark, entry.path,
            "steps need strictly increasing times; a ramp may repeat a time to jump (got " +
                time.node.Scalar() + " after " + previous->second + ")");
      se.ok = false;
    }
    previous = {*t, time.node.Scalar()};
    se.entries.emplace_back(*t, element(entry, 1));
  }
  return se;
}

}  // namespace rodlab::io::detail
