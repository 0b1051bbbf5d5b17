#pragma once
// States of the semi-discrete rod for the tests of its f and Newton matrix
// (test_analytic_jacobian.cpp, test_semi_discrete_packed.cpp).
#include <random>
#include <vector>

#include "rodlab/lie/se3.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"

namespace rodlab::testing::dynamics {

/// A bent, moving state: node poses from random strains (curvature `curvature` rad/m per bending
/// component, so segment angles ~1.3 ds curvature; shear and stretch ~1e-2), velocities 0.3 omega_1
/// and 0.3 omega_1 L, every quaternion scaled by 1.3 (R is formed from q / |q|) and every other one
/// negated. A clamped tip's chain is bent onto the clamp, a share per node.
inline solvers::dynamics::SemiDiscreteRod::Vector bent_moving_state(
    const solvers::dynamics::SemiDiscreteRod& rod, double curvature, unsigned seed) {
  using solvers::dynamics::SemiDiscreteRod;
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  const double ds = rod.ds(), L = rod.problem().length(), w1 = rod.omega1();
  const int N = rod.nodes();
  std::vector<lie::SE3> g(N, rod.problem().base());
  std::vector<lie::Vector6> eta(N, lie::Vector6::Zero());
  for (int j = 1; j < N; ++j) {
    lie::Vector6 xi;
    xi << curvature * n(rng), curvature * n(rng), 0.4 * curvature * n(rng), 0.01 * n(rng),
        0.01 * n(rng), 1.0 + 0.01 * n(rng);
    g[j] = g[j - 1] * lie::SE3::exp(ds * xi);
    for (int i = 0; i < 6; ++i) eta[j][i] = 0.3 * (i < 3 ? w1 : w1 * L) * n(rng);
  }
  if (rod.problem().tip_clamped()) {
    const lie::Vector6 miss = (g.back().inverse() * rod.problem().tip_target()).log();
    for (int j = 1; j < N; ++j) g[j] = g[j] * lie::SE3::exp(miss * (j / (N - 1.0)));
    eta.back().setZero();
  }
  SemiDiscreteRod::Vector y = SemiDiscreteRod::Vector::Zero(rod.size());
  rod.pack_nodes(g, eta, y);
  for (int j = 0; j * SemiDiscreteRod::kBlock < rod.node_size(); ++j)
    y.segment<4>(SemiDiscreteRod::kBlock * j + SemiDiscreteRod::kQ) *= (j % 2 ? -1.3 : 1.3);
  return y;
}

}  // namespace rodlab::testing::dynamics
