#pragma once
// Muscles and length control in the variational integrator (docs/dynamics.md "Muscles and
// length control"); private to solvers/dynamics (variational_stepper.hpp). Only scenes that have
// them pay for this: the plain Cosserat step is untouched.
//
// Embedded muscles: every node has the full inertia M_j of DynamicProblem::node_inertia (the
// muscles' Ad^T M_a Ad, (3.20)), so (3.42) is solved with a full mass matrix; the stresses have
// the muscles' stiffness and viscosity (DynamicProblem::internal_wrench) and the nodes their
// weight at the offsets. The active force F = law(q(t1), Delta, Delta*) needs the muscle's
// current length Delta, a global functional of the strains: the explicit step knows the new
// strains before the stresses, so a pre-pass (segment_update, then muscle_forces) computes them
// and Delta = sum_j o_j |u(s_j + ds/2, xi_j)| (o_j the overlap of segment j with the span;
// Delta* the same sum at xi*) before the stress pass.
//
// Length control (cable displacement, chamber volume): the actuator's force F is a multiplier,
// chosen like the Kirchhoff constraint forces (SHAKE): the step's stress pass runs with F = 0
// for these actuators, then the impulses F_e (dt / w_j) b_ej enter the momenta of the nodes
// (b_ej: per unit force, dexp^-T_{ds xi_j} c_e(xi_j) from segment j, -Ad^T_{G_(j-1)} of segment
// j - 1's, -c_e at a cable's entry node) and F is solved so that the next step's segments
// ((E^j)^-1 G^j E^(j+1), E = exp(dt eta)) have the prescribed path lengths at t1 + dt. Newton
// with a finite-difference Jacobian (one column per actuator), from the last step's forces. The
// actuators' work -F_e (the step's change of their path length) (and -F_e c_e . eta dt at an
// entry node) is added to work_in with the solved forces.
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "discrete_legendre.hpp"
#include "rodlab/lie/se3.hpp"
#include "../staggered_paths.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {

class VariationalActuators {
 public:
  /// Throws std::invalid_argument for Kirchhoff rods (not supported with muscles or length
  /// control in `variational` yet).
  VariationalActuators(const DynamicProblem& problem, int nodes, const DiscreteLegendre& legendre);

  bool muscles() const { return muscles_; }
  /// Node j's inertia per unit length and its inverse (muscles); all nodes' inertias.
  const lie::Matrix6& inertia(int j) const { return M_[j]; }
  const std::vector<lie::Matrix6>& inertias() const { return M_; }
  const lie::Matrix6& inertia_inverse(int j) const { return M_inv_[j]; }
  /// (3.42) at node j with its inertia.
  bool solve_velocity(int j, double dt, const lie::Vector6& mu, const lie::Vector6& mu_old,
                      lie::Vector6& eta) const;
  /// The muscles' weight on node j (body frame, at the offsets; zero without gravity).
  lie::Vector6 weight(int j, const lie::SO3& R) const;

  /// The step's forces at t1 from the new segment strains xi (muscles: the law at their
  /// lengths; length-controlled actuators: 0, see above).
  const DynamicProblem::Forces& forces(double t1, std::span<const lie::Vector6> xi);
  const DynamicProblem::Forces& last_forces() const { return F_; }
  /// The forces that weight the path-length changes of the step in the ledger: the mean of the
  /// last step's and this step's (call after forces()), zero for the length-controlled ones
  /// (their work is added by enforce_lengths).
  DynamicProblem::Forces work_forces() const;

  /// The per-unit-force power of the length-controlled actuators in the step: segment j (its
  /// path length change from xi_old to xi over dt) and a node load (entry point) at velocity eta.
  void add_segment_power(int j, const lie::Vector6& xi_old, const lie::Vector6& xi, double dt);
  void add_entry_power(double s_entry, const lie::Vector6& xi, const lie::Vector6& eta);

  /// Length control after the stress pass: solves the forces, adds their impulses to mu and
  /// re-solves eta (nodes 1..N-1), and returns their power in the step (W) through `power`.
  /// G and xi: this step's segments. Returns false with failure() set when the solve fails.
  bool enforce_lengths(double t1, double dt, std::span<const lie::SE3> G,
                       std::span<const lie::Vector6> xi, std::span<lie::Vector6> mu,
                       std::span<lie::Vector6> eta, double& power);
  const std::string& failure() const { return failure_; }

  /// The readings of the actuators with unknowns for the segment strains xi.
  std::vector<ActuatorReading> readings(std::span<const lie::Vector6> xi) const;

 private:
  double weight_of(int j) const { return j == n_ - 1 ? 0.5 * ds_ : ds_; }
  /// The lengths of the length-controlled actuators' paths on the next step's segments, from
  /// the velocities eta; into lengths_next_.
  void next_lengths(double dt, std::span<const lie::SE3> G, std::span<const lie::Vector6> eta);
  /// Momenta with the impulses of the forces Fl_ and their velocities (3.42).
  bool apply_forces(double dt, std::span<lie::Vector6> mu, std::span<lie::Vector6> eta);

  const DynamicProblem& P_;
  int n_;
  double ds_;
  DiscreteLegendre legendre_;
  bool muscles_ = false;
  std::vector<lie::Matrix6> M_, M_inv_;
  // Unknowns (DynamicProblem::unknown_actuators()): muscles and length-controlled actuators.
  std::vector<int> which_;
  std::vector<char> is_muscle_;
  StaggeredPaths paths_;                   ///< their path lengths and rest lengths
  std::vector<double> unknowns_;           ///< per unknown: Delta (muscle) or F (length)
  DynamicProblem::Forces F_{}, F_prev_{};  ///< this step's forces; the last step's
  bool started_ = false;                   ///< F_prev_ is set
  // Length control: the indices (into the unknowns) of the length-controlled ones, their
  // forces, unit powers, impulse directions (per actuator, per node) and the solve's work.
  std::vector<int> lengths_;
  Eigen::VectorXd Fl_, Fl_prev_, power_, residual_, lengths_next_, trial_;
  Eigen::MatrixXd J_;
  std::vector<lie::Vector6> b_, mu_free_, eta_free_, xi_next_;
  std::string failure_;
};

}  // namespace rodlab::solvers::dynamics
