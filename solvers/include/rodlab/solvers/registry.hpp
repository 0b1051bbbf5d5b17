#pragma once
// The scheme registry: each scheme of the catalogue (schemes.hpp) with the function that runs it,
// a statics solver or a dynamics stepper factory. solve_static() and solve_dynamic() dispatch
// through it; registry.cpp holds the one table, checked at compile time to cover the catalogue
// in order, with the right kind of entry for each scheme's problem.
#include <memory>

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

struct SchemeEntry {
  SchemeId id;
  StaticSolver solve_static = nullptr;     ///< set for statics schemes only
  StepperFactory make_stepper = nullptr;   ///< set for dynamics schemes only
};

/// The entry of a scheme.
const SchemeEntry& registry_entry(SchemeId id);

/// The scheme of that name if it solves `problem`; otherwise throws std::invalid_argument
/// naming the valid schemes.
const SchemeInfo& scheme_for(std::string_view name, Problem problem);

}  // namespace rodlab::solvers
