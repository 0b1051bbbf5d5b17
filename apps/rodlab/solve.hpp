#pragma once
// From a checked scene and run settings to a result: the bridge between the command line and
// the solvers library. Adding a scheme means adding its call here, nothing else: the
// subcommands already check the input, ask availability.hpp, write the result and choose
// the exit status.
#include "rodlab/result/dynamic_result.hpp"
#include "rodlab/result/static_result.hpp"
#include "rodlab/scene/scene.hpp"

#include "common_options.hpp"

namespace rodlab::cli {

/// Runs the statics scheme of `run`. Only called for schemes the catalogue marks available.
result::StaticResult solve_static(const scene::Scene& scene, const StaticRun& run);
/// Runs the dynamics scheme of `run` (run.dt resolved: automatic steps are already replaced
/// by the explicit step (3.44)).
result::DynamicResult solve_dynamic(const scene::Scene& scene, const DynamicRun& run);

}  // namespace rodlab::cli
