#pragma once
// The constitutive reference of a rod with embedded muscles in one step of a shooting scheme,
// shared by the two marches (shooting_stepper.cpp on the nodes, staggered_shooting_stepper.cpp
// on the segments). Private to solvers/dynamics.
//
// With the strain rate xi_dot = c xi + h (time_rule.hpp) the stress (3.10) with the muscles'
// stiffness and viscosity transported to the rod's axis ((3.19), docs/dynamics.md "The embedded
// rod") is
//   Lambda = (K + K_emb) (xi - xi*) + (V + V_emb) (c xi + h) + tendons = Kt (xi - xi_ref) + tendons,
//   Kt = K + K_emb + c (V + V_emb),   Kt xi_ref = (K + K_emb) xi* - (V + V_emb) h,
// a full 6 x 6 Kt when a muscle sits off the axis. Kirchhoff rods keep nu_ref = nu* and solve the
// moment rows for omega_ref.
#include <Eigen/LU>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"

namespace rodlab::solvers::dynamics {

/// Kt and xi_ref (header) at one point of the grid from its rest strain xs, the embedded
/// stiffness K_emb and viscosity V_emb there (DynamicProblem::embedded_stiffness /
/// embedded_viscosity), the step constant c and the history h of the strain rate.
inline void embedded_reference(const DynamicProblem& P, const Vector6& xs,
                               const lie::Matrix6& K_emb, const lie::Matrix6& V_emb, double c,
                               const Vector6& h, lie::Matrix6& Kt, Vector6& xi_ref) {
  const lie::Matrix6 Ktot = lie::Matrix6(P.model().K_diag().asDiagonal()) + K_emb;
  const lie::Matrix6 Vtot = lie::Matrix6(P.model().V_diag().asDiagonal()) + V_emb;
  Kt = Ktot + c * Vtot;
  const Vector6 b = Ktot * xs - Vtot * h;
  if (P.is_kirchhoff()) {
    xi_ref.tail<3>() = xs.tail<3>();
    xi_ref.head<3>() = Kt.topLeftCorner<3, 3>().partialPivLu().solve(
        Vector3(b.head<3>() - Kt.topRightCorner<3, 3>() * xs.tail<3>()));
  } else {
    xi_ref = Kt.partialPivLu().solve(b);
  }
}

}  // namespace rodlab::solvers::dynamics
