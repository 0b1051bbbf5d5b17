#pragma once
// The localised helical buckle of a twisted Kirchhoff rod under end tension (van der Heijden &
// Thompson 2000, "The spatial elastica of a localized helical buckling"; the case of Gazzola,
// Dudte & Mahadevan 2018, section 4.2), for the "literature" family. Derived in docs/validation.md
// "literature":
//
// An isotropic inextensible, unshearable rod (bending stiffness B, torsional stiffness C) with
// internal force n = T e_z (tension T) and the twisting moment M about its ends' axis e_z. Its
// tangent t = (sin theta cos psi, sin theta sin psi, cos theta) (Euler angles z-y-z, psi, theta,
// phi; R = Rz(psi) Ry(theta) Rz(phi)) has three first integrals: m . t = C tau = M (isotropic
// section), m . e_z = M (no moment about the axis is added along the rod) and the Hamiltonian
// (B / 2) |t'|^2 + T cos theta = T (the rod straight at infinity). With u = 1 - cos theta they give
//     psi' = M / (B (1 + cos theta)),   phi' = M / C - psi' cos theta,
//     u'^2 = (2 T / B) u^2 (a - u),  a = 2 - M^2 / (2 B T),
// whose homoclinic solution is the envelope
//     1 - cos theta(s) = a sech^2(kappa s),   kappa = sqrt(T a / (2 B)),
// (2 (1 - m^2 / 4) sech^2(s sqrt(1 - m^2 / 4)) in units of sqrt(B / T), m = M / sqrt(B T)); it
// exists for m < 2, the twisted straight rod's stability limit under tension.
#include <span>
#include <vector>

#include "rodlab/lie/se3.hpp"

namespace rodlab::validation::reference {

class LocalisedHelix {
 public:
  /// The buckle centred at s = 0 on the rod [-L/2, L/2]; throws std::invalid_argument unless
  /// B, C, T, L > 0 and M^2 < 4 B T.
  LocalisedHelix(double B, double C, double T, double M, double L);

  double amplitude() const { return a_; }  ///< a: 1 - cos theta at the centre
  double decay() const { return kappa_; }  ///< kappa
  /// 1 - cos theta(s), the angle between the tangent and the axis e_z.
  double envelope(double s) const;

  /// The rod's state at one arclength.
  struct Sample {
    lie::SE3 pose;       ///< R = Rz(psi) Ry(theta) Rz(phi), position; psi = phi = 0, p = 0 at -L/2
    lie::Vector6 wrench; ///< the internal wrench in the body frame [B w1, B w2, M; R^T T e_z]
  };
  /// The samples at the ascending arclengths s in [-L/2, L/2] (an rk8pd integration of psi, phi
  /// and the position, at tolerance 1e-13).
  std::vector<Sample> samples(std::span<const double> s) const;

 private:
  double B_, C_, T_, M_, L_, a_, kappa_;
};

}  // namespace rodlab::validation::reference
