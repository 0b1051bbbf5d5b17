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
// 2. A direct integration of the planar equations by GSL's rk8pd at 1e-14, for any tip force
//    that depends on the tip angle (dead or follower), shooting on the tip angle: integrate
//    from the tip (theta = theta_L, m = 0) back to the base and solve theta(0; theta_L) = 0 by
//    bisection (first sign change from theta_L = 0).
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
#include <functional>
#include <numbers>
#include <stdexcept>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <gsl/gsl_sf_ellint.h>

namespace rodlab::testing::statics {

struct PlanarTip {
  double theta = 0.0;  ///< tip angle from +z towards +x [rad]
  double x = 0.0;      ///< tip x / L
  double z = 0.0;      ///< tip z / L
};

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

/// The direct integration (2) above, L = EI = 1; force(theta_L) gives (F_x, F_z) in units of
/// EI / L^2.
inline PlanarTip elastica_ode(const std::function<void(double, double&, double&)>& force) {
  struct Params {
    double Fx, Fz;
  };
  auto rhs = [](double, const double y[], double dydt[], void* params) -> int {
    const auto* p = static_cast<const Params*>(params);
    dydt[0] = y[1];
    dydt[1] = -(std::cos(y[0]) * p->Fx - std::sin(y[0]) * p->Fz);
    dydt[2] = std::sin(y[0]);
    dydt[3] = std::cos(y[0]);
    return GSL_SUCCESS;
  };
  // Integrates from the tip back to the base; returns theta(0), fills the base position
  // relative to the tip.
  auto shoot = [&](double theta_L, double& x0, double& z0) {
    Params p{};
    force(theta_L, p.Fx, p.Fz);
    gsl_odeiv2_system sys{rhs, nullptr, 4, &p};
    gsl_odeiv2_driver* d = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rk8pd, -1e-3, 1e-14, 1e-14);
    double s = 1.0, y[4] = {theta_L, 0.0, 0.0, 0.0};
    const int status = gsl_odeiv2_driver_apply(d, &s, 0.0, y);
    gsl_odeiv2_driver_free(d);
    if (status != GSL_SUCCESS) throw std::runtime_error("elastica_ode: integration failed");
    x0 = y[2];
    z0 = y[3];
    return y[0];
  };
  double x0, z0;
  double lo = 0.0, f_lo = shoot(lo, x0, z0), hi = lo;
  // First sign change of theta(0; theta_L) from theta_L = 0 upwards.
  for (int i = 1; i <= 2000; ++i) {
    hi = 0.01 * i;
    const double f_hi = shoot(hi, x0, z0);
    if ((f_lo < 0) != (f_hi < 0)) break;
    lo = hi;
    f_lo = f_hi;
    if (i == 2000) throw std::runtime_error("elastica_ode: no root bracketed");
  }
  for (int i = 0; i < 100 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double f_mid = shoot(mid, x0, z0);
    if ((f_mid < 0) == (f_lo < 0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  PlanarTip t;
  t.theta = 0.5 * (lo + hi);
  shoot(t.theta, x0, z0);
  t.x = -x0;  // the tip relative to the base
  t.z = -z0;
  return t;
}

inline PlanarTip elastica_dead_load_ode(double alpha) {
  return elastica_ode([alpha](double, double& Fx, double& Fz) {
    Fx = alpha;
    Fz = 0.0;
  });
}

/// Follower force of magnitude alpha along the tip's body x axis, Ry(theta_L) e_x.
inline PlanarTip elastica_follower_ode(double alpha) {
  return elastica_ode([alpha](double theta_L, double& Fx, double& Fz) {
    Fx = alpha * std::cos(theta_L);
    Fz = -alpha * std::sin(theta_L);
  });
}

}  // namespace rodlab::testing::statics
