#include "rodlab/rod/material.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "rodlab/check.hpp"

namespace rodlab::rod {

Material Material::from_poisson(double E, double poisson, double rho, double viscosity) {
  RODLAB_THROW_UNLESS(poisson > -1.0 && poisson <= 0.5, "poisson must be in (-1, 0.5] (got {:g})",
                      poisson);
  return {E, E / (2.0 * (1.0 + poisson)), rho, viscosity};
}

}  // namespace rodlab::rod
