#pragma once
// The command-line parser shared by every subcommand. A subcommand declares its options
// (OptionSpec) and positional arguments; parse_arguments() checks the structure (unknown
// options, missing values, repeated single-valued options, number of positionals) and
// OptionReader converts and checks the values. Both collect every problem and report them
// together as one UsageError, each message naming the option and the bad value.
//
// Accepted forms: `--name value`, `--name=value`, `--flag`, `--` (the rest is positional).
// `--help` / `-h` is understood by every subcommand.
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rodlab::cli {

struct OptionSpec {
  std::string_view name;     ///< "--nodes"
  std::string_view metavar;  ///< "N"; empty for a flag that takes no value
  std::string_view help;     ///< one line for `--help`
  bool repeatable = false;   ///< may be given more than once (e.g. --set)
};

/// What the command line said, structurally valid.
class Arguments {
 public:
  bool help_requested() const { return help_; }
  const std::vector<std::string>& positionals() const { return positionals_; }
  bool has(std::string_view option) const { return values_.find(option) != values_.end(); }
  /// The value of a single-valued option, if given.
  std::optional<std::string> value(std::string_view option) const;
  /// Every value of a repeatable option, in command-line order.
  std::vector<std::string> values(std::string_view option) const;

 private:
  friend Arguments parse_arguments(std::span<const std::string>, std::span<const OptionSpec>,
                                   std::span<const std::string_view>);
  bool help_ = false;
  std::vector<std::string> positionals_;
  std::map<std::string, std::vector<std::string>, std::less<>> values_;
};

/// Parses `args` (everything after the subcommand). Throws UsageError listing every
/// structural problem. When --help/-h is present nothing else is checked.
Arguments parse_arguments(std::span<const std::string> args, std::span<const OptionSpec> options,
                          std::span<const std::string_view> positional_names);

/// Converts and checks option values, collecting the problems; finish() throws them.
class OptionReader {
 public:
  explicit OptionReader(const Arguments& args) : args_(args) {}

  const Arguments& arguments() const { return args_; }
  bool flag(std::string_view option) const { return args_.has(option); }
  std::optional<std::string> text(std::string_view option) const { return args_.value(option); }

  /// An integer >= min.
  std::optional<int> integer(std::string_view option, int min);
  /// A finite number > 0.
  std::optional<double> positive(std::string_view option);
  /// Comma-separated lists: "5,10,20".
  std::optional<std::vector<int>> integers(std::string_view option, int min);
  std::optional<std::vector<double>> positives(std::string_view option);
  std::optional<std::vector<std::string>> names(std::string_view option);
  /// One of `choices`.
  std::optional<std::string> choice(std::string_view option,
                                    std::span<const std::string_view> choices);

  /// Records a problem; the message should start with the option it is about.
  void problem(std::string message) { problems_.push_back(std::move(message)); }
  bool ok() const { return problems_.empty(); }
  /// Throws UsageError with every problem recorded so far, if any.
  void finish() const;

 private:
  const Arguments& args_;
  std::vector<std::string> problems_;
};

/// Strict conversions (the whole text, no leading '+', no spaces); nullopt when malformed.
std::optional<int> to_int(std::string_view text);
std::optional<double> to_double(std::string_view text);      ///< finite numbers only
std::vector<std::string> split_list(std::string_view text);  ///< on ','

}  // namespace rodlab::cli
