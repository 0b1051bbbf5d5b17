#pragma once
// The dynamic workspace (thesis 3.4.1): a soft rod reaches beyond its static workspace by
// building up momentum, to points it cannot hold. As in the thesis, random inputs are held
// constant for a while each (so momentum builds up), in one simulation, and the workspace model
// of the statics (2.116)-(2.127) is fitted around every tip position the run reaches (the
// outputs of the run). The result has the static workspace's form, so the two compare directly
// (docs/dynamics.md, "Dynamic workspace").
#include "rodlab/result/workspace_result.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"

namespace rodlab::solvers::dynamics {

struct DynamicWorkspaceOptions {
  DynamicSolveOptions solve;  ///< scheme, nodes, dt, tol (t_end is holds x hold_time)
  int holds = 10;             ///< input vectors, each held for hold_time
  double hold_time = 0.0;     ///< [s] > 0
  int outputs_per_hold = 50;  ///< tip positions recorded per hold
  unsigned seed = 1;
};

/// Draws `holds` input vectors uniformly within every actuator's limits (the generator of the
/// static workspace, so the same seed gives the same first draws), holds each for hold_time,
/// simulates from the scene's initial state and returns every recorded tip as a sample (its
/// inputs: those held at that time), with the fitted bounds. A run that fails (instability,
/// non-convergence) keeps the samples it reached and counts one failure. Throws
/// std::invalid_argument for a scene without actuators or limits, or bad options.
result::WorkspaceResult sample_dynamic_workspace(const scene::Scene& scene,
                                                 const DynamicWorkspaceOptions& options);

}  // namespace rodlab::solvers::dynamics
