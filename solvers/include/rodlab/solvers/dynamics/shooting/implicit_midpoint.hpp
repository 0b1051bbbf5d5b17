#pragma once
// `implicit-midpoint`: implicit midpoint in time, explicit Euler RKMK in space, single shooting
// (thesis Algorithm 2, (3.46)-(3.54)); docs/dynamics.md.
//
// The shooting stepper of shooting_stepper.hpp with the midpoint rule (time_rule.hpp): each
// step solves the BVP at the half step h = i + 1/2, x_h = (x_i + x_(i+1)) / 2, with
//   x_dot_h = 2 (x_h - x_i) / dt   for x = xi, eta                               (3.50)
//   Lambda_h' = 2 M (eta_h - eta_i) / dt - ad_{eta_h}^T M eta_h + ad_{xi_h}^T Lambda_h - W_bar_h  (3.51)
//   eta_h'    = 2 (xi_h - xi_i) / dt - ad_{xi_h} eta_h                                          (3.52)
//   Lambda_h  = K (xi_h - xi*) + 2 V (xi_h - xi_i) / dt + sum_k F_k c_k(xi_h)    (solved for xi_h)
// then xi_(i+1) = 2 xi_h - xi_i, eta_(i+1) = 2 eta_h - eta_i (3.53)-(3.54). The state is (xi, eta)
// at the nodes; poses follow from xi by the same spatial integration (the thesis also steps g in
// time, g_(i+1) = g_i exp(dt eta_h), which can drift away from the strains).
#include <memory>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/shooting/shooting_stepper.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {

/// Nodes, tolerance, iterations and the march's grid (shooting_stepper.hpp).
using ImplicitMidpointOptions = ShootingOptions;

/// Starts at rest from `initial` (options.nodes nodes).
std::unique_ptr<Stepper> make_implicit_midpoint(const DynamicProblem& problem,
                                                const ImplicitMidpointOptions& options,
                                                const RestState& initial);

}  // namespace rodlab::solvers::dynamics
