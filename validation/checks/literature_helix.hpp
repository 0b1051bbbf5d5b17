#pragma once
// The "literature" family's localised helical buckling (literature_helix.cpp): a twisted Kirchhoff
// rod under end tension against van der Heijden and Thompson's closed-form envelope
// (reference/localised_helix.hpp).
#include <vector>

#include "checks/check.hpp"

namespace rodlab::validation {

std::vector<Check> localised_helix_checks(const ValidationContext& context);

}  // namespace rodlab::validation
