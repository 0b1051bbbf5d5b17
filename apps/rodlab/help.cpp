#include "help.hpp"

#include "rodlab/io/text_table.hpp"

namespace rodlab::cli {

std::string usage_overview(std::span<const Command* const> commands) {
  std::string out = "rodlab " RODLAB_VERSION
                    " - Cosserat and Kirchhoff rods: statics, dynamics, studies\n\n"
                    "Usage: rodlab SUBCOMMAND [arguments] [options]\n\n"
                    "Subcommands:\n";
  io::TextTable table;
  for (const Command* c : commands)
    table.add_row(
        {"  " + std::string(c->name) + " " + std::string(c->synopsis), std::string(c->summary)});
  table.add_row({"  help [SUBCOMMAND]", "this text, or the detailed help of a subcommand"});
  out += table.render();
  out +=
      "\n"
      "Options:\n"
      "  -h, --help     help (after a subcommand: that subcommand's help)\n"
      "  --version      print the version\n"
      "\n"
      "Exit status: 0 solved; 1 not converged or unstable (a result file is still written)\n"
      "or a validation check failed; 2 bad input or usage (nothing is written).\n"
      "\n"
      "Start with `rodlab check SCENE.yaml`. Documentation: docs/getting-started.md and\n"
      "docs/cli.md in the source tree (" RODLAB_SOURCE_DIR ").\n";
  return out;
}

std::string command_help(const Command& command) {
  std::string out = "Usage: rodlab " + std::string(command.name) + " " +
                    std::string(command.synopsis) + "\n\n" + std::string(command.description);
  if (!out.empty() && out.back() != '\n') out += '\n';
  io::TextTable table;
  for (const auto& o : command.options) {
    std::string left = "  " + std::string(o.name);
    if (!o.metavar.empty()) (left += " ") += o.metavar;
    table.add_row({left, std::string(o.help) + (o.repeatable ? " (repeatable)" : "")});
  }
  table.add_row({"  -h, --help", "this help"});
  out += "\nOptions:\n" + table.render();
  return out;
}

}  // namespace rodlab::cli
