#pragma once
// Static workspace (thesis 2.7.3, (2.116)-(2.127)): sample the actuator inputs within their
// limits, solve the statics for each sample, and fit the bounds of the constant-curvature
// workspace model around the reached tips. The coordinate map is made robust where the thesis's
// is singular (docs/statics.md): omega from atan2 (tips bent past 90 degrees), epsilon from the
// chord length |p| = 2 sin(omega L / 2) (1 + epsilon) / omega instead of (2.123), which divides
// by sin(omega L) and fails at omega L = pi.
#include <functional>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include "rodlab/result/workspace_result.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::solvers::statics {

using result::WorkspaceBounds;
using result::WorkspaceCoordinates;

/// (2.121)-(2.127): model coordinates of a tip position p (base frame) of a rod of length L.
WorkspaceCoordinates workspace_coordinates(const Vector3& p, double L);
/// (2.120): the tip position of the model at given coordinates.
Vector3 workspace_tip(const WorkspaceCoordinates& c, double L);
/// Point membership: is p inside the model workspace with these bounds? (used by control)
bool workspace_contains(const WorkspaceBounds& bounds, const Vector3& p, double L, double margin = 0.0);

/// The input that drives each actuator of `scene` (tension, displacement, pressure, volume or
/// q), as a pointer into the scene so that a sample can overwrite it, with its limits. Throws
/// std::invalid_argument naming the actuator when it has no `limits`.
struct WorkspaceInput {
  scene::ScalarSchedule* value;
  std::pair<double, double> limits;
};
std::vector<WorkspaceInput> workspace_inputs(scene::Scene& scene);

/// A value uniform in [lo, hi] from the raw generator (std distributions differ across
/// platforms, and runs must repeat).
double workspace_uniform(std::mt19937& rng, double lo, double hi);

/// The bounds (2.116)-(2.120) that enclose the converged samples.
WorkspaceBounds fit_workspace_bounds(std::span<const result::WorkspaceSample> samples);

/// Samples `samples` input vectors uniformly within every actuator's `limits` (std::mt19937
/// with `seed`), solves each, fits the bounds. Throws std::invalid_argument if the scene has no
/// actuators or an actuator has no limits. `progress` (if set) is called after every sample.
result::WorkspaceResult sample_workspace(
    const scene::Scene& scene, const StaticSolveOptions& options, int samples, unsigned seed = 1,
    const std::function<void(int done, int total)>& progress = {});

}  // namespace rodlab::solvers::statics
