// rodlab schemes: the scheme catalogue as a table.
#include <iostream>
#include <string>

#include "rodlab/solvers/schemes.hpp"

#include "command.hpp"
#include "exit_status.hpp"
#include "text_table.hpp"

namespace rodlab::cli {
namespace {

int run(const Invocation&) {
  TextTable table;
  table.add_row({"name", "problem", "order", "type", "reference", "status", "method"});
  table.add_rule();
  for (const auto& s : solvers::all_schemes()) {
    const std::string status =
        s.arrives.empty() ? std::string("available") : "arrives with " + std::string(s.arrives);
    table.add_row({std::string(s.name), std::string(solvers::to_string(s.problem)),
                   std::string(s.order), s.implicit ? "implicit" : "explicit",
                   s.reference ? "reference" : "", status, std::string(s.method)});
  }
  std::cout << table.render();
  return kSolved;
}

}  // namespace

const Command& schemes_command() {
  static const Command command{
      "schemes",
      "",
      "list the schemes: problem, order, explicit/implicit, status",
      "Lists every scheme: its name (for --scheme), the problem it solves (statics: the\n"
      "boundary-value problem in s; dynamics: the initial-boundary-value problem in s and t),\n"
      "its order, whether it is implicit in its marching direction, whether it is the SUNDIALS\n"
      "reference of its class, whether it is available in this build (or which issue brings\n"
      "it), and the method in one line.\n"
      "\n"
      "Exit status: 0.\n",
      {},
      {},
      &run};
  return command;
}

}  // namespace rodlab::cli
