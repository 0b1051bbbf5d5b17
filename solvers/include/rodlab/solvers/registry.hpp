#pragma once
// The scheme registry: each scheme of the catalogue (schemes.hpp) with the function that runs it,
// a statics solver or a dynamics stepper factory. solve_static() and solve_dynamic() dispatch
// through it; registry.cpp holds the one table, checked at compile time to cover the catalogue
// in order, with the right kind of entry for each scheme's problem.
#include <memory>
#include <variant>

#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"
#include "rodlab/solvers/schemes.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::solvers {

/// Solves one static equilibrium with the scheme (statics schemes).
using StaticSolver = result::StaticResult (*)(const statics::StaticProblem& problem,
                                              const statics::StaticSolveOptions& options);
/// Makes the scheme's stepper at rest in `initial` (dynamics schemes).
using StepperFactory = std::unique_ptr<dynamics::Stepper> (*)(
    const dynamics::DynamicProblem& problem, const dynamics::DynamicSolveOptions& options,
    const dynamics::RestState& initial);

/// A scheme and what runs it: a StaticSolver for a statics scheme, a StepperFactory for a
/// dynamics one.
struct SchemeEntry {
  SchemeId id;
  std::variant<StaticSolver, StepperFactory> run;
};

/// The entry of a scheme.
const SchemeEntry& registry_entry(SchemeId id);
/// What runs a statics scheme; throws std::invalid_argument for a dynamics scheme.
StaticSolver static_solver(SchemeId id);
/// What makes a dynamics scheme's stepper; throws std::invalid_argument for a statics scheme.
StepperFactory stepper_factory(SchemeId id);

/// The scheme of that name if it solves `problem`; otherwise throws std::invalid_argument
/// naming the valid schemes.
const SchemeInfo& scheme_for(std::string_view name, Problem problem);

}  // namespace rodlab::solvers
