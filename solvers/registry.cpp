// The scheme registry (registry.hpp): every scheme of the catalogue with the function that runs
// it. Adding a scheme: its catalogue line (rodlab/scene/schemes.hpp), one adapter and one line
// here (docs/development.md "How to add a scheme").
#include "rodlab/solvers/registry.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

#include "rodlab/check.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/ida_reference.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/implicit_midpoint_collocation.hpp"
#include "rodlab/solvers/dynamics/shooting/bdf_alpha.hpp"
#include "rodlab/solvers/dynamics/shooting/implicit_midpoint.hpp"
#include "rodlab/solvers/dynamics/variational/variational.hpp"
#include "rodlab/solvers/statics/chebyshev.hpp"
#include "rodlab/solvers/statics/kinsol_collocation.hpp"
#include "rodlab/solvers/statics/shooting.hpp"

namespace rodlab::solvers {
namespace {

using dynamics::DynamicProblem;
using dynamics::DynamicSolveOptions;
using dynamics::RestState;
using dynamics::Stepper;
using statics::StaticProblem;
using statics::StaticSolveOptions;

// Statics: the run options mapped onto each scheme's own options.

template <statics::RkmkMethod method>
result::StaticResult rkmk(const StaticProblem& problem, const StaticSolveOptions& o) {
  return statics::solve_shooting(problem, method, {o.nodes, o.tol, o.max_iterations, {}});
}

result::StaticResult chebyshev(const StaticProblem& problem, const StaticSolveOptions& o) {
  statics::ChebyshevOptions options;
  options.nodes = o.nodes;
  options.tol = o.tol;
  options.max_iterations = o.max_iterations;
  return statics::solve_chebyshev(problem, options);
}

result::StaticResult kinsol(const StaticProblem& problem, const StaticSolveOptions& o) {
  statics::KinsolCollocationOptions options;
  options.nodes = o.nodes;
  options.tol = o.tol;
  options.max_iterations = o.max_iterations;
  return statics::solve_kinsol_collocation(problem, options);
}

// Dynamics: the run options mapped onto each scheme's own options.

std::unique_ptr<Stepper> variational(const DynamicProblem& problem, const DynamicSolveOptions& o,
                                     const RestState& initial) {
  dynamics::VariationalOptions options;  // its Newton solve of (3.42) keeps its own defaults,
  options.nodes = o.nodes;               // tightened further by a smaller run tolerance
  options.tol = std::min(o.tol, options.tol);
  options.step = o.variational_step;
  options.corrected_grid = o.grid == dynamics::ShootingGrid::corrected;
  return dynamics::make_variational(problem, options, initial);
}

dynamics::ShootingOptions shooting_options(const DynamicSolveOptions& o) {
  return {o.nodes, o.tol, o.max_iterations, o.grid, o.shooting_intervals};
}

std::unique_ptr<Stepper> implicit_midpoint(const DynamicProblem& problem,
                                           const DynamicSolveOptions& o, const RestState& initial) {
  return dynamics::make_implicit_midpoint(problem, shooting_options(o), initial);
}

std::unique_ptr<Stepper> bdf_alpha(const DynamicProblem& problem, const DynamicSolveOptions& o,
                                   const RestState& initial) {
  return dynamics::make_bdf_alpha(problem, {shooting_options(o), o.alpha}, initial);
}

std::unique_ptr<Stepper> collocation(const DynamicProblem& problem, const DynamicSolveOptions& o,
                                     const RestState& initial) {
  dynamics::ImplicitMidpointCollocationOptions options;
  options.nodes = o.nodes;
  options.tol = o.tol;
  options.max_iterations = o.max_iterations;
  options.corrected_grid = o.grid == dynamics::ShootingGrid::corrected;
  return dynamics::make_implicit_midpoint_collocation(problem, options, initial);
}

std::unique_ptr<Stepper> ida(const DynamicProblem& problem, const DynamicSolveOptions& o,
                             const RestState& initial) {
  dynamics::IdaOptions options;
  options.nodes = o.nodes;
  options.rtol = o.rtol;
  options.atol = o.atol;
  options.corrected_grid = o.grid == dynamics::ShootingGrid::corrected;
  return dynamics::make_ida(problem, options, initial);
}

using statics::RkmkMethod;
constexpr std::array<SchemeEntry, scene::kSchemeCount> kRegistry{{
    {SchemeId::rkmk_euler_explicit, StaticSolver{&rkmk<RkmkMethod::euler_explicit>}},
    {SchemeId::rkmk_euler_implicit, StaticSolver{&rkmk<RkmkMethod::euler_implicit>}},
    {SchemeId::rkmk_midpoint_explicit, StaticSolver{&rkmk<RkmkMethod::midpoint_explicit>}},
    {SchemeId::rkmk_midpoint_implicit, StaticSolver{&rkmk<RkmkMethod::midpoint_implicit>}},
    {SchemeId::rkmk_rk4, StaticSolver{&rkmk<RkmkMethod::rk4>}},
    {SchemeId::chebyshev, StaticSolver{&chebyshev}},
    {SchemeId::kinsol, StaticSolver{&kinsol}},
    {SchemeId::variational, StepperFactory{&variational}},
    {SchemeId::implicit_midpoint, StepperFactory{&implicit_midpoint}},
    {SchemeId::implicit_midpoint_collocation, StepperFactory{&collocation}},
    {SchemeId::bdf_alpha, StepperFactory{&bdf_alpha}},
    {SchemeId::ida, StepperFactory{&ida}},
}};

/// Every catalogue entry, in order, with the kind of function its problem needs.
constexpr bool covers_the_catalogue() {
  for (int i = 0; i < scene::kSchemeCount; ++i) {
    const SchemeEntry& e = kRegistry[i];
    const bool statics = scene::kSchemeCatalogue[i].problem == Problem::statics;
    if (static_cast<int>(e.id) != i || e.run.index() != (statics ? 0u : 1u)) return false;
  }
  return true;
}
static_assert(covers_the_catalogue(),
              "kRegistry must give every catalogue scheme, in order, the solver of its problem");

}  // namespace

const SchemeEntry& registry_entry(SchemeId id) { return kRegistry[static_cast<int>(id)]; }

StaticSolver static_solver(SchemeId id) {
  const auto* f = std::get_if<StaticSolver>(&registry_entry(id).run);
  RODLAB_THROW_UNLESS(f != nullptr, "'{}' is not a statics scheme", scheme_info(id).name);
  return *f;
}

StepperFactory stepper_factory(SchemeId id) {
  const auto* f = std::get_if<StepperFactory>(&registry_entry(id).run);
  RODLAB_THROW_UNLESS(f != nullptr, "'{}' is not a dynamics scheme", scheme_info(id).name);
  return *f;
}

const SchemeInfo& scheme_for(std::string_view name, Problem problem) {
  const auto info = find_scheme(name);
  if (!info || info->problem != problem)
    throw std::invalid_argument(rodlab::format("unknown {} scheme '{}' (valid: {})",
                                                to_string(problem), name, scheme_names(problem)));
  return scheme_info(info->id);
}

}  // namespace rodlab::solvers
