#pragma once
// An independent reference for planar cantilevers under dead loads: the rod's equilibrium in the
// x-z plane written as four first-order ODEs and integrated by GSL's rk8pd at 1e-14, shooting
// on the tip angle. It shares no code with rodlab's schemes (no Lie groups, no K matrix), so it
// checks them; docs/validation.md "literature".
//
// The rod is clamped at the origin along +z and bends about y. theta(s) is the angle of the
// section from +z towards +x: d3 = (sin theta, cos theta), d1 = (cos theta, -sin theta) in
// (x, z). n(s) is the force that the part beyond s exerts on the part before it; with a uniform
// world load f per unit length and a tip force F, n(s) = F + (L - s) f. Linear law of (2.28):
//     n . d1 = GA nu1,   n . d3 = EA (nu3 - 1),   m = EI theta'
// (Kirchhoff: nu1 = 0, nu3 = 1), and the balance of moments about y, m' + (p' x n)_y = 0:
//     theta' = m / EI,   m' = n_z p'_x - n_x p'_z,   p' = nu1 d1 + nu3 d3,   n' = -f.
// Shooting: from the tip (theta = theta_L, m = 0, n = F) back to the base, theta(0; theta_L) = 0
// by bisection on the first sign change met when theta_L walks away from `start`. A follower tip
// force is F = Fx d1(theta_L) + Fz d3(theta_L).
//
// Cross-checked with mpmath (30 digits) for the tip-loaded Kirchhoff elastica, L = EI = 1
// (tests/statics/elastica_reference.hpp): alpha = 1, x = 0.30172077379981353,
// z = 0.94356676371662312, theta_L = 0.46135194971187896.

namespace rodlab::validation::reference {

struct PlanarRod {
  double length = 1.0;
  double EI = 1.0;
  double GA = 0.0;  ///< shear stiffness; 0 with EA = 0: inextensible and unshearable (Kirchhoff)
  double EA = 0.0;
  bool kirchhoff() const { return GA == 0.0 && EA == 0.0; }
};

struct PlanarLoads {
  double fx = 0.0, fz = 0.0;  ///< uniform world force per unit length [N/m]
  double Fx = 0.0, Fz = 0.0;  ///< tip force [N]: world (x, z), or along (d1, d3) if follower
  bool follower = false;      ///< the tip force turns with the tip section
};

struct PlanarTip {
  double theta = 0.0;  ///< tip angle from +z towards +x [rad]
  double x = 0.0;      ///< tip position [m]
  double z = 0.0;
};

/// The equilibrium whose tip angle is the first root of theta(0; theta_L) met walking theta_L
/// from `start` in steps of `step` (either sign; away from the straight root when start != 0).
/// Throws std::runtime_error when no root is bracketed within 2000 steps or rk8pd fails.
PlanarTip planar_cantilever(const PlanarRod& rod, const PlanarLoads& loads, double start,
                            double step);

}  // namespace rodlab::validation::reference
