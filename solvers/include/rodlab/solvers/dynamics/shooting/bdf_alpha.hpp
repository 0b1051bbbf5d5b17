#pragma once
// `bdf-alpha`: BDF-alpha in time (Till, Aloi & Rucker 2019), explicit Euler RKMK in space,
// single shooting: the shooting stepper of `implicit-midpoint` (shooting_stepper.hpp) with the
// unknowns at the new time t + dt and
//   x_dot(t + dt) = c0 x(t + dt) + c1 x(t) + c2 x(t - dt) + d1 x_dot(t)        (time_rule.hpp)
// for the strains and velocities. alpha in [-0.5, 0]: 0 is BDF2 (strong damping of the high
// frequencies), -0.5 the trapezoidal rule (none). docs/dynamics.md.
#include <memory>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/shooting/shooting_stepper.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {

/// Till, Aloi & Rucker's choice in their examples (0 is BDF2, -0.5 the trapezoidal rule).
inline constexpr double kDefaultBdfAlpha = -0.2;

/// The shooting options (nodes, tolerance, iterations, grid; shooting_stepper.hpp) and alpha.
struct BdfAlphaOptions : ShootingOptions {
  double alpha = kDefaultBdfAlpha;  ///< in [-0.5, 0]
};

/// Starts at rest from `initial` (options.nodes nodes). Throws std::invalid_argument for alpha
/// outside [-0.5, 0].
std::unique_ptr<Stepper> make_bdf_alpha(const DynamicProblem& problem,
                                        const BdfAlphaOptions& options, const RestState& initial);

}  // namespace rodlab::solvers::dynamics
