#pragma once
// Linear elastic material with Kelvin-Voigt viscosity (thesis (2.23)-(2.26), (3.10)).

namespace rodlab::rod {

struct Material {
  double E = 0.0;          ///< Young's modulus [Pa]
  double G = 0.0;          ///< shear modulus [Pa]
  double rho = 0.0;        ///< density [kg/m^3]
  double viscosity = 0.0;  ///< Kelvin-Voigt shear viscosity alpha [Pa s]; 0: elastic

  /// G = E / (2 (1 + poisson)); throws std::invalid_argument unless -1 < poisson <= 0.5.
  static Material from_poisson(double E, double poisson, double rho, double viscosity = 0.0);

  /// E / (2 G) - 1.
  double poisson() const { return E / (2.0 * G) - 1.0; }
};

}  // namespace rodlab::rod
