#pragma once
// The reach study of inverse statics (thesis 4.1: 100 random static-workspace targets, 9.33 +-
// 3.24 updates to 1 % tip error with q <- q - 0.2 J^-1 e), for test_inverse_statics and the
// controllers that will follow (tracking, MPC).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <iostream>
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/control/inverse_statics.hpp"
#include "rodlab/solvers/control/static_targets.hpp"

namespace rodlab::testing::control {

using namespace rodlab::solvers::control;

inline scene::Scene cable_driven() {
  return io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/cable-driven.yaml");
}

struct ReachStats {
  int targets = 0, reached = 0, outside_limits = 0;
  double mean_updates = 0.0, std_updates = 0.0, max_error = 0.0, mean_time_s = 0.0;
  int max_updates = 0;
};

/// Draws `count` targets with `seed` (chebyshev N = 24, the scene's scheme) and solves each
/// afresh from the middle of the box (0.25 N each), with `method`.
inline ReachStats reach_study(int count, unsigned seed, double tolerance,
                              InverseStaticsMethod method = InverseStaticsMethod::gauss_newton) {
  const scene::Scene scene = cable_driven();
  const auto targets = sample_static_targets(scene, {"chebyshev", 24, 1e-10, 50}, count, seed);
  BOOST_TEST_REQUIRE(targets.failed == 0);
  InverseStaticsOptions options;
  options.tolerance = tolerance;
  options.method = method;
  InverseStatics solver(scene, options);
  ReachStats s;
  double sum = 0.0, sum2 = 0.0;
  for (std::size_t i = 0; i < targets.tips.size(); ++i) {
    const auto r = solver.solve(targets.tips[i], Eigen::VectorXd::Constant(solver.inputs(), 0.25));
    ++s.targets;
    if (r.reached) ++s.reached;
    else std::cout << "target " << i << " missed: " << r.reason << "\n";
    for (int k = 0; k < solver.inputs(); ++k)
      if (!(r.u[k] >= solver.limits()[k].first && r.u[k] <= solver.limits()[k].second)) ++s.outside_limits;
    sum += r.updates;
    sum2 += double(r.updates) * r.updates;
    s.max_updates = std::max(s.max_updates, r.updates);
    s.max_error = std::max(s.max_error, r.error);
    s.mean_time_s += r.wall_time_s / static_cast<double>(targets.tips.size());
  }
  s.mean_updates = sum / s.targets;
  s.std_updates = std::sqrt(std::max(0.0, sum2 / s.targets - s.mean_updates * s.mean_updates));
 std::cout << (method == InverseStaticsMethod::ceres ? "ceres " : "gauss-newton ") << "reach study (seed " << seed << ", " << s.targets << " targets, tolerance " << tolerance
            << " m): reached " << s.reached << ", updates mean " << s.mean_updates << " std "
            << s.std_updates << " max " << s.max_updates << ", max error " << s.max_error
            << " m, inputs outside limits " << s.outside_limits << ", mean wall time "
            << 1e3 * s.mean_time_s << " ms per target\n";
  return s;
}

}  // namespace rodlab::testing::control
