#pragma once
// The scheme catalogue (rodlab/scene/schemes.hpp: names, problem, order, kind) as rodlab::solvers
// names it; registry.hpp attaches each scheme's solver to its entry.
#include "rodlab/scene/schemes.hpp"

namespace rodlab::solvers {

using scene::all_schemes;
using scene::find_scheme;
using scene::min_nodes;
using scene::Problem;
using scene::scheme_info;
using scene::scheme_names;
using scene::SchemeId;
using scene::SchemeInfo;
using scene::to_string;

}  // namespace rodlab::solvers
