#include "rodlab/solvers/learning/observer.hpp"

#include <algorithm>
#include <cmath>

#include "rodlab/check.hpp"
#include "rodlab/rod/characteristics.hpp"

namespace rodlab::solvers::learning {

Observer::Observer(const control::Plant& plant, int nodes, const ObservationLayout& layout)
    : layout_(layout), length_(plant.length()) {
  RODLAB_THROW_UNLESS(layout.state_nodes >= 0, "learning: state_nodes must be >= 0 (got {})",
                      layout.state_nodes);
  const auto c = rod::characteristics(plant.problem().model(), nodes, rod::TipSupport::free);
  period_ = 1.0 / c.first_bending_frequency_hz;
  // the tangent coordinates of K segments and nodes, evenly spaced to the tip (plant.hpp: the
  // strains of segments 0..N-2, then the velocities of nodes 1..N-1)
  const int strains = plant.state_size() / (nodes - 1) - 6;  // 6 (Cosserat) or 3 (Kirchhoff)
  const int K = std::min(layout.state_nodes, nodes - 1);
  for (int k = 1; k <= K; ++k) {
    const int node = static_cast<int>(std::lround(static_cast<double>(k) * (nodes - 1) / K));
    for (int i = 0; i < strains; ++i) state_index_.push_back((node - 1) * strains + i);
    for (int i = 0; i < 6; ++i) state_index_.push_back((nodes - 1) * strains + (node - 1) * 6 + i);
  }
  size_ = (layout.goal_velocity ? 12 : 9) + static_cast<int>(state_index_.size());
  x_.resize(plant.state_size());
}

void Observer::observe(const control::Plant& plant, const std::optional<lie::Vector3>& tip_before,
                       const lie::Vector3& goal, const lie::Vector3& goal_velocity,
                       std::span<double> o) {
  RODLAB_THROW_UNLESS(static_cast<int>(o.size()) == size_,
                      "learning: expected an observation of {} values, got {}", size_, o.size());
  const double L = length_;
  const lie::Vector3 p = plant.tip();
  const lie::Vector3 v =
      tip_before ? lie::Vector3((p - *tip_before) / plant.dt_control()) : lie::Vector3::Zero();
  std::size_t i = 0;
  for (int k = 0; k < 3; ++k) o[i++] = p[k] / L;
  for (int k = 0; k < 3; ++k) o[i++] = v[k] * period_ / L;
  for (int k = 0; k < 3; ++k) o[i++] = goal[k] / L;
  if (layout_.goal_velocity)
    for (int k = 0; k < 3; ++k) o[i++] = goal_velocity[k] * period_ / L;
  if (state_index_.empty()) return;
  plant.read_state(std::span<double>(x_.data(), x_.size()));
  for (const int j : state_index_) o[i++] = x_[j] / plant.state_scale()[j];
}

}  // namespace rodlab::solvers::learning
