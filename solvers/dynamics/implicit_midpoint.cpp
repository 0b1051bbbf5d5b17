#include "rodlab/solvers/dynamics/implicit_midpoint.hpp"

#include "rodlab/solvers/dynamics/shooting_stepper.hpp"
#include "rodlab/solvers/dynamics/time_rule.hpp"

namespace rodlab::solvers::dynamics {

std::unique_ptr<Stepper> make_implicit_midpoint(const DynamicProblem& problem,
                                                const ImplicitMidpointOptions& options,
                                                const RestState& initial) {
  return make_shooting_stepper(problem, {options.nodes, options.tol, options.max_iterations, options.grid},
                               initial, make_midpoint_rule());
}

}  // namespace rodlab::solvers::dynamics
