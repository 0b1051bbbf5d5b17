#pragma once
// The linearisation of one control step x+ = f(x, u) (4.13) of a plant (plant.hpp) in its
// tangent coordinates, dx+ = A dx + B du, by finite differences as the thesis (4.33)-(4.34) but
// central by default and with a step per coordinate from the plant's state scale (the thesis
// perturbs every coordinate by eps = 1e-5 forward). docs/control.md "Linearisation".
//
// directional() is the building block: one directional derivative (A dx + B du and the tip's
// d p+) from two control steps (one, forward), so that a controller asks only for the products
// it needs (the task-space Jacobian of a horizon, NLSQ-MPC) instead of the full A (n steps).
// An input on its limit is differenced on its feasible side.
#include <Eigen/Core>

#include "rodlab/solvers/control/plant.hpp"

namespace rodlab::solvers::control {

/// How jacobians() obtains A, B, C, D.
enum class JacobianMethod {
  /// The scheme's own linearised step (Plant::advance_linearised: the implicit function theorem
  /// on its converged equations), where the scheme has one; else finite_difference.
  implicit_function,
  finite_difference,  ///< every column from differenced control steps (4.33)-(4.34)
};

struct LinearisationOptions {
  /// The step along a direction whose scaled size (dx / state_scale, du / input range) is 1.
  double relative_step = 1e-5;
  bool central = true;  ///< central differences (else forward, as (4.33)-(4.34))
  JacobianMethod method = JacobianMethod::implicit_function;  ///< jacobians()' method
};

/// A directional derivative of one control step.
struct StepDerivative {
  Eigen::VectorXd dx;  ///< d x+ (tangent coordinates)
  Vector3 dtip;        ///< d p_tip at x+ [m]
};

class Linearisation {
 public:
  /// Buffers and snapshots for `plant` (allocates once).
  explicit Linearisation(const Plant& plant, LinearisationOptions options = {});

  /// A dx + B du at the plant's current state and input; the plant is back in that state on
  /// return. A step that fails in a perturbed run is reported (ok false, reason).
  dynamics::StepStatus directional(Plant& plant, const Eigen::Ref<const Eigen::VectorXd>& dx,
                                   const Eigen::Ref<const Eigen::VectorXd>& du, StepDerivative& out);
  /// The same where a controller's rollout has taken the unperturbed step: its x+, tip and the
  /// plant after it. With forward differences (options.central false) one control step instead
  /// of two, and the perturbed step's solves start from the unperturbed solution
  /// (Plant::warm_start_from): one or two shooting integrations instead of about ten.
  dynamics::StepStatus directional(Plant& plant, const Eigen::Ref<const Eigen::VectorXd>& dx,
                                   const Eigen::Ref<const Eigen::VectorXd>& du, StepDerivative& out,
                                   const Eigen::VectorXd& x_next, const Vector3& tip_next,
                                   const PlantSnapshot& after);

  /// A (n x n) and B (n x m) and the tip Jacobian C = d p_tip(x+) / d x and
  /// D = d p_tip(x+) / d u (3 x n, 3 x m): by options.method; finite differences column by
  /// column.
  /// With `tip_next` also the tip after the unperturbed step (free with the implicit function
  /// method, one more step with differences).
  dynamics::StepStatus jacobians(Plant& plant, Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                 Eigen::MatrixXd& C, Eigen::MatrixXd& D,
                                 Vector3* tip_next = nullptr);

 private:
  /// x+ and the tip after one control step from the saved state moved by h (dx, du).
  dynamics::StepStatus difference(Plant& plant, const Eigen::Ref<const Eigen::VectorXd>& dx,
                                  const Eigen::Ref<const Eigen::VectorXd>& du, StepDerivative& out,
                                  const Eigen::VectorXd* x_next, const Vector3* tip_next);
  dynamics::StepStatus perturbed(Plant& plant, double h, const Eigen::Ref<const Eigen::VectorXd>& dx,
                                 const Eigen::Ref<const Eigen::VectorXd>& du, Eigen::VectorXd& x,
                                 Vector3& tip);

  LinearisationOptions options_;
  PlantSnapshot start_;
  const PlantSnapshot* after_ = nullptr;  ///< the unperturbed step's end (directional, rollout)
  Eigen::VectorXd x_plus_, x_minus_, step_, u_, e_x_, e_u_;
  StepDerivative column_;
};

}  // namespace rodlab::solvers::control
