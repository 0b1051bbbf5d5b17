// rodlab study KIND SCENE [options]: convergence, work-precision and stability studies, and
// the scheme recommendation built on them.
#include <array>
#include <stdexcept>
#include <string>

#include "availability.hpp"
#include "command.hpp"
#include "common_options.hpp"
#include "format.hpp"

namespace rodlab::cli {
namespace {

using solvers::Problem;

constexpr std::array<std::string_view, 2> kPositionals{"KIND", "SCENE"};
constexpr std::array<std::string_view, 4> kKinds{"convergence", "work-precision", "stability",
                                                 "recommend"};
constexpr std::array<std::string_view, 3> kReferences{"kinsol", "ida", "chebyshev"};
constexpr std::array<OptionSpec, 9> kOptions{
    OptionSpec{"--schemes", "A,B,...",
               "schemes to compare, comma-separated (one problem class); default: all"},
    OptionSpec{"--nodes", "N1,N2,...", "node counts, comma-separated integers >= 2"},
    OptionSpec{"--dt", "X1,X2,...", "time steps > 0, comma-separated (dynamics studies)"},
    OptionSpec{"--reference", "NAME", "reference solution: kinsol, ida or chebyshev"},
    kTolOption,
    OptionSpec{"--budget-ms", "X", "time budget per run in milliseconds, > 0"},
    OptionSpec{"--jobs", "N", "runs in parallel, integer >= 1"},
    OptionSpec{"--out", "DIR", "directory for the study's data and report (created if missing)"},
    kSetOption};

/// The problem class of the study from its schemes, its reference, or its kind.
void check_problem_class(OptionReader& reader, const std::string& kind) {
  std::optional<Problem> problem;
  std::string decided_by;
  if (kind == "stability") {
    problem = Problem::dynamics;
    decided_by = "a stability study (time stepping)";
  }
  if (const auto names = reader.names("--schemes")) {
    for (const auto& name : *names) {
      const auto scheme = solvers::find_scheme(name);
      if (!scheme) {
        reader.problem("--schemes: unknown scheme '" + name +
                       "'; the statics schemes are: " + solvers::scheme_names(Problem::statics) +
                       "; the dynamics schemes are: " + solvers::scheme_names(Problem::dynamics));
        continue;
      }
      if (problem && *problem != scheme->problem) {
        reader.problem("--schemes: '" + name + "' is a " +
                       std::string(solvers::to_string(scheme->problem)) + " scheme but " +
                       decided_by + " needs " + std::string(solvers::to_string(*problem)) +
                       " schemes");
        continue;
      }
      if (!problem) {
        problem = scheme->problem;
        decided_by = "'" + name + "'";
      }
    }
  }
  if (const auto reference = reader.choice("--reference", kReferences)) {
    const Problem p = solvers::find_scheme(*reference)->problem;
    if (problem && *problem != p)
      reader.problem("--reference: '" + *reference + "' is a " +
                     std::string(solvers::to_string(p)) + " reference but " + decided_by +
                     " needs a " + std::string(solvers::to_string(*problem)) + " one");
    else if (!problem) {
      problem = p;
      decided_by = "--reference " + *reference;
    }
  }
  if (reader.arguments().has("--dt") && problem == Problem::statics)
    reader.problem("--dt: only dynamics studies step in time, and " + decided_by +
                   " makes this a statics study");
}

int run(const Invocation& inv) {
  OptionReader reader(inv.args);
  const std::string kind = inv.args.positionals().front();
  bool kind_ok = false;
  for (const auto k : kKinds) kind_ok = kind_ok || k == kind;
  if (!kind_ok) {
    std::vector<std::string> kinds(kKinds.begin(), kKinds.end());
    reader.problem("KIND: unknown study '" + kind + "'; the studies are: " + join(kinds));
  }
  SolveOptions options;
  options.scene_path = inv.args.positionals().back();
  options.overrides = read_overrides(reader);
  options.tol = reader.positive(kTolOption.name);
  reader.integers("--nodes", 2);
  reader.positives("--dt");
  reader.positive("--budget-ms");
  reader.integer("--jobs", 1);
  read_out_dir(reader);
  if (kind_ok) check_problem_class(reader, kind);
  reader.finish();
  static_cast<void>(load_checked_scene(options));
  require_available(kStudiesArrive);
  // The studies themselves arrive with kStudiesArrive.
  throw std::logic_error("the studies are marked available but not linked");
}

}  // namespace

const Command& study_command() {
  static const Command command{
      "study",
      "KIND SCENE [options]",
      "convergence, work-precision, stability studies; scheme recommendation",
      "KIND is one of:\n"
      "  convergence      error against the reference as the nodes (or dt) are refined; observed "
      "order\n"
      "  work-precision   error against wall time for each scheme\n"
      "  stability        largest stable time step of each dynamics scheme\n"
      "  recommend        the fastest scheme that meets --tol within --budget-ms\n"
      "The options and the scene are checked before anything runs.\n"
      "\n"
      "Exit status: 0 the study ran; 1 some runs failed (the report says which); 2 bad input\n"
      "or usage (nothing is written).\n",
      kPositionals,
      kOptions,
      &run};
  return command;
}

}  // namespace rodlab::cli
