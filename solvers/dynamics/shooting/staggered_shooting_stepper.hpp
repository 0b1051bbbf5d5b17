#pragma once
// The shooting steppers' second march (`solver.grid: staggered`, docs/dynamics.md): the time
// rule of `implicit-midpoint` or `bdf-alpha` applied to the semi-discrete rod of `ida` and
// `implicit-midpoint-collocation` (semi_discrete_rod.hpp: the staggered grid of `variational`),
// solved by single shooting on the base wrench. Private to solvers/dynamics; the public entry is
// make_shooting_stepper (shooting_stepper.hpp).
//
// Nodes j = 0..N-1 carry g_j and eta_j, segments j = 0..N-2 carry xi_j and lambda_j. With the
// unknowns at t_u and x_dot = c x + h (time_rule.hpp) the semi-discrete equations
//   sigma_j  = K (xi_j - xi*) + V (c xi_j + h_j) + tendons = dexp^T_{ds xi_j} lambda_j    (3.10), (3.40)
//   eta_(j+1) = Ad_{G_j^-1} eta_j + ds dexp_{-ds xi_j} (c xi_j + h_j)    compatibility, G_j = exp(ds xi_j)
//   lambda_(j+1) = Ad^T_{G_j} lambda_j - entry + w (M eta_dot - ad_eta^T M eta - W_bar)   (3.41), (3.8)
// are marched from the base (g_0, eta_0 = 0, lambda_0 unknown) to the tip, where
// lambda_(N-1) = W_tip is the residual (w = ds inside, ds / 2 at the tip). The first line is
// solved for xi_j by a fixed-point iteration on dexp^T (se3::dexp_transpose_apply), a
// contraction of ratio about ds |lambda| / (2 E I). The rest is explicit, so one integration
// costs a few exp, dexp and Ad applications per node. At equal N the march solves the equations
// `ida` integrates in time: their difference is the time discretisation only. Muscles and length
// control (docs/dynamics.md "Muscles and length control"): the full node inertia, the embedded
// Kt per segment (embedded_reference.hpp) and one extra shooting unknown per muscle (Delta) or
// length-controlled actuator (F), with the rows of `ida` on the segment-sum path lengths.
#include <memory>

#include "rodlab/solvers/dynamics/shooting/shooting_stepper.hpp"

namespace rodlab::solvers::dynamics {

std::unique_ptr<Stepper> make_staggered_shooting_stepper(const DynamicProblem& problem,
                                                         const ShootingOptions& options,
                                                         const RestState& initial,
                                                         std::unique_ptr<TimeRule> rule);

}  // namespace rodlab::solvers::dynamics
