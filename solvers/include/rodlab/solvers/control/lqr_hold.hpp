#pragma once
// Reach and hold by infinite-horizon LQR (thesis 4.2.2; docs/control.md "LQR"): about the
// equilibrium (x*, u*) of the plant's own scheme under the inputs u* that the inverse statics
// give for the target, the control step is linearised (linearisation.hpp), the discrete
// algebraic Riccati equation solved (lqr.hpp) for
//
//   cost = sum_k  |C dx_k + D du_k|^2 / L^2  +  eps |dx_k / scale|^2  +  w |du_k / range|^2,
//
// (the tip's deviation after each step, a small state weight eps that makes every mode
// detectable, the input effort w), and the plant is driven by u = clamp(u* - K (x - x*)).
// Tracking moves the reference along the trajectory's quasi-static equilibria: u_ref from the
// inverse statics of the coming target, x_ref = x* + S (u_ref - u*) the linearised plant's
// steady state under it, S = (I - A)^-1 B, with the gain of the first target.
#include <string>

#include <Eigen/Core>

#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/control/plant.hpp"

namespace rodlab::solvers::control {

struct LqrWeights {
  double state = 1e-6;  ///< eps on the scaled state deviation
  double input = 1e-3;  ///< w on the scaled input deviation
};

struct HoldGain {
  bool ok = false;
  std::string reason;
  Eigen::VectorXd x_star, u_star;  ///< the equilibrium (tangent coordinates) and its inputs
  Vector3 tip_star = Vector3::Zero();
  Eigen::MatrixXd K;  ///< du = -K dx
  Eigen::MatrixXd steady;  ///< S = dx*/du* = (I - A)^-1 B, the equilibrium's input sensitivity
  double spectral_radius = 0.0;  ///< of the linear closed loop A - B K (< 1: stable)

  /// u* - K (x - x*) clamped to the plant's limits.
  Eigen::VectorXd control(const Plant& plant) const { return control(plant, u_star); }
  /// u_ref - K (x - x_ref), x_ref = x* + S (u_ref - u*), clamped to the limits.
  Eigen::VectorXd control(const Plant& plant, const Eigen::VectorXd& u_ref) const;
};

/// The gain about the equilibrium of `scene` under u_star on the plant options' scheme (the
/// plant's own statics: dynamics.initial static). Throws what the plant throws.
HoldGain hold_gain(const scene::Scene& scene, const PlantOptions& options,
                   const Eigen::VectorXd& u_star, const LqrWeights& weights = {});

}  // namespace rodlab::solvers::control
