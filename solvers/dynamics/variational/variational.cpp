#include "rodlab/solvers/dynamics/variational/variational.hpp"

#include "variational_stepper.hpp"

namespace rodlab::solvers::dynamics {

// variational_actuated.cpp
std::unique_ptr<Stepper> make_actuated_variational(const DynamicProblem& problem,
                                                   const VariationalOptions& options,
                                                   const RestState& initial);

std::string_view variational_step_name(VariationalStep step) {
  return step == VariationalStep::verlet ? "verlet" : "symplectic-euler";
}

std::optional<VariationalStep> variational_step_from_name(std::string_view name) {
  if (name == "verlet") return VariationalStep::verlet;
  if (name == "symplectic-euler") return VariationalStep::symplectic_euler;
  return std::nullopt;
}

std::unique_ptr<Stepper> make_variational(const DynamicProblem& problem,
                                          const VariationalOptions& options,
                                          const RestState& initial) {
  if (problem.unknown_count() > 0) return make_actuated_variational(problem, options, initial);
  return std::make_unique<Variational<false>>(problem, options, initial);
}

}  // namespace rodlab::solvers::dynamics
