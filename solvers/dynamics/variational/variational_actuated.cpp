// The variational step with muscles or length control (variational_stepper.hpp says why it
// is instantiated in a translation unit of its own).
#include "variational_stepper.hpp"

namespace rodlab::solvers::dynamics {

std::unique_ptr<Stepper> make_actuated_variational(const DynamicProblem& problem,
                                                   const VariationalOptions& options,
                                                   const RestState& initial) {
  return std::make_unique<Variational<true>>(problem, options, initial);
}

}  // namespace rodlab::solvers::dynamics
