#pragma once
// The energies of the dynamic result (interface spec section 4), computed by the same formulas
// for every scheme on its own grid:
//   kinetic (3.5)  T = int 1/2 <eta, M eta> ds            trapezoid over the nodes
//   strain (2.28)  U = int 1/2 <xi - xi*, K (xi - xi*)>   midpoint over segments (strains on
//                                                         segments) or trapezoid (on nodes)
//   gravity        P = -int rho_eff A <g, p - p*> ds      trapezoid, zero in the reference pose
// `dissipated` (viscous and drag power) and `work_in` (tip wrench, distributed wrench, actuators)
// are running integrals kept by each scheme with its own quadrature in time.
#include <span>

#include "rodlab/lie/se3.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"

namespace rodlab::solvers::dynamics {

struct Energy {
  double kinetic = 0.0, strain = 0.0, gravity = 0.0, dissipated = 0.0, work_in = 0.0;
  /// kinetic + strain + gravity + dissipated - work_in: constant for an exact solution.
  double total() const { return kinetic + strain + gravity + dissipated - work_in; }
  /// kinetic + strain + gravity.
  double mechanical() const { return kinetic + strain + gravity; }
};

/// Trapezoid weights: 1/2 at both ends, 1 inside, times ds.
double kinetic_energy(const rod::RodModel& model, std::span<const Vector6> eta_nodes, double ds);
double strain_energy_segments(const rod::RodModel& model, std::span<const Vector6> xi_segments,
                              double ds);
double strain_energy_nodes(const rod::RodModel& model, std::span<const Vector6> xi_nodes, double ds);
double gravity_energy(const DynamicProblem& problem, std::span<const SE3> g_nodes, double ds);

// Embedded muscles (docs/dynamics.md "Muscles and length control"): the kinetic energy with the
// full node inertia of DynamicProblem::node_inertia, 1/2 <eta, M_j eta> (M_j couples linear and
// angular velocity where a muscle sits off the centreline, (3.20)), and the muscles' own strain
// and gravity energies, which the schemes add to the rod's (zero without muscles).
double kinetic_energy(std::span<const lie::Matrix6> inertia, std::span<const Vector6> eta_nodes,
                      double ds);
double embedded_strain_energy_segments(const DynamicProblem& problem,
                                       std::span<const Vector6> xi_segments, double ds);
double embedded_strain_energy_nodes(const DynamicProblem& problem,
                                    std::span<const Vector6> xi_nodes, double ds);
double embedded_gravity_energy(const DynamicProblem& problem, std::span<const SE3> g_nodes,
                               double ds);

/// Kinetic, strain and gravity energies of a state on the staggered grid (node poses g and
/// velocities eta, segment strains xi; `ida`, collocation, the staggered shooting march), with
/// the embedded muscles when `inertia` (DynamicProblem::node_inertia) is given; dissipated and
/// work_in are left 0.
Energy staggered_energy(const DynamicProblem& problem, std::span<const SE3> g,
                        std::span<const Vector6> eta, std::span<const Vector6> xi, double ds,
                        std::span<const lie::Matrix6> inertia = {});

}  // namespace rodlab::solvers::dynamics
