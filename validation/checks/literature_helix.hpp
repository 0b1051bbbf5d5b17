#pragma once
// The "literature" family's localised helical buckling (literature_helix.cpp): a twisted Kirchhoff
// rod under end tension against van der Heijden and Thompson's closed-form envelope
// (reference/localised_helix.hpp).
#include <vector>

#include "rodlab/result/static_result.hpp"
#include "rodlab/rod/rod_model.hpp"

#include "checks/check.hpp"
#include "reference/localised_helix.hpp"

namespace rodlab::validation {

std::vector<Check> localised_helix_checks(const ValidationContext& context);

/// The Kirchhoff rod `model` clamped at the closed form's end poses, solved by rkmk-rk4 at
/// `nodes` from the closed form's base wrench with a 1 % error in every component; `exact` the
/// closed form at the nodes (s centred on the rod).
struct LocalisedHelixSolve {
  result::StaticResult result;
  std::vector<double> s;
  std::vector<reference::LocalisedHelix::Sample> exact;
};
LocalisedHelixSolve solve_localised_helix(const rod::RodModel& model,
                                          const reference::LocalisedHelix& helix, int nodes);

}  // namespace rodlab::validation
