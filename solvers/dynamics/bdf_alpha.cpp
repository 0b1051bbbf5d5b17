#include "rodlab/solvers/dynamics/bdf_alpha.hpp"

#include "rodlab/solvers/dynamics/shooting_stepper.hpp"
#include "rodlab/solvers/dynamics/time_rule.hpp"

namespace rodlab::solvers::dynamics {

std::unique_ptr<Stepper> make_bdf_alpha(const DynamicProblem& problem,
                                        const BdfAlphaOptions& options, const RestState& initial) {
  return make_shooting_stepper(problem, {options.nodes, options.tol, options.max_iterations, options.grid},
                               initial, make_bdf_alpha_rule(options.alpha, options.nodes));
}

}  // namespace rodlab::solvers::dynamics
