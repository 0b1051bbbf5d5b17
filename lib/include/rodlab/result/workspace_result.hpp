#pragma once
// The static workspace (thesis 2.7.3): sampled actuator inputs, the tips they reach, and the
// bounds of the constant-curvature workspace model that encloses them.
#include <string>
#include <vector>

#include "rodlab/lie/se3.hpp"

namespace rodlab::result {

/// Coordinates of a tip position in the constant-curvature, constant-stretch model
/// (2.116)-(2.120): bending omega >= 0 about an axis at angle phi, stretch epsilon.
struct WorkspaceCoordinates {
  double omega = 0.0, phi = 0.0, epsilon = 0.0;
};

/// Bounds of the model workspace: 0 <= omega <= omega_bound, eps_low <= epsilon <= eps_high.
struct WorkspaceBounds {
  double omega_bound = 0.0, eps_low = 0.0, eps_high = 0.0;
};

struct WorkspaceSample {
  std::vector<double> inputs;  ///< one per actuator, in scene order
  lie::Vector3 tip = lie::Vector3::Zero();  ///< tip position in the base frame
  WorkspaceCoordinates coordinates;
  bool converged = false;
};

struct WorkspaceResult {
  std::string scene, scheme;
  int nodes = 0;
  double length = 0.0;
  unsigned seed = 0;
  std::vector<WorkspaceSample> samples;
  WorkspaceBounds bounds;  ///< fitted on the converged samples
  int failed = 0;
  double wall_time_s = 0.0;
};

}  // namespace rodlab::result
