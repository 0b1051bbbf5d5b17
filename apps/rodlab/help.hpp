#pragma once
// Help texts, rendered from the Command table (so they never drift from the parser).
#include <span>
#include <string>

#include "command.hpp"

namespace rodlab::cli {

/// `rodlab --help`: synopsis, every subcommand with its summary, exit statuses.
std::string usage_overview(std::span<const Command* const> commands);
/// `rodlab NAME --help`: synopsis, description, options.
std::string command_help(const Command& command);

}  // namespace rodlab::cli
