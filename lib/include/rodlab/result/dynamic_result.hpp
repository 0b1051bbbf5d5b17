#pragma once
// What every dynamics scheme returns (interface spec section 4, rodlab.dynamic-result/1).
#include <string>
#include <vector>

#include "rodlab/result/static_result.hpp"

namespace rodlab::result {

struct EnergySeries {
  std::vector<double> kinetic, strain, gravity, dissipated, work_in, total;
};

struct DynamicResult {
  std::string scene, scheme;
  int nodes = 0;
  double dt = 0.0;
  long steps = 0;
  bool converged = false;
  std::string reason;
  double wall_time_s = 0.0;
  double real_time_ratio = 0.0;  ///< wall time / simulated time
  std::vector<double> t;
  std::vector<lie::Vector3> tip_position;
  EnergySeries energy;
  std::vector<double> max_det_deviation;
  std::vector<CenterlineSample> final_centerline;
};

}  // namespace rodlab::result
