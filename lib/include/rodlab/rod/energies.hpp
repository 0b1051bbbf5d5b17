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

double strain_energy_density(const RodModel& model, const Vector6& xi);
double kinetic_energy_density(const RodModel& model, const Vector6& eta);
/// rho_eff = rho - fluid_density (buoyancy, (2.36)); p_ref is the reference position p*(s).
double gravity_energy_density(const RodModel& model, const Vector3& gravity, const Vector3& p,
                              const Vector3& p_ref, double fluid_density = 0.0);
double viscous_power_density(const RodModel& model, const Vector6& xi_dot);

/// Trapezoidal rule over samples f_0..f_{n-1} at uniform spacing ds (n >= 2).
double integrate_trapezoid(std::span<const double> f, double ds);

/// Reference configuration g*(s) = g0 exp(s xi*) (constant xi*, (2.78) is exact then).
lie::SE3 reference_pose(const RodModel& model, const lie::SE3& base, double s);

/// Its centreline p*(s), reference_pose(model, base, s).translation() to the last bit. For a
/// straight reference (no rest curvature or twist) exp(s xi*) = (I, s nu*), and p* = p0 + R0
/// s nu* without an SE(3) exponential: the gravity energy evaluates it at every node and
/// output (12 % of a short variational run that records every step).
inline Vector3 reference_position(const RodModel& model, const lie::SE3& base, double s) {
  const Vector6 x = s * model.xi_star();
  if (!x.head<3>().isZero()) return reference_pose(model, base, s).translation();
  return base.translation() + base.rotation() * Vector3(x.tail<3>());
}

}  // namespace rodlab::rod
