#pragma once
// Inverse statics, quasi-static control (thesis 4.1, (4.5)-(4.11); docs/control.md): the actuator
// inputs u that put the rod's tip at a target, within every input's limits.
//
// FORMULATION. A bounded nonlinear least-squares problem in u alone, with the bounds
// lo <= u <= hi from each actuator's `limits`:
//     min_u  |p(u) - p*|^2 / L^2  +  w sum_k (u_k / s_k)^2,      s_k = max(|lo_k|, |hi_k|),
// where p(u) is the tip of the statics (4.5)-(4.7) with inputs u: each residual evaluation is a
// `chebyshev` solve, followed from the last equilibrium (statics/chebyshev_tracker.hpp), so the
// base wrench, the thesis' second unknown xi_0, is eliminated by the statics' own Newton. The
// Jacobian dp/du is exact: the implicit function theorem on the converged collocation system,
// the exact form of (4.10) J = E_q - E_xi B_xi^-1 B_q (the thesis takes finite differences).
//
// SOLVER (method gauss_newton, the default). Bounded Gauss-Newton with Levenberg-Marquardt
// damping: each update evaluates J once and takes the exact minimiser of the damped linear model
// within the box (common/box_qp.hpp, projected Newton: inputs at a limit leave the step, the
// others get the reduced Gauss-Newton step), accepted on the actual/predicted reduction ratio
// (Nielsen's damping update; undamped while the model predicts well). It stops once the tip is
// within `tolerance` and the last update moved no input by more than step_tolerance s_k, or
// when no input can move (the KKT point of an unreachable target). Method ceres runs the same
// problem through Ceres 2.1 (trust region, Levenberg-Marquardt, dense QR, bounds): its bounds
// are handled by projecting the unconstrained step onto the box plus a projected line search,
// which stalls where the step points out of a corner (docs/control.md: measured), so it is kept
// for comparison only.
//
// Against (4.11)'s update q <- q - 0.2 J^-1 e: the damping replaces the fixed gain 0.2, the
// limits are kept (the thesis' tensions can leave [0, 0.5] N), and with more inputs than task
// coordinates (4 cables, 3 coordinates) J has no inverse: the step is the least-squares one of
// the regularised, stacked residual.
//
// MINIMUM INPUT NORM. The small weight w (default 1e-8) selects, among the inputs that reach the
// target, the one of least scaled norm: the minimiser of the regularised problem tends to it as
// w -> 0, and its tip misses the target by O(w) (about 16 w m for the cable-driven robot: 0.2 um
// at 1e-8). Since the regulariser is a linear residual, Gauss-Newton's model holds it exactly
// and one undamped step lands on the least-norm point of the linearised solution set.
//
// A target outside the workspace gets the bounded least-squares minimum: the closest tip the
// limits allow, reached = false and a reason with the remaining error.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "rodlab/lie/se3.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::solvers::control {

using lie::Vector3;

enum class InverseStaticsMethod { gauss_newton, ceres };

struct InverseStaticsOptions {
  InverseStaticsMethod method = InverseStaticsMethod::gauss_newton;
  /// The forward statics: scheme (only `chebyshev`, whose Newton system gives the exact
  /// sensitivities), nodes, tol, max_iterations, time (the scene's schedules are evaluated
  /// there); max_wall_time is not used.
  statics::StaticSolveOptions statics{"chebyshev", 24, 1e-10, 50};
  double tolerance = 1e-3;        ///< reach tolerance [m] on |p_tip - target|
  double regularization = 1e-8;   ///< w above (minimum input norm); 0: none
  int max_updates = 50;           ///< Jacobian evaluations
  /// Stop once the tip is within `tolerance` and the last update moved no input by more than
  /// this fraction of its scale s_k (the minimum-norm solution has settled too).
  double step_tolerance = 1e-4;
};

struct InverseStaticsResult {
  bool converged = false;  ///< the least-squares problem was solved (KKT, or the stop rule)
  bool reached = false;    ///< |tip - target| <= tolerance
  std::string reason;      ///< why not converged or not reached (empty when both hold)
  Eigen::VectorXd u;       ///< inputs, one per actuator (scene order), within their limits
  Vector3 tip = Vector3::Zero();  ///< tip reached with u (world frame)
  double error = 0.0;      ///< |tip - target| [m]
  int updates = 0;         ///< outer iterations: Jacobian (sensitivity) evaluations
  int statics_solves = 0;  ///< forward statics solves (residual evaluations)
  int newton_iterations = 0;  ///< Newton iterations of those solves
  double wall_time_s = 0.0;
};

/// A reusable inverse-statics solver for one scene: keeps the forward statics (its layout, its
/// last equilibrium and factorisation) and the last inputs across targets, as a controller does
/// once per control update while it tracks a moving target.
class InverseStatics {
 public:
  /// Throws std::invalid_argument naming the actuator when one has no `limits`, when the scene
  /// has no actuators or a clamped tip, or for a scheme other than `chebyshev`.
  InverseStatics(const scene::Scene& scene, const InverseStaticsOptions& options = {});
  ~InverseStatics();
  InverseStatics(InverseStatics&&) noexcept;
  InverseStatics& operator=(InverseStatics&&) noexcept;

  int inputs() const;
  /// The limits [lo, hi] of each input (scene order).
  const std::vector<std::pair<double, double>>& limits() const;
  /// Solves for a target (world frame), warm-started from the last solution's inputs (the first
  /// time: zero clamped to the limits).
  InverseStaticsResult solve(const Vector3& target_world);
  /// The same from the inputs u0 (clamped to the limits); size inputs().
  InverseStaticsResult solve(const Vector3& target_world, const Eigen::VectorXd& u0);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One solve with a fresh solver: from u0 if given (non-empty), else zero clamped to the limits.
InverseStaticsResult solve_inverse_statics(const scene::Scene& scene, const Vector3& target_world,
                                           const InverseStaticsOptions& options = {},
                                           const Eigen::VectorXd& u0 = {});

}  // namespace rodlab::solvers::control
