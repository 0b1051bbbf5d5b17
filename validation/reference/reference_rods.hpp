#pragma once
// The reference rods of the validation suite, the tests and the benchmarks, defined once with
// their closed forms. Table 2.1 of the thesis (section 2.7): E = 1 MPa, G = 0.33 MPa,
// rho = 1000 kg/m^3, a circular section of D = 1 cm, L = 10 cm, straight along +z from the
// origin. Closed forms that lib/ already provides (rod::characteristics: the Euler-Bernoulli
// frequencies, wave speeds, the explicit step) are taken from there, not re-derived.
#include <numbers>
#include <string>

#include "rodlab/rod/characteristics.hpp"
#include "rodlab/rod/rod_model.hpp"

namespace rodlab::validation::reference {

struct Table21 {
  static constexpr double E = 1.0e6, G = 0.33e6, rho = 1000.0, D = 0.01, L = 0.1;
  static constexpr double pi = std::numbers::pi;
  static constexpr double A = pi * D * D / 4.0;           // 7.853981634e-5 m^2
  static constexpr double I = pi * D * D * D * D / 64.0;  // 4.908738521e-10 m^4
  static constexpr double J = 2.0 * I;                    // polar = torsion constant (circle)
  static constexpr double EI = E * I;                     // 4.908738521e-4 N m^2
  static constexpr double GJ = G * J;
  static constexpr double GA = G * A;                     // 25.918 N
  static constexpr double EA = E * A;                     // 78.540 N
  static constexpr double rhoA = rho * A;                 // 0.0785 kg/m
  static constexpr double weight = rho * A * 9.81;        // 0.77048 N/m
};

/// The Table 2.1 rod (Kelvin-Voigt viscosity alpha [Pa s], 0 by default).
inline rod::RodModel table21_model(rod::ModelKind kind = rod::ModelKind::cosserat,
                                   double length = Table21::L, double viscosity = 0.0) {
  return {length, rod::Circle{Table21::D},
          rod::Material{Table21::E, Table21::G, Table21::rho, viscosity}, kind};
}

/// Its `rod:` block for a scene written in code, with the viscosity as given (YAML text).
inline std::string table21_rod_yaml(const std::string& viscosity = "0",
                                    const std::string& model = "cosserat") {
  return "rod:\n  model: " + model +
         "\n  length: 0.1\n  section: {shape: circle, diameter: 0.01}\n"
         "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: " + viscosity + "}\n";
}

/// First bending frequency of the Table 2.1 cantilever (clamped base, free tip), Euler-Bernoulli:
/// f1 = 1.8751^2 / (2 pi) sqrt(EI / (rho A L^4)) = 4.424 Hz (rod::characteristics).
inline double table21_first_bending_frequency_hz() {
  return rod::characteristics(table21_model(), 2, rod::TipSupport::free)
      .first_bending_frequency_hz;
}

}  // namespace rodlab::validation::reference
