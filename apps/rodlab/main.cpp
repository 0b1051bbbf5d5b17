// rodlab: the command line (interface spec section 2). This file only dispatches to the
// subcommands (cmd_*.cpp) and turns their errors into messages and exit statuses.

#include <array>
#include <exception>
#include <stdexcept>
#include <iostream>
#include <string>
#include <vector>

#include "rodlab/heap.hpp"
#include "rodlab/io/atomic_file.hpp"
#include "rodlab/io/scene_loader.hpp"
#include "rodlab/io/text_format.hpp"

#include "command.hpp"
#include "errors.hpp"
#include "exit_status.hpp"
#include "help.hpp"

namespace rodlab::cli {
namespace {

const std::array<const Command*, 10>& command_table() {
  static const std::array<const Command*, 10> table{
      &check_command(),  &static_command(), &dynamic_command(),  &control_command(),
      &schemes_command(), &study_command(), &train_command(), &validate_command(),
      &workspace_command(), &plot_command()};
  return table;
}

const Command* find_command(std::string_view name) {
  for (const Command* c : command_table())
    if (c->name == name) return c;
  return nullptr;
}

std::string command_names() {
  std::string out;
  for (const Command* c : command_table()) out += std::string(c->name) + ", ";
  return out + "help";
}

int run_command(const Command& command, std::span<const std::string> args,
                const std::string& command_line) {
  const std::string prefix = "rodlab " + std::string(command.name) + ": ";
  try {
    Arguments parsed = parse_arguments(args, command.options, command.positionals);
    if (parsed.help_requested()) {
      std::cout << command_help(command);
      return kSolved;
    }
    return command.run(Invocation{command, std::move(parsed), command_line});
  } catch (const UsageError& e) {
    for (const auto& m : e.messages()) std::cerr << prefix << m << '\n';
    std::cerr << "Run 'rodlab " << command.name << " --help' for the options.\n";
  } catch (const io::SceneError& e) {
    for (const auto& d : e.diagnostics()) std::cerr << d.to_string() << '\n';
  } catch (const io::WriteError& e) {  // disk full, directory removed: a failure, not bad input
    std::cerr << prefix << "error: " << e.what() << '\n';
    return kFailed;
  } catch (const std::invalid_argument& e) {  // bad values the scene checks did not catch
    std::cerr << prefix << "error: " << e.what() << '\n';
  } catch (const std::logic_error& e) {  // a broken invariant: a bug, not the user's input
    std::cerr << prefix << "internal error (please report): " << e.what() << '\n';
  } catch (const std::exception& e) {
    std::cerr << prefix << "error: " << e.what() << '\n';
  }
  return kBadInput;
}

int dispatch(const std::vector<std::string>& args, const std::string& command_line) {
  const auto& commands = command_table();
  if (args.empty()) {
    std::cerr << usage_overview(commands);
    return kBadInput;
  }
  const std::string& first = args.front();
  if (first == "--help" || first == "-h" || (first == "help" && args.size() == 1)) {
    std::cout << usage_overview(commands);
    return kSolved;
  }
  if (first == "--version") {
    std::cout << "rodlab " RODLAB_VERSION "\n";
    return kSolved;
  }
  if (first == "help") {
    if (args.size() > 2) {
      std::cerr << "rodlab help: unexpected argument '" << args[2]
                << "' (expected one SUBCOMMAND)\n";
      return kBadInput;
    }
    const Command* c = find_command(args[1]);
    if (c == nullptr) {
      std::cerr << "rodlab help: unknown subcommand '" << args[1]
                << "'; the subcommands are: " << command_names() << '\n';
      return kBadInput;
    }
    std::cout << command_help(*c);
    return kSolved;
  }
  const Command* command = find_command(first);
  if (command == nullptr) {
    std::cerr << "rodlab: unknown " << (first.rfind('-', 0) == 0 ? "option" : "subcommand") << " '"
              << first << "'; the subcommands are: " << command_names()
              << "\nRun 'rodlab --help' for the usage.\n";
    return kBadInput;
  }
  return run_command(*command, std::span(args).subspan(1), command_line);
}

}  // namespace
}  // namespace rodlab::cli

int main(int argc, char** argv) {
  // Large blocks from the heap, kept after free and on huge pages (rodlab/heap.hpp): a one-shot
  // kinsol solve at N = 100 took 11.2 -> 7.5 ms, then 3.73 -> 2.55 ms (docs/statics.md "Cold and
  // warm solves").
  rodlab::configure_process_heap();
  const std::vector<std::string> args(argv + 1, argv + argc);
  std::string command_line = "rodlab";
  for (const auto& a : args) (command_line += ' ') += rodlab::io::shell_quote(a);
  return rodlab::cli::dispatch(args, command_line);
}
