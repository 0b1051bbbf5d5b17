#pragma once
// Gravity as a distributed wrench in the body frame (2.36), with buoyancy: the weight per unit
// length is (rho - rho_fluid) A g_r, and in the body frame W_bar = [0; R^T (rho_eff A g_r)].
#include "rodlab/lie/se3.hpp"
#include "rodlab/rod/rod_model.hpp"

namespace rodlab::loads {

using lie::SO3;
using lie::Vector3;
using lie::Vector6;

class Gravity {
 public:
  Gravity(const rod::RodModel& model, const Vector3& g_world, double fluid_density = 0.0)
      : weight_W_((model.material().rho - fluid_density) * model.properties().A * g_world) {}

  /// Weight per unit length in the world frame [N/m].
  const Vector3& weight_per_length() const { return weight_W_; }

  /// (2.36): distributed wrench on the section with rotation R, body frame.
  Vector6 body_wrench(const SO3& R, double scale = 1.0) const {
    return lie::se3::join(Vector3::Zero(), R.inverse() * (scale * weight_W_));
  }

 private:
  Vector3 weight_W_;
};

}  // namespace rodlab::loads
