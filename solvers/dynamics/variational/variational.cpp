#include "rodlab/solvers/dynamics/variational/variational.hpp"

#include "variational_stepper.hpp"

namespace rodlab::solvers::dynamics {

// variational_actuated.cpp
std::unique_ptr<Stepper> make_actuated_variational(const DynamicProblem& problem,
                                                   const VariationalOptions& options,
                                                   const RestState& initial);

std::unique_ptr<Stepper> make_variational(const DynamicProblem& problem,
                                          const VariationalOptions& options,
                                          const RestState& initial) {
  if (problem.unknown_count() > 0) return make_actuated_variational(problem, options, initial);
  return std::make_unique<Variational<false>>(problem, options, initial);
}

}  // namespace rodlab::solvers::dynamics
