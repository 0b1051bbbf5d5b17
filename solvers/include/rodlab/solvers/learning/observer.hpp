#pragma once
// The observation of a learned policy (docs/learning.md "Environment"), built from a plant's
// state alone, so that training (rod_environment.hpp) and control with a trained policy
// (`rodlab control --controller policy`) observe the rod the same way. Dimensionless, L the rod
// length, T the first bending period:
//   [0, 3)    the tip position p / L (world frame)
//   [3, 6)    the tip's mean velocity over the last control step, (p_k - p_(k-1)) / dt_c * T / L
//             (zero at an episode's start)
//   [6, 9)    the goal's position p_des / L at the end of the coming control step
//   [9, 12)   with goal_velocity (track): the goal's velocity there, v_des * T / L
//   then, with state_nodes = K > 0: the plant's tangent coordinates (plant.hpp: segment strains
//             minus xi*, node velocities) of K segments and nodes evenly spaced to the tip, each
//             divided by its characteristic size (Plant::state_scale).
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "rodlab/solvers/control/plant.hpp"

namespace rodlab::solvers::learning {

struct ObservationLayout {
  bool goal_velocity = false;  ///< entries 9-11 (track)
  int state_nodes = 0;         ///< K
};

class Observer {
 public:
  /// For `plant` (its nodes, rod and tangent layout). Throws std::invalid_argument for K < 0.
  Observer(const control::Plant& plant, int nodes, const ObservationLayout& layout);

  int size() const { return size_; }
  double period() const { return period_; }  ///< T [s]
  const ObservationLayout& layout() const { return layout_; }

  /// The observation of `plant` now; `tip_before`: the tip one control step ago (none: at
  /// rest), `goal` and `goal_velocity` at the end of the coming control step. Does not allocate.
  void observe(const control::Plant& plant, const std::optional<lie::Vector3>& tip_before,
               const lie::Vector3& goal, const lie::Vector3& goal_velocity,
               std::span<double> observation);

 private:
  ObservationLayout layout_;
  double period_ = 0.0, length_ = 0.0;
  int size_ = 0;
  std::vector<int> state_index_;  ///< tangent coordinates observed
  Eigen::VectorXd x_;
};

}  // namespace rodlab::solvers::learning
