#pragma once
// Energy densities per unit reference length and their integrals over node values. Every
// scheme reports energies through these functions (interface spec section 4).
//   strain   (2.28): U = int 1/2 <xi - xi*, K (xi - xi*)> ds
//   kinetic  (3.5) : T = int 1/2 <eta, M eta> ds
//   gravity        : P = -int rho_eff A <g_r, p - p*> ds, zero in the reference configuration
//   viscous power  : D = int <xi_dot, V xi_dot> ds  (Kelvin-Voigt dissipation rate)
#include <span>

#include "rodlab/rod/rod_model.hpp"

namespace rodlab::rod {

using lie::Vector3;

/// At s: the rest strain xi*(s) (a rest-strain span's begin belongs to it).
double strain_energy_density(const RodModel& model, const Vector6& xi, double s = 0.0);
double kinetic_energy_density(const RodModel& model, const Vector6& eta);
/// rho_eff = rho - fluid_density (buoyancy, (2.36)); p_ref is the reference position p*(s).
double gravity_energy_density(const RodModel& model, const Vector3& gravity, const Vector3& p,
                              const Vector3& p_ref, double fluid_density = 0.0);
double viscous_power_density(const RodModel& model, const Vector6& xi_dot);

/// Trapezoidal rule over samples f_0..f_{n-1} at uniform spacing ds (n >= 2).
double integrate_trapezoid(std::span<const double> f, double ds);

/// Reference configuration g*(s) = g0 exp(s xi*) (constant xi*, (2.78) is exact then; over
/// rest-strain spans the product of their exponentials, RodModel::rest_pose).
lie::SE3 reference_pose(const RodModel& model, const lie::SE3& base, double s);

/// The trapezoidal sum ds sum_j c_j p*(s_j) of the reference centreline p*(s) =
/// reference_pose(model, base, s).translation() over n >= 2 uniform nodes (c_j = 1/2 at the ends,
/// 1 inside), which the gravity energy subtracts at every output. For a straight reference (no
/// rest curvature or twist) p*(s) = p0 + R0 s nu* is linear in s, for which the rule is exact:
/// L p0 + R0 nu* L^2 / 2, with no node evaluated (before: an SE(3) exponential per node and
/// output, 12 % of a short variational run that records every step; then a rotation per node,
/// 6 %).
inline Vector3 reference_centreline_sum(const RodModel& model, const lie::SE3& base, double ds,
                                        std::size_t n) {
  const double L = ds * static_cast<double>(n - 1);
  if (!model.has_rest_spans() && model.xi_star().head<3>().isZero())
    return L * base.translation() +
           base.rotation() * Vector3((0.5 * L * L) * model.xi_star().tail<3>());
  Vector3 sum = Vector3::Zero();
  for (std::size_t j = 0; j < n; ++j)
    sum += (j == 0 || j + 1 == n ? 0.5 : 1.0) *
           reference_pose(model, base, ds * static_cast<double>(j)).translation();
  return ds * sum;
}

}  // namespace rodlab::rod
