#pragma once
// What the time loop (solve_dynamic.hpp) needs from a dynamics scheme. A stepper owns its state
// (allocated once), advances it by one step without allocating, and reports the quantities of
// the result file through the shared formulas of energy.hpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/dynamics/energy.hpp"

namespace rodlab::solvers::dynamics {

/// max |det R - 1| over node poses: the structure diagnostic every stepper reports.
inline double max_det_deviation(std::span<const SE3> g) {
  double worst = 0.0;
  for (const SE3& x : g) worst = std::max(worst, std::abs(x.rotation_matrix().determinant() - 1.0));
  return worst;
}

/// The centreline of a staggered grid (`variational`, `ida`, collocation): node poses g (N)
/// and segment strains xi (N - 1); a node's strain is the mean of its adjacent segments' (one
/// segment at the ends).
inline std::vector<result::CenterlineSample> staggered_centerline(std::span<const SE3> g,
                                                                 std::span<const Vector6> xi,
                                                                 double ds) {
  const std::size_t n = g.size();
  std::vector<result::CenterlineSample> out(n);
  for (std::size_t j = 0; j < n; ++j) {
    const Vector6 x = j == 0 ? xi[0] : j == n - 1 ? xi[n - 2] : Vector6(0.5 * (xi[j - 1] + xi[j]));
    out[j] = {static_cast<double>(j) * ds, g[j], x};
  }
  return out;
}

/// A state at rest: node poses and node strains, base first.
struct RestState {
  std::vector<SE3> g;
  std::vector<Vector6> xi;
  /// The state is a static equilibrium (`initial: static`, sampled from a statics solution on
  /// another grid): a scheme may re-solve it on its own grid.
  bool equilibrium = false;
};

/// An actuator whose force is not given (a muscle, or under length control): its path length on
/// the scheme's grid in the current state and its axial force in the last step.
struct ActuatorReading {
  int actuator = 0;     ///< index in the scene's actuator list
  double length = 0.0;  ///< [m]
  double force = 0.0;   ///< [N] (tension positive; a chamber's pressure is -force / A_c)
};

struct StepStatus {
  bool ok = true;
  std::string reason;  ///< why the step failed (no convergence, instability)
  int iterations = 0;  ///< nonlinear iterations or shooting integrations spent on the step
  /// A failed step that left the state inside the step (ida: where IDA stopped): that time;
  /// NaN when the state is at the step's end or unchanged.
  double reached = std::numeric_limits<double>::quiet_NaN();
  static StepStatus failed(std::string why) { return {false, std::move(why), 0}; }
};

class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Advances the state from t to t + dt (inputs evaluated inside [t, t + dt] as the scheme
  /// prescribes) and adds the step's dissipated energy and input work to the ledger.
  virtual StepStatus step(double t, double dt) = 0;
  /// Energies of the current state (kinetic, strain, gravity) and the running dissipation and
  /// input work.
  virtual Energy energy() const = 0;
  virtual lie::Vector3 tip_position() const = 0;
  /// max |det R - 1| over the nodes.
  virtual double max_det_deviation() const = 0;
  /// Node poses and strains, base first.
  virtual std::vector<result::CenterlineSample> centerline() const = 0;
  /// Node velocities eta = [omega; v] in the body frame, base first (centerline()'s nodes).
  virtual std::vector<Vector6> velocities() const = 0;
  /// The actuators with unknowns (DynamicProblem::unknown_actuators()), in that order.
  virtual std::vector<ActuatorReading> actuator_readings() const { return {}; }

  // --- control (solvers/control/plant.hpp, docs/control.md "The state") -------------------
  // A controller rolls futures out from a saved state and linearises a step in the state's
  // tangent coordinates: the segment strains xi_j - xi* (j = 0..N-2; Kirchhoff rods: the
  // angular part only, nu = nu* is held) followed by the node velocities eta_j (j = 1..N-1; the
  // base is fixed). Poses follow from the strains, g_(j+1) = g_j exp(ds xi_j), so these are
  // global coordinates of the configuration wherever |ds xi_j| < pi. A scheme that does not
  // support control keeps the defaults, which throw std::invalid_argument.

  /// A copy of this stepper with its state (allocates: a controller makes its snapshots once).
  virtual std::unique_ptr<Stepper> clone() const { throw unsupported("clone"); }
  /// Makes this stepper's state that of `other`, a clone of it (same scheme, problem and grid),
  /// without allocating: the steps that follow repeat those of `other` bit for bit.
  virtual void assign_state(const Stepper& /*other*/) { throw unsupported("assign_state"); }
  /// Starts the next step's nonlinear solve from the solution of `after`, a clone that has just
  /// taken that step from a nearby state (finite differences of a step: a perturbed step then
  /// converges in one or two iterations). Explicit schemes ignore it.
  virtual void warm_start_from(const Stepper& /*after*/) {}
  /// The number of tangent coordinates.
  virtual int tangent_size() const { throw unsupported("tangent_size"); }
  /// The current state's tangent coordinates (x.size() == tangent_size()).
  virtual void read_tangent(std::span<double> /*x*/) const { throw unsupported("read_tangent"); }
  /// Moves the state by dx in tangent coordinates (the poses and every derived quantity follow).
  virtual void add_tangent(std::span<const double> /*dx*/) { throw unsupported("add_tangent"); }

  /// Whether step_linearised() is available here (else a controller differences whole steps).
  virtual bool has_step_linearisation() const { return false; }
  /// Takes the step of step(t, dt) and linearises it about the state it started from, in tangent
  /// coordinates: A = dx+/dx (n x n) and B = dx+/du (n x m), u the actuators' drive inputs in
  /// scene order (the held inputs: tension, pressure; DynamicProblem::hold_input). A failed step
  /// leaves A and B unset. The implicit schemes differentiate their own converged equations
  /// (the implicit function theorem, docs/control.md "Linearisation").
  virtual StepStatus step_linearised(double /*t*/, double /*dt*/, Eigen::MatrixXd& /*A*/,
                                     Eigen::MatrixXd& /*B*/) {
    throw unsupported("step_linearised");
  }
  /// The tip position's derivative with respect to the current state's tangent coordinates
  /// (3 x n; the velocities' columns are zero).
  virtual void tip_jacobian(Eigen::MatrixXd& /*T*/) const { throw unsupported("tip_jacobian"); }

 protected:
  static std::invalid_argument unsupported(const char* what) {
    return std::invalid_argument(std::string("this dynamics scheme does not support control (") +
                                 what + "); use variational, implicit-midpoint, bdf-alpha or "
                                        "implicit-midpoint-collocation");
  }
};

}  // namespace rodlab::solvers::dynamics
