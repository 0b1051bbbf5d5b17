#include "rodlab/rod/material.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rodlab::rod {

Material Material::from_poisson(double E, double poisson, double rho, double viscosity) {
  if (!(poisson > -1.0 && poisson <= 0.5))
    throw std::invalid_argument("poisson must be in (-1, 0.5] (got " + std::to_string(poisson) + ")");
  return {E, E / (2.0 * (1.0 + poisson)), rho, viscosity};
}

}  // namespace rodlab::rod
