// rodlab schemes: the scheme catalogue as a table.
#include <iostream>
#include <string>

#include "rodlab/io/text_table.hpp"
#include "rodlab/solvers/schemes.hpp"

#include "command.hpp"
#include "exit_status.hpp"

namespace rodlab::cli {
namespace {

int run(const Invocation&) {
  io::TextTable table;
  table.add_row({"name", "problem", "order", "type", "reference", "method"});
  table.add_rule();
  for (const auto& s : solvers::all_schemes()) {
    table.add_row({std::string(s.name), std::string(solvers::to_string(s.problem)),
                   std::string(s.order), s.implicit ? "implicit" : "explicit",
                   s.reference ? "reference" : "", std::string(s.method)});
  }
  std::cout << table.render();
  return kSolved;
}

}  // namespace

const Command& schemes_command() {
  static const Command command{
      "schemes",
      "",
      "list the schemes: problem, order, explicit/implicit, method",
      "Lists every scheme: its name (for --scheme), the problem it solves (statics: the\n"
      "boundary-value problem in s; dynamics: the initial-boundary-value problem in s and t),\n"
      "its order, whether it is implicit in its marching direction, whether it is the SUNDIALS\n"
      "reference of its class, and the method in one line.\n"
      "\n"
      "Exit status: 0.\n",
      {},
      {},
      &run};
  return command;
}

}  // namespace rodlab::cli
