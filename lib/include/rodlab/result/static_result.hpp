#pragma once
// What every statics scheme returns (interface spec section 4, rodlab.static-result/1).
#include <string>
#include <vector>

#include "rodlab/lie/se3.hpp"

namespace rodlab::result {

struct CenterlineSample {
  double s = 0.0;
  lie::SE3 pose;       ///< g(s) in the world frame
  lie::Vector6 twist;  ///< xi(s) = [omega; nu]
};

struct StaticResult {
  std::string scene, scheme;
  int nodes = 0;
  bool converged = false;
  std::string reason;  ///< why it did not converge (empty when converged)
  int iterations = 0;
  double residual_norm = 0.0;
  double wall_time_s = 0.0;
  std::vector<CenterlineSample> centerline;  ///< base first, tip last
  lie::Vector6 base_wrench = lie::Vector6::Zero();  ///< lambda(0) = K (xi(0) - xi*), [moment; force]
  double max_det_deviation = 0.0;        ///< max |det R - 1| over the centreline
  double max_orthogonality_error = 0.0;  ///< max ||R^T R - I||_F over the centreline
};

}  // namespace rodlab::result
