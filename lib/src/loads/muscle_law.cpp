#include "rodlab/loads/muscle_law.hpp"

#include <stdexcept>

#include "rodlab/check.hpp"

namespace rodlab::loads {

std::shared_ptr<const MuscleLaw> make_muscle_law(std::string_view type, double gain, double stiffness) {
  if (type == "linear") return std::make_shared<LinearMuscleLaw>(gain, stiffness);
  throw std::invalid_argument(rodlab::format("unknown muscle law '{}' (valid: linear)", type));
}

}  // namespace rodlab::loads
