#pragma once
// The corrected grid (`solver.grid: corrected`; docs/dynamics.md "The corrected grid"): the
// staggered grid of `variational` and `ida` with its two O(ds^2) errors of the bending modes
// removed, each by a term that vanishes as ds -> 0:
//
// 1. the residual bending flexibility (RodModel::with_residual_bending_flexibility): the grid's
//    bending stiffness is too high by (k ds)^2 / 12, which a shear compliance of ds^2 / (12 E I)
//    cancels;
// 2. the free tip's half cell [L - ds/2, L] as a rigid body whose centre of mass sits ds / 6
//    behind the tip node (TipHalfCell): the trapezoidal rule puts the half cell's mass at the
//    tip, and its Euler-Maclaurin end term -(ds^2 / 12) d/ds (rho A |v|^2 / 2 - rho A g . p)
//    at s = L is what that offset adds to the kinetic and gravitational energies.
//
// On the Table 2.1 cantilever (0.5 s under gravity) `variational` reaches 5.4e-5 m at N = 10
// where the plain grid reaches 8.2e-4 m. Every dynamics scheme takes it: `variational`, the
// semi-discrete rod of `ida` and `implicit-midpoint-collocation` (SemiDiscreteRod's
// corrected_grid) and the staggered shooting march of `implicit-midpoint` and `bdf-alpha`.
#include <optional>
#include <string>

#include "rodlab/lie/se3.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"

namespace rodlab::solvers::dynamics {

/// Why the scene cannot take the corrected grid (every dynamics scheme can), naming
/// solver.grid: Kirchhoff rods (the flexibility is a shear compliance) and scenes with actuators
/// (their node inertia and loads are not corrected); nullopt where it can.
std::optional<std::string> corrected_grid_refusal(const DynamicProblem& problem);
/// Throws std::invalid_argument with corrected_grid_refusal's reason, where there is one.
void require_corrected_grid(const DynamicProblem& problem);

/// The problem on the corrected grid of `nodes` nodes: its model with the residual bending
/// flexibility of ds = L / (nodes - 1). The time step `dt: auto` follows from it (the softer
/// shear lowers the rotation-shear frequency).
DynamicProblem corrected_grid_problem(const DynamicProblem& problem, int nodes);

/// The free tip's half cell as a rigid body of mass rho A ds / 2 per the node's cell, centre of
/// mass at `offset` = -(ds / 6) t in the tip's body frame (t: the unit tangent of the last
/// segment's rest strain). Per unit length of the cell (as the node's diagonal M):
///   M = [[rho J - rho A d^ d^, rho A d^], [-rho A d^, rho A I]]   (twist order [omega; v]),
/// a rigid body's inertia (positive definite for every ds): 1/2 eta^T M eta = rho J omega^2 / 2
/// + rho A |v + omega x d|^2 / 2. The Schur complement of its linear block is rho J, so the
/// section's rotation is not stiffened against the shear (no smaller stable step).
struct TipHalfCell {
  lie::Vector3 offset;
  lie::Matrix6 M, M_inv;
  lie::SO3 rest_rotation;  ///< the tip's in the rest pose (set by `of`; gravity_energy's R_ref)

  static TipHalfCell make(const rod::RodModel& model, int nodes);
  /// A scheme's tip cell on the corrected grid (require_corrected_grid first): the free tip's,
  /// with its rest rotation, or none for a clamped tip (it does not move).
  static std::optional<TipHalfCell> of(const DynamicProblem& problem, int nodes);
  /// A distributed wrench per unit length at the node, [m; f], moved to act at the centre of
  /// mass: [m + d x f; f].
  lie::Vector6 at_centre_of_mass(const lie::Vector6& wrench) const {
    lie::Vector6 w = wrench;
    w.head<3>() += offset.cross(wrench.tail<3>());
    return w;
  }
  /// The gravitational energy the offset adds to the trapezoidal sum (energy.hpp): the half
  /// cell (weight `weight_per_length` x ds / 2) at p + R d instead of p, against the rest pose's
  /// rotation R_ref.
  double gravity_energy(const lie::Vector3& weight_per_length, const lie::SO3& R,
                        const lie::SO3& R_ref, double ds) const {
    return -0.5 * ds * weight_per_length.dot(R * offset - R_ref * offset);
  }
  double gravity_energy(const lie::Vector3& weight_per_length, const lie::SO3& R, double ds) const {
    return gravity_energy(weight_per_length, R, rest_rotation, ds);
  }
};

}  // namespace rodlab::solvers::dynamics
