#pragma once
// A fluidic chamber (thesis 2.4.3, (2.48)-(2.53)) as the tendon it acts as (docs/statics.md
// "Actuators"): the fluid at pressure P pushes on the chamber's walls and caps; over any cut the
// net load is the pressure on the fluid column, a force -P A_c along the chamber's centreline at
// its offset, anchored at both caps. So the chamber is a tendon of tension F = -P A_c, and under
// volume control its length is V / A_c (the section is rigid), (2.53). The thesis's distributed
// moment (2.50)-(2.51) depends on an Euler-angle parametrisation and is replaced by this.
#include <numbers>

namespace rodlab::loads {

/// A_c = pi r_c^2, the chamber's cross-section [m^2].
constexpr double chamber_area(double chamber_radius) {
  return std::numbers::pi * chamber_radius * chamber_radius;
}

/// The chamber's axial (tendon) force at pressure P [N]: F = -P A_c (tension positive).
constexpr double fluidic_chamber_force(double pressure, double area) { return -pressure * area; }

/// The pressure that a chamber's axial force F stands for: P = -F / A_c.
constexpr double fluidic_chamber_pressure(double force, double area) { return -force / area; }

/// Volume control, (2.53): the chamber's path length for a volume V (rigid section), V / A_c.
constexpr double chamber_length(double volume, double area) { return volume / area; }

}  // namespace rodlab::loads
