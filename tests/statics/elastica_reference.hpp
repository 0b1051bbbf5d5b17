#pragma once
// Independent references for the planar cantilever elastica (inextensible, unshearable rod =
// the Kirchhoff model), clamped at the origin along +z, bending about y, with a tip force of
// magnitude P perpendicular to the undeformed rod (along +x): alpha = P L^2 / EI.
//
// 1. Closed form, dead load (Bisshopp & Drucker 1945, Q. Appl. Math. 3(3):272-275; Timoshenko &
//    Gere, Theory of Elastic Stability, 2nd ed., section 2.7). With theta(s) the tangent angle
//    from +z (tangent (sin theta, 0, cos theta)), the moment about y of the load about the
//    section at s is P (z_tip - z(s)), so
//        EI theta' = P (z_tip - z(s)),   EI theta'' = -P cos theta,   theta(0) = 0, theta'(L) = 0.
//    First integral: EI theta'^2 / 2 = P (sin phi0 - sin theta), phi0 = theta(L) (tip angle).
//    Substituting 1 + sin theta = 2 k^2 sin^2 phi with 2 k^2 = 1 + sin phi0, i.e.
//    k = sin(pi/4 + phi0/2), maps theta = 0 to sin phi1 = 1/(k sqrt 2) and theta = phi0 to
//    phi = pi/2, and gives d theta / sqrt(sin phi0 - sin theta) = sqrt 2 d phi / sqrt(1 - k^2 sin^2 phi):
//        sqrt(alpha) = K(k) - F(phi1, k)                                          (length)
//        z_tip / L = sqrt(2 (2 k^2 - 1) / alpha)              (from EI theta'(0) = P z_tip)
//        x_tip / L = 1 - 2 (E(k) - E(phi1, k)) / sqrt(alpha)
//                    (sin theta = 2 k^2 sin^2 phi - 1 = 1 - 2 (1 - k^2 sin^2 phi))
//        phi0 = asin(2 k^2 - 1)
//    K, F, E: complete/incomplete elliptic integrals of the first and second kind with modulus k
//    (GSL's convention; parameter m = k^2). k is found by bisection on (1/sqrt 2, 1), where
//    K - F(phi1) rises from 0 to infinity.
//
// 2. A direct integration of the planar equations by GSL's rk8pd at 1e-14 (planar_cantilever,
//    validation/reference/planar_rod.hpp), dead or follower tip force, shooting on the tip
//    angle: integrate from the tip (theta = theta_L, m = 0) back to the base and solve
//    theta(0; theta_L) = 0 by bisection (first sign change from theta_L = 0).
//        theta' = m / EI,  m' = -(cos theta F_x - sin theta F_z),  x' = sin theta,  z' = cos theta
//    (m(s) = ((p_L - p(s)) x F)_y). Follower force along the tip's body x axis:
//    F = P (cos theta_L, 0, -sin theta_L).
//
// Both were cross-checked with mpmath (30 digits, ellipk/ellipf/ellipe and an odefun shooting):
//   alpha = 1:  x/L = 0.30172077379981353, z/L = 0.94356676371662312, phi0 = 0.46135194971187896
//   alpha = 2:  x/L = 0.49345748039671182, z/L = 0.83935827917483276, phi0 = 0.78174983155654304
//   alpha = 5:  x/L = 0.71379152361191273, z/L = 0.61237163927557013, phi0 = 1.2153681176116811
//   alpha = 10: x/L = 0.81060902488029645, z/L = 0.44500440224624873, phi0 = 1.4302855388038575
// Bisshopp & Drucker's 4-digit table: alpha = 1: vertical 0.3017 L; alpha = 10: vertical
// 0.8106 L. (The horizontal displacement 1 - z/L is 0.0564 L at alpha = 1 and 0.5550 L at
// alpha = 10; the tip angle at alpha = 1 is 0.4614 rad = 26.43 deg.)
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gsl/gsl_sf_ellint.h>

#include "reference/planar_rod.hpp"

namespace rodlab::testing::statics {

/// theta: the tip angle from +z towards +x [rad]; x, z: the tip / L (L = 1 here).
using PlanarTip = validation::reference::PlanarTip;

/// The closed form (1) above for a dead load, alpha = P L^2/EI > 0.
inline PlanarTip elastica_dead_load_elliptic(double alpha) {
  const double root = std::sqrt(alpha);
  auto phi1_of = [](double k) { return std::asin(std::min(1.0, 1.0 / (k * std::numbers::sqrt2))); };
  auto length = [&](double k) {
    return gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE) - gsl_sf_ellint_F(phi1_of(k), k, GSL_PREC_DOUBLE);
  };
  double lo = 1.0 / std::numbers::sqrt2, hi = 1.0 - 1e-16;
  if (!(length(hi) > root)) throw std::domain_error("elastica: alpha too large for the bisection bracket");
  for (int i = 0; i < 200 && hi - lo > 1e-17; ++i) {
    const double mid = 0.5 * (lo + hi);
    (length(mid) < root ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi), phi1 = phi1_of(k);
  PlanarTip t;
  t.theta = std::asin(2.0 * k * k - 1.0);
  t.z = std::sqrt(2.0 * (2.0 * k * k - 1.0) / alpha);
  t.x = 1.0 - 2.0 * (gsl_sf_ellint_Ecomp(k, GSL_PREC_DOUBLE) - gsl_sf_ellint_E(phi1, k, GSL_PREC_DOUBLE)) / root;
  return t;
}

/// The direct integration (2) above (validation/reference/planar_rod.hpp, L = EI = 1,
/// inextensible), dead tip force alpha along +x.
inline PlanarTip elastica_dead_load_ode(double alpha) {
  return validation::reference::planar_cantilever({1.0, 1.0, 0.0, 0.0}, {0, 0, alpha, 0}, 0.0,
                                                  0.01);
}

/// Follower force of magnitude alpha along the tip's body x axis, Ry(theta_L) e_x.
inline PlanarTip elastica_follower_ode(double alpha) {
  return validation::reference::planar_cantilever({1.0, 1.0, 0.0, 0.0},
                                                  {0, 0, alpha, 0, true}, 0.0, 0.01);
}

}  // namespace rodlab::testing::statics
