#pragma once
// Artificial-muscle laws (thesis 2.4.4): the contraction force of a muscle from its input q and
// its global deformation, the current length Delta (2.66) against the rest length Delta*.
// Laws are pluggable: implement MuscleLaw and register it in make_muscle_law.
#include <memory>
#include <string>
#include <string_view>

namespace rodlab::loads {

class MuscleLaw {
 public:
  virtual ~MuscleLaw() = default;
  /// Contraction force [N] (acts like a cable tension along the muscle).
  virtual double force(double q, double length, double rest_length) const = 0;
  virtual std::string_view name() const = 0;
};

/// force = gain q - stiffness (Delta - Delta*) / Delta*: an input-proportional contraction
/// with a linear spring on the strain of the whole muscle.
class LinearMuscleLaw final : public MuscleLaw {
 public:
  LinearMuscleLaw(double gain, double stiffness) : gain_(gain), stiffness_(stiffness) {}
  double force(double q, double length, double rest_length) const override {
    return gain_ * q - stiffness_ * (length - rest_length) / rest_length;
  }
  std::string_view name() const override { return "linear"; }

 private:
  double gain_, stiffness_;
};

/// The law named `type` ("linear"); throws std::invalid_argument for an unknown one.
std::shared_ptr<const MuscleLaw> make_muscle_law(std::string_view type, double gain, double stiffness);

}  // namespace rodlab::loads
