#pragma once
// The plant of a controller (thesis 4.2, (4.13) x_(i+1) = f(x_i, u_i); docs/control.md): a
// dynamics scheme stepping one scene under inputs u that a controller sets once per control
// step of length dt_c and holds over it (zero-order hold). u holds the drive input of every
// actuator in scene order (cable tension or displacement, fluidic pressure or volume, muscle
// input q), each inside the actuator's `limits`. One control step is one step of an implicit
// scheme (dt = dt_c, or several equal steps when solver dt is set smaller), or as many equal
// `variational` steps below its stability limit as dt_c needs.
//
// A controller rolls futures out from the current state: snapshot() makes a copy once
// (allocating), save()/restore() copy a state into and out of it without allocating, so a
// rollout from a restored state repeats the original bit for bit. The state's tangent
// coordinates (stepper.hpp: segment strains minus xi*, node velocities) give LQR and iLQR the
// vector space they work in.
#include <memory>
#include <span>

#include <Eigen/Core>

#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::control {

using lie::Vector3;

struct PlantOptions {
  PlantOptions() { solver.max_iterations = kShotsPerStep; }
  /// Single shooting needs 80-100 integrations for the step after a 0.4 N jump of a cable's
  /// tension at dt = 0.01 s (N = 10-40, the control robot; 50, the dynamics default, fails):
  /// a controller's inputs jump at every control step.
  static constexpr int kShotsPerStep = 200;
  /// The scheme and its options (scheme, nodes, tol, grid, alpha, initial); solver.dt is the
  /// scheme's own step: 0 takes dt_c for the implicit schemes and the stable step (dt: auto)
  /// for `variational`.
  dynamics::DynamicSolveOptions solver;
  double dt_control = 0.05;  ///< [s], > 0
};

/// The scheme step a plant asks for before it fits a whole number of them into dt_c:
/// solver.dt when set, else the stable step (`dt: auto`) for `variational`, else dt_c (one
/// implicit step per control step). Throws std::invalid_argument for an unknown scheme.
double requested_step(const dynamics::DynamicProblem& problem, const PlantOptions& options);

/// A saved plant state (Plant::snapshot); opaque to controllers.
struct PlantSnapshot {
  std::unique_ptr<dynamics::Stepper> stepper;
  double t = 0.0;
  Eigen::VectorXd u;
};

class Plant {
 public:
  /// Throws std::invalid_argument for bad options, a scheme without control support, a tip that
  /// is not free, an actuator without `limits`, a scene without actuators, or a step that the
  /// scheme refuses (single shooting's lower step bound, step_bound.hpp).
  Plant(const scene::Scene& scene, const PlantOptions& options);

  int input_count() const { return static_cast<int>(lower_.size()); }
  const Eigen::VectorXd& lower() const { return lower_; }
  const Eigen::VectorXd& upper() const { return upper_; }
  double dt_control() const { return dt_control_; }
  /// The scheme's step and the number of them in a control step.
  double substep() const { return dt_; }
  int substeps() const { return substeps_; }
  double time() const { return t_; }
  double length() const { return problem_->length(); }
  const dynamics::DynamicProblem& problem() const { return *problem_; }

  /// The input of the coming control steps; throws std::invalid_argument unless each u_k lies
  /// in [lower_k, upper_k] (controllers respect the bounds: a violation is a bug, not a clip).
  void set_input(const Eigen::Ref<const Eigen::VectorXd>& u);
  const Eigen::VectorXd& input() const { return u_; }
  /// Advances one control step under the held input. A failed step (no convergence,
  /// instability) is repeated from its start with finer steps (kMaxStepSplit); when that fails
  /// too it is reported in the status and leaves the state where the scheme stopped. Throws
  /// WallTimeExceeded (common/deadline.hpp) once the thread's deadline has passed.
  dynamics::StepStatus advance();
  /// A failed control step is repeated from its start with 2, 4, ... up to this many times as
  /// many scheme steps (advance(); the same held input, a finer step).
  static constexpr int kMaxStepSplit = 8;
  /// Control steps that needed a finer step (advance()) since construction.
  int split_steps() const { return split_steps_; }

  /// Whether advance_linearised() is available (the scheme differentiates its own step).
  bool has_step_linearisation() const { return stepper_->has_step_linearisation(); }
  /// advance() with the step's linearisation in tangent coordinates (Stepper::step_linearised,
  /// chained over the substeps): A = dx+/dx, B = dx+/du, and the tip's C = dp(x+)/dx,
  /// D = dp(x+)/du. Throws std::invalid_argument where has_step_linearisation() is false.
  dynamics::StepStatus advance_linearised(Eigen::MatrixXd& A, Eigen::MatrixXd& B,
                                          Eigen::MatrixXd& C, Eigen::MatrixXd& D);

  Vector3 tip() const { return stepper_->tip_position(); }
  const dynamics::Stepper& stepper() const { return *stepper_; }

  /// A copy of the current state (allocates).
  PlantSnapshot snapshot() const;
  /// Copies the current state into `s`, a snapshot of this plant, without allocating.
  void save(PlantSnapshot& s) const;
  /// Makes `s` the current state (time and input included), without allocating.
  void restore(const PlantSnapshot& s);

  /// Makes this plant's state that of `other`, a plant of another scheme on the same scene and
  /// grid, through their tangent coordinates (time and input included): a controller's model
  /// taking over the plant's state before it predicts (docs/control.md "Model and plant"). This
  /// plant's scheme must keep its whole state in them (not bdf-alpha's history). Throws
  /// std::invalid_argument when the tangent coordinates differ in size. Does not allocate.
  void set_state_of(const Plant& other);

  /// Starts the next control step's solves from those of `after`, a snapshot taken after the
  /// same step from a nearby state (Stepper::warm_start_from; finite differences of a step).
  void warm_start_from(const PlantSnapshot& after) { stepper_->warm_start_from(*after.stepper); }

  /// Tangent coordinates of the state (stepper.hpp).
  int state_size() const { return stepper_->tangent_size(); }
  void read_state(std::span<double> x) const { stepper_->read_tangent(x); }
  void add_state(std::span<const double> dx) { stepper_->add_tangent(dx); }
  /// A characteristic size of each tangent coordinate (finite-difference steps, weights):
  /// 1/L for bending and torsion strains, 1e-2 for shear and axial strains, 1/T for angular and
  /// L/T for linear velocities, T the period of the first bending mode.
  const Eigen::VectorXd& state_scale() const { return state_scale_; }

 private:
  /// Runs substep(k) for k = 0..substeps-1 (each returning its StepStatus), advancing the time;
  /// stops at the first failure.
  template <class Substep>
  dynamics::StepStatus each_substep(Substep substep);

  std::unique_ptr<dynamics::DynamicProblem> problem_;  // the steppers refer to it: fixed address
  std::unique_ptr<dynamics::Stepper> stepper_;
  Eigen::VectorXd lower_, upper_, u_, state_scale_;
  Eigen::MatrixXd sub_A_, sub_B_, tip_J_;  ///< advance_linearised()'s workspace
  Eigen::VectorXd x_other_, x_own_;         ///< set_state_of()'s workspace
  double dt_control_ = 0.0, dt_ = 0.0, t_ = 0.0;
  int substeps_ = 1;
  PlantSnapshot before_step_;  ///< advance()'s start, for a repeat with a finer step
  int split_steps_ = 0;
};

}  // namespace rodlab::solvers::control
