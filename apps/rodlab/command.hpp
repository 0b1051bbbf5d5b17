#pragma once
// A subcommand of `rodlab`: its name, help texts, options and entry point. main.cpp holds
// the table of subcommands; help.cpp renders every help text from these fields.
#include <span>
#include <string>
#include <string_view>

#include "options.hpp"

namespace rodlab::cli {

struct Command;

/// What a subcommand runs with.
struct Invocation {
  const Command& command;
  Arguments args;
  std::string command_line;  ///< the whole command line, shell-quoted (for provenance)
};

struct Command {
  std::string_view name;
  std::string_view synopsis;     ///< after "rodlab NAME", e.g. "SCENE [options]"
  std::string_view summary;      ///< one line for `rodlab --help`
  std::string_view description;  ///< paragraphs for `rodlab NAME --help` (exit status included)
  std::span<const std::string_view> positionals;  ///< required, in order, e.g. {"SCENE"}
  std::span<const OptionSpec> options;
  int (*run)(const Invocation&);
};

// One per file: cmd_<name>.cpp.
const Command& check_command();
const Command& control_command();
const Command& static_command();
const Command& dynamic_command();
const Command& plot_command();
const Command& schemes_command();
const Command& study_command();
const Command& train_command();
const Command& validate_command();
const Command& workspace_command();

}  // namespace rodlab::cli
