#pragma once
// The path lengths of the actuators with unknowns (muscles, length control) on the staggered
// grid (nodes and segments of `variational`, `ida` and the staggered shooting march):
//   L_e(xi) = sum_j o_j |u_e(s_j + ds/2, xi_j)|,
// o_j the overlap of segment j with actuator e's span, |u_e| the path's length rate (2.46) at the
// segment's midpoint; the rest length Delta*_e is the same sum at xi*. SemiDiscreteRod
// (segment_lengths) evaluates the same sum on its own state. Private to solvers/dynamics.
#include <cstddef>
#include <span>
#include <vector>

#include "rodlab/solvers/dynamics/dynamic_problem.hpp"

namespace rodlab::solvers::dynamics {

class StaggeredPaths {
 public:
  StaggeredPaths() = default;
  /// The actuators `which` (indices into problem.actuators()) on a grid of `nodes` nodes.
  StaggeredPaths(const DynamicProblem& problem, std::vector<int> which, int nodes)
      : P_(&problem), which_(std::move(which)), n_(nodes),
        ds_(problem.length() / (nodes - 1)) {
    const std::size_t m = which_.size();
    weight_.assign(m * (n_ - 1), 0.0);
    rest_.assign(m, 0.0);
    std::vector<lie::Vector6> reference(n_ - 1);  // each segment's rest strain
    for (int j = 0; j + 1 < n_; ++j) reference[j] = problem.model().xi_star((j + 0.5) * ds_);
    for (std::size_t e = 0; e < m; ++e) {
      for (int j = 0; j + 1 < n_; ++j)
        weight_[e * (n_ - 1) + j] = problem.span_overlap(which_[e], j * ds_, (j + 1) * ds_);
      rest_[e] = length(static_cast<int>(e), reference);
    }
  }

  /// L_e of the segments' strains xi (N - 1 of them).
  double length(int e, std::span<const lie::Vector6> xi) const {
    const auto& path = P_->actuators()[which_[e]].path;
    const std::size_t row = static_cast<std::size_t>(e) * (n_ - 1);
    double sum = 0.0;
    for (int j = 0; j + 1 < n_; ++j) {
      const double o = weight_[row + j];
      if (o != 0.0) sum += o * path.length_rate((j + 0.5) * ds_, xi[j]);
    }
    return sum;
  }

  /// Delta*_e, the grid's rest lengths (in the order of `which`).
  const std::vector<double>& rest() const { return rest_; }
  /// o_j of actuator e, segment j.
  double overlap(int e, int j) const { return weight_[static_cast<std::size_t>(e) * (n_ - 1) + j]; }

 private:
  const DynamicProblem* P_ = nullptr;
  std::vector<int> which_;
  int n_ = 0;
  double ds_ = 0.0;
  std::vector<double> weight_, rest_;  ///< overlaps (m x (N - 1)); rest lengths
};

}  // namespace rodlab::solvers::dynamics
