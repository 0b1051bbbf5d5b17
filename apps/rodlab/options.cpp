#include "options.hpp"

#include <charconv>
#include <cmath>

#include "errors.hpp"

namespace rodlab::cli {
namespace {

const OptionSpec* find_option(std::span<const OptionSpec> options, std::string_view name) {
  for (const auto& o : options)
    if (o.name == name) return &o;
  return nullptr;
}

std::string join(std::span<const std::string_view> items, std::string_view separator) {
  std::string out;
  for (const auto& item : items) {
    if (!out.empty()) out += separator;
    out += item;
  }
  return out;
}

std::string quoted(std::string_view text) { return std::string("'").append(text).append("'"); }

}  // namespace

std::optional<std::string> Arguments::value(std::string_view option) const {
  const auto it = values_.find(option);
  if (it == values_.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

std::vector<std::string> Arguments::values(std::string_view option) const {
  const auto it = values_.find(option);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

Arguments parse_arguments(std::span<const std::string> args, std::span<const OptionSpec> options,
                          std::span<const std::string_view> positional_names) {
  Arguments out;
  for (const auto& a : args) {
    if (a == "--") break;
    if (a == "--help" || a == "-h") {
      out.help_ = true;
      return out;
    }
  }

  std::vector<std::string> problems;
  bool only_positionals = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    // "-" and negative numbers are arguments, not options.
    const bool looks_like_option = arg.size() >= 2 && arg[0] == '-' && !to_double(arg);
    if (only_positionals || !looks_like_option) {
      out.positionals_.push_back(arg);
      continue;
    }
    if (arg == "--") {
      only_positionals = true;
      continue;
    }
    const auto eq = arg.find('=');
    const std::string name = arg.substr(0, eq);
    const OptionSpec* spec = find_option(options, name);
    if (spec == nullptr) {
      if (options.empty())
        problems.push_back("unknown option " + quoted(name) +
                           " (this subcommand takes no options)");
      else {
        std::vector<std::string_view> names;
        for (const auto& o : options) names.push_back(o.name);
        problems.push_back("unknown option " + quoted(name) +
                           "; the options are: " + join(names, ", "));
      }
      continue;
    }
    std::string value;
    if (spec->metavar.empty()) {
      if (eq != std::string::npos) {
        problems.push_back(name + " takes no value (got " + quoted(arg.substr(eq + 1)) + ")");
        continue;
      }
    } else if (eq != std::string::npos) {
      value = arg.substr(eq + 1);
    } else if (i + 1 < args.size() && args[i + 1].rfind("--", 0) != 0) {
      value = args[++i];
    } else {
      problems.push_back(name + ": missing value " + std::string(spec->metavar));
      continue;
    }
    auto& slot = out.values_[name];
    if (!slot.empty() && !spec->repeatable) {
      problems.push_back(name + ": given more than once (" + quoted(slot.front()) + " and " +
                         quoted(value) + "); give it once");
      continue;
    }
    slot.push_back(value);
  }

  if (out.positionals_.size() < positional_names.size()) {
    for (std::size_t k = out.positionals_.size(); k < positional_names.size(); ++k)
      problems.push_back("missing " + std::string(positional_names[k]));
  } else {
    for (std::size_t k = positional_names.size(); k < out.positionals_.size(); ++k)
      problems.push_back("unexpected argument " + quoted(out.positionals_[k]) +
                         (positional_names.empty()
                              ? std::string(" (this subcommand takes no arguments)")
                              : " (expected only " + join(positional_names, " ") + ")"));
  }
  if (!problems.empty()) throw UsageError(std::move(problems));
  return out;
}

std::optional<int> OptionReader::integer(std::string_view option, int min) {
  const auto text = args_.value(option);
  if (!text) return std::nullopt;
  const auto v = to_int(*text);
  if (!v || *v < min) {
    problem(std::string(option) + ": must be an integer >= " + std::to_string(min) + " (got " +
            *text + ")");
    return std::nullopt;
  }
  return v;
}

std::optional<double> OptionReader::positive(std::string_view option) {
  const auto text = args_.value(option);
  if (!text) return std::nullopt;
  const auto v = to_double(*text);
  if (!v || !(*v > 0.0)) {
    problem(std::string(option) + ": must be a number > 0 (got " + *text + ")");
    return std::nullopt;
  }
  return v;
}

std::optional<std::vector<int>> OptionReader::integers(std::string_view option, int min) {
  const auto text = args_.value(option);
  if (!text) return std::nullopt;
  std::vector<int> out;
  const auto items = split_list(*text);
  for (const auto& item : items) {
    const auto v = to_int(item);
    if (!v || *v < min) {
      problem(std::string(option) + ": every entry must be an integer >= " + std::to_string(min) +
              " (got " + quoted(item) + " in " + *text + ")");
      return std::nullopt;
    }
    out.push_back(*v);
  }
  if (out.empty()) problem(std::string(option) + ": empty list");
  return out.empty() ? std::nullopt : std::optional(out);
}

std::optional<std::vector<double>> OptionReader::positives(std::string_view option) {
  const auto text = args_.value(option);
  if (!text) return std::nullopt;
  std::vector<double> out;
  for (const auto& item : split_list(*text)) {
    const auto v = to_double(item);
    if (!v || !(*v > 0.0)) {
      problem(std::string(option) + ": every entry must be a number > 0 (got " + quoted(item) +
              " in " + *text + ")");
      return std::nullopt;
    }
    out.push_back(*v);
  }
  if (out.empty()) problem(std::string(option) + ": empty list");
  return out.empty() ? std::nullopt : std::optional(out);
}

std::optional<std::vector<std::string>> OptionReader::names(std::string_view option) {
  const auto text = args_.value(option);
  if (!text) return std::nullopt;
  auto out = split_list(*text);
  for (const auto& item : out) {
    if (item.empty()) {
      problem(std::string(option) + ": empty entry in " + quoted(*text));
      return std::nullopt;
    }
  }
  return out;
}

std::optional<std::string> OptionReader::choice(std::string_view option,
                                                std::span<const std::string_view> choices) {
  const auto text = args_.value(option);
  if (!text) return std::nullopt;
  for (const auto& c : choices)
    if (c == *text) return text;
  problem(std::string(option) + ": must be one of " + join(choices, ", ") + " (got " + *text + ")");
  return std::nullopt;
}

void OptionReader::finish() const {
  if (!problems_.empty()) throw UsageError(problems_);
}

std::optional<int> to_int(std::string_view text) {
  int v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return v;
}

std::optional<double> to_double(std::string_view text) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty() || !std::isfinite(v))
    return std::nullopt;
  return v;
}

std::vector<std::string> split_list(std::string_view text) {
  std::vector<std::string> out;
  if (text.empty()) return out;
  std::size_t start = 0;
  while (true) {
    const auto comma = text.find(',', start);
    out.emplace_back(text.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace rodlab::cli
