#pragma once
// Natural frequencies of a clamped-free rod, for the "literature" family's free vibration
// (docs/validation.md "literature").
//
// Bending: the linearised Cosserat rod about the straight state is the Timoshenko beam with the
// shear stiffness G A (shear coefficient 1, as rodlab's K (2.28)) and the rotary inertia rho I
// (3.5). With w the deflection and psi the section's rotation, w, psi ~ e^{i omega t}:
//     G A (w'' - psi') + rho A omega^2 w = 0,   E I psi'' + G A (w' - psi) + rho I omega^2 psi = 0,
// clamped w = psi = 0 at s = 0, free psi' = 0 and w' = psi at s = L (Timoshenko 1921; the
// cantilever's frequency equation is Huang's, J. Appl. Mech. 28 (1961) 579-584). The frequencies
// are the zeros of the 2 x 2 determinant of the free-end conditions over the two solutions that
// start clamped, integrated by GSL's rk8pd at 1e-13; the roots are bracketed on a scan in omega
// and bisected.
//
// Torsion and extension: the wave equations G Jt theta'' = rho J theta_tt and
// E A u'' = rho A u_tt, clamped-free: f_n = (2n - 1) / (4 L) c with the wave speed
// c = sqrt(G Jt / (rho J)), resp. sqrt(E / rho).
#include <vector>

namespace rodlab::validation::reference {

struct TimoshenkoBeam {
  double length, EI, GA, rhoA, rhoI;
};

/// The first `count` bending frequencies [Hz] of the clamped-free Timoshenko beam, ascending.
/// Throws std::runtime_error when rk8pd fails or fewer roots lie below the scan's end.
std::vector<double> timoshenko_cantilever_frequencies(const TimoshenkoBeam& beam, int count);

/// The n-th (1-based) frequency [Hz] of a clamped-free rod's wave equation with wave speed c.
double clamped_free_wave_frequency(double length, double wave_speed, int n);

}  // namespace rodlab::validation::reference
