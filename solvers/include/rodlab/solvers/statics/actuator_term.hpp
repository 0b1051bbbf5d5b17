#pragma once
// One actuator of a statics problem: a tendon-like path with its axial force, and what is
// prescribed about it (docs/statics.md):
//   cable, tension given          F = T
//   cable, displacement given     F unknown; its path length = rest length - displacement (2.47)
//   fluidic, pressure given       F = -P A_c
//   fluidic, volume given         P unknown; A_c * path length = V (the chamber wall is rigid in
//                                 the section, so only its length changes; (2.53) with the stretch)
//   muscle                        F = law(q, Delta, Delta*) with Delta unknown and the
//                                 extra condition Delta = path length (2.66)-(2.67), plus the
//                                 embedded rod's own stiffness K_a at the offset (2.64)
#include <memory>
#include <optional>

#include "rodlab/loads/muscle_law.hpp"
#include "rodlab/loads/tendon.hpp"

namespace rodlab::solvers::statics {

enum class ActuatorKind { cable, fluidic, muscle };

struct ActuatorTerm {
  ActuatorTerm(ActuatorKind kind_, loads::TendonPath path_) : kind(kind_), path(std::move(path_)) {}

  ActuatorKind kind;
  loads::TendonPath path;
  double rest_length = 0.0;  ///< path length in the reference configuration

  // What is prescribed (at load factor 1): exactly one of these drives the actuator.
  double input = 0.0;                   ///< tension T, pressure P, or muscle input q
  std::optional<double> target_length;  ///< displacement or volume control: the path length

  double chamber_area = 0.0;  ///< fluidic: A_c = pi r_c^2
  std::shared_ptr<const loads::MuscleLaw> law;  ///< muscle
  lie::Vector6 embedded_stiffness = lie::Vector6::Zero();  ///< muscle: diag K_a about its own axis

  /// An extra unknown of the BVP: the force of a length-controlled actuator, or a muscle's Delta.
  bool has_unknown() const { return target_length.has_value() || kind == ActuatorKind::muscle; }
  /// A cable is pulled from outside where it enters the rod; chambers and muscles are anchored
  /// at both ends (their end forces are internal to rod + actuator).
  bool enters_from_outside() const { return kind == ActuatorKind::cable; }
};

}  // namespace rodlab::solvers::statics
