#pragma once
// The constitutive law with tendon-like actuators, solved for the strain (docs/statics.md):
//
//     Kt (xi - xi_ref) + sum_k F_k c_k(xi) = Lambda,
//
// by Newton from xi_ref (or a given guess: the last iterate of an outer iteration, from which
// Newton needs one or two steps instead of three to five). Kt is the rod's (effective) stiffness: K in the statics (plus embedded
// muscle stiffness), K + 2 V / dt in an implicit-midpoint step. Kirchhoff rods solve the moment
// rows for omega only and keep nu = nu_ref. `add_tendons(xi, r, J)` adds sum_k F_k c_k(xi) to r
// and its Jacobian to J.
#include "rodlab/lie/se3.hpp"
#include "rodlab/solvers/common/small_lu.hpp"

namespace rodlab::solvers {

template <class AddTendons>
lie::Vector6 solve_tendon_law(const lie::Matrix6& Kt, const lie::Vector6& xi_ref,
                              const lie::Vector6& Lambda, bool kirchhoff, AddTendons add_tendons,
                              const lie::Vector6* guess = nullptr) {
  constexpr int kMaxIterations = 30;
  lie::Vector6 xi = guess != nullptr ? *guess : xi_ref, r;
  if (kirchhoff) xi.tail<3>() = xi_ref.tail<3>();
  lie::Matrix6 J;
  for (int it = 0; it < kMaxIterations; ++it) {
    r = Kt * (xi - xi_ref) - Lambda;
    J = Kt;
    add_tendons(xi, r, J);
    lie::Vector6 dxi = lie::Vector6::Zero();
    if (kirchhoff)
      dxi.head<3>() = -solve_partial_pivoting<3>(J.topLeftCorner<3, 3>(), r.head<3>());
    else
      dxi = -solve_partial_pivoting<6>(J, r);
    xi += dxi;
    if (!xi.allFinite()) break;
    if (dxi.lpNorm<Eigen::Infinity>() <= 1e-15 * (1.0 + (xi - xi_ref).lpNorm<Eigen::Infinity>()))
      break;
  }
  return xi;
}

}  // namespace rodlab::solvers
