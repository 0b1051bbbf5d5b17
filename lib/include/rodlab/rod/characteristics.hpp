#pragma once
// Derived quantities a user wants before running a scene (printed by `rodlab check`).
#include "rodlab/rod/rod_model.hpp"

namespace rodlab::rod {

enum class TipSupport { free, clamped };

struct Characteristics {
  SectionProperties section;
  Vector6 K_diag, M_diag, V_diag;
  double axial_wave_speed = 0;  ///< sqrt(E/rho)
  double shear_wave_speed = 0;  ///< sqrt(G/rho)
  int nodes = 0;
  double ds = 0;                     ///< L / (nodes - 1)
  double dt_cfl = 0;                 ///< ds / c, the CFL bound (3.43) with c = fastest wave speed
  double dt_thesis = 0;              ///< (3.44): 0.1 ds sqrt(rho/E) (0.9 for Kirchhoff)
  double thesis_safety_factor = 0;   ///< 0.1 Cosserat, 0.9 Kirchhoff, as in the thesis
  double first_bending_frequency_hz = 0;  ///< Euler-Bernoulli, weaker axis, given supports
  double first_axial_frequency_hz = 0;
  double shear_to_bending = 0;       ///< G A L^2 / (E I), I the smaller second moment
  double axial_to_bending = 0;       ///< E A L^2 / (E I)
  double kirchhoff_error_estimate = 0;  ///< relative tip-deflection change from shear: 3 E I / (G A L^2)
  bool kirchhoff_safe = false;          ///< estimate below 1 %
};

Characteristics characteristics(const RodModel& model, int nodes, TipSupport tip);

}  // namespace rodlab::rod
