#pragma once
// The "literature" family's free vibration (literature_frequencies.cpp): the first three bending,
// the first torsional and the first axial natural frequencies of the Table 2.1 cantilever, from
// the dynamics schemes' free vibration, against the Timoshenko beam and the wave equations
// (reference/cantilever_frequencies.hpp).
#include <vector>

#include "checks/check.hpp"

namespace rodlab::validation {

std::vector<Check> free_vibration_frequencies(const ValidationContext& context);

}  // namespace rodlab::validation
