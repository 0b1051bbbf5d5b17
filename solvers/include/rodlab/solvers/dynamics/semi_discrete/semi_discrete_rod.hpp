#pragma once
// The semi-discrete rod shared by `ida` (ida_reference.hpp) and `implicit-midpoint-collocation`
// (implicit_midpoint_collocation.hpp): the method-of-lines ODE y' = f(t, y) on the staggered grid
// of `variational` (variational.hpp), so at equal N these schemes differ only in time.
//
// Grid: nodes j = 0..N-1 at s_j = j ds, ds = L / (N - 1); node 0 is the fixed base (g_0 = base,
// eta_0 = 0), and a clamped tip's node N - 1 is prescribed the same way (g = the clamp's pose,
// eta = 0; not an unknown: the last segment still carries its stress, whose reaction the clamp
// takes; docs/dynamics.md "Clamped tips"). State y, 13 unknowns per unknown node (j >= 1, block
// j - 1): the position p_j (world), a
// quaternion q_j = [w x y z] (normalised when R_j is formed; its ODE is linear and
// skew-symmetric in q, so |q| is a quadratic invariant) and the body velocity
// eta_j = [psi; kappa]; then two ledger unknowns, D (dissipated) and W (work_in).
// On segment j (nodes j, j + 1):
//   G = g_j^-1 g_(j+1),  xi_j = log(G) / ds                                   (3.38), t-continuous
//   xi_dot_j = dexp^-1_{-ds xi_j} (eta_(j+1) - Ad_{G^-1} eta_j) / ds   (exact d/dt of xi_j)
//   sigma_j = K (xi_j - xi*) + V xi_dot_j + sum_k F_k c_k(xi_j)         (3.10) at the midpoint
//   lambda_j = dexp^-T_{ds xi_j} sigma_j   (node j's frame; Ad_G^T lambda_j in node j + 1's) (3.40)
// and at the nodes, with trapezoid weights w_j = ds (w_(N-1) = ds / 2):
//   F_j = lambda_j - Ad_{G_(j-1)}^T lambda_(j-1)   (lambda_(N-1) := W_tip at the tip)    (3.41)
//   p_dot = R kappa,  q_dot = q (x) [0; psi] / 2,
//   M eta_dot = ad_eta^T M eta + F_j / w_j + W_bar(R_j, eta_j, t)       (thesis (3.8))
// plus the entry load of a cable pulled from outside at the node nearest its entry point.
// The ledger rows: D' = sum_j ds xi_dot_j^T V xi_dot_j - sum_j w_j drag_j . eta_j (viscous and
// drag power), W' = tip, distributed, actuator and cable-entry power. f does not depend on D, W.
// The semi-discrete balance T + U + P + D - W = const is exact (energy.hpp formulas).
//
// df/dy is block tridiagonal in the nodes (13 x 13 blocks) plus the two dense ledger rows. It is
// formed analytically (semi_discrete_jacobian.cpp) where the derivation covers the scene
// (analytic_jacobian()), else by finite differences with three node colours (j mod 3): every
// node row sees at most one perturbed node, and the ledger powers are sums of per-segment and
// per-node terms, of which a perturbed node k moves segments k - 1, k and node k only.
//
// Characteristic scales per component (scale(), the finite-difference increments' floor):
// position L, quaternion 1, angular velocity omega_1 [rad/s], linear velocity L omega_1 [m/s],
// D and W E_bend [J], with omega_1 = 2 pi f_1 the first (Euler-Bernoulli, free tip) bending
// frequency and E_bend = 1/2 EI (pi / 2L)^2 L the strain energy of a quarter-circle bend (the
// characteristic velocity and energy of the rod's gross motion). tolerance_scale() is the same
// with positions absolute (1 m): ida's absolute tolerances are atol * tolerance_scale(), and the
// collocation scheme scales its residual and unknowns by it.
//
// Kirchhoff rods (nu = nu*) only with `constrained` (the collocation scheme; `ida` through the
// stabilised index-2 form below: the constraint makes the plain system an index-3 DAE). Segment k then carries an unknown constraint
// force f_k (3 per segment, world-free: the force part of the segment's stress) that the caller
// supplies: sigma_k = [m-part of (3.10) at nu = nu*, nu_dot = 0; 0] + [0; f_k] (the rod's own
// force part K_nu (nu - nu*) + V_nu nu_dot is dropped, actuators act as usual), so node k gets
// + B_k f_k and node k + 1 gets - Ad^T_{G_k} B_k f_k, B_k = dexp^-T_{ds xi_k} [0; I]. The
// constraint c_k(y) = nu(log(g_k^-1 g_(k+1))) / ds - nu* (3 per segment) is evaluated by
// constraint(); the ledger uses the Kirchhoff strain rate (nu_dot = 0), the constraint forces
// do no work on the constraint manifold. rest_state() puts the initial poses on the constraint
// (each segment keeps its rotation and gets nu = nu*).
//
// Actuators whose force is not given (DynamicProblem::unknown_actuators(); docs/dynamics.md
// "Muscles and length control") add one unknown x_e each, which the caller carries next to y:
// a muscle's length Delta [m] (its force is the law's, F = law(q(t), Delta, Delta*)), or a
// length-controlled actuator's force F [N] (cable displacement, chamber volume; only with
// `constrained`: the prescribed length makes the plain system an index-3 DAE; `ida` uses the
// stabilised index-2 form below). Their
// rows (actuator_rows()):
//   muscle   (x_e - L_e(y_f)) / L      algebraic, at the state where f is evaluated
//   length   (L_e(y_c) - L_target(t_c)) / L     at the constraint state (collocation: the end
//                                                of the step, the analogue of SHAKE)
// with the grid's path length L_e(y) = sum_j o_j |u_e(s_j + ds/2, xi_j)| (o_j the overlap of
// segment j with the span; the rest length Delta* is the same sum at xi*). Muscles also bring
// their embedded rod: stiffness and viscosity in the stresses (DynamicProblem::embedded_wrench),
// the full node inertia M_j of DynamicProblem::node_inertia (eta_dot = M_j^-1 (...): linear and
// angular accelerations couple where a muscle sits off the centreline, (3.20)) and their weight
// at the offset. `ida` carries the muscle lengths as algebraic unknowns after D and W (index 1;
// consistent initial values are the lengths of the initial poses).
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/energy.hpp"

namespace rodlab::solvers::dynamics {

class SemiDiscreteRod {
 public:
  using Vector = Eigen::VectorXd;
  using ConstRef = Eigen::Ref<const Vector>;
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor>;

  /// Unknowns per node: p (3), q = [w x y z] (4), eta = [psi; kappa] (6).
  static constexpr int kBlock = 13;
  static constexpr int kP = 0, kQ = 3, kEta = 7;

  /// `who` names the scheme in error messages. Throws std::invalid_argument for nodes < 3 and,
  /// unless `constrained`, Kirchhoff rods and length control. The problem must outlive this
  /// object. `corrected_grid` (corrected_grid.hpp): the problem is to carry the grid's model
  /// (corrected_grid_problem), and a free tip's half cell is a rigid body (TipHalfCell: its
  /// full inertia in the tip's balance, gravity at its centre of mass, both in the energies);
  /// require_corrected_grid's conditions hold.
  SemiDiscreteRod(const DynamicProblem& problem, int nodes, const std::string& who,
                  bool constrained = false, bool corrected_grid = false);

  const DynamicProblem& problem() const { return P_; }
  int nodes() const { return n_; }
  double ds() const { return ds_; }
  /// 13 (N - 1) node unknowns (13 (N - 2) with a clamped tip), then D and W, then the actuator
  /// unknowns (muscle lengths; ida).
  int size() const { return dim_; }
  int node_size() const { return iD_; }
  int dissipated_index() const { return iD_; }
  int work_index() const { return iW_; }
  /// Characteristic scale per component (see above), size().
  const Vector& scale() const { return scale_; }
  /// scale() with 1 m for the positions (tolerances on positions are absolute).
  Vector tolerance_scale() const;
  /// omega_1 [rad/s], the characteristic rate of the gross motion.
  double omega1() const { return omega1_; }
  /// A Kirchhoff rod (constrained construction only): constraint forces and constraint rows.
  bool kirchhoff() const { return kirchhoff_; }
  /// 3 (N - 1) for a Kirchhoff rod (one force / constraint triple per segment), else 0.
  int constraint_size() const { return kirchhoff_ ? 3 * (n_ - 1) : 0; }
  /// E I / L^2 [N], the characteristic constraint force.
  double force_scale() const { return force_scale_; }

  // --- actuator unknowns (see above) ---------------------------------------------------------
  /// One per DynamicProblem::unknown_actuators(), stored after D and W in y.
  int unknown_size() const { return m_; }
  int unknown_index() const { return iX_; }
  /// Whether unknown e is a muscle's length (else a length-controlled actuator's force).
  bool unknown_is_length(int e) const { return is_muscle_[e]; }
  /// The characteristic size of unknown e: L for a length, force_scale() for a force.
  double unknown_scale(int e) const { return is_muscle_[e] ? P_.length() : force_scale_; }
  /// Their initial values at the state y: muscle lengths L_e(y), forces 0.
  Vector initial_unknowns(const ConstRef& y) const;
  /// The rows of the actuator unknowns (above), after an rhs() at y_f with the same unknowns x:
  /// the muscles' rows use the lengths of that evaluation; the length-controlled rows evaluate
  /// the path lengths at (t_c, y_c).
  void actuator_rows(double t_c, const ConstRef& y_c, const ConstRef& x, Eigen::Ref<Vector> rows) const;
  /// Path lengths of the actuator unknowns' paths at y (size unknown_size()).
  void path_lengths(const ConstRef& y, Eigen::Ref<Vector> lengths) const;
  /// The grid rest length Delta*_e and the target length of unknown e at t (length control).
  double rest_length(int e) const { return rest_[e]; }
  double target_length(int e, double t) const;
  /// The axial forces of the last rhs() evaluation, by actuator.
  const DynamicProblem::Forces& last_forces() const { return F_; }

  /// y at rest at the node poses g0 (base first, nodes() of them), D = W = 0, muscle lengths
  /// of the poses. Throws std::invalid_argument for a wrong count.
  Vector rest_state(std::span<const SE3> g0) const;

  /// f(t, y) of y' = f(t, y): y and f of size() (node_size() is enough for y without actuator
  /// unknowns: D and W are not read; with them y of size() carries them), f of size() (ledger
  /// rows, then the rates of the unknowns' path lengths) or node_size() (node rows only).
  void rhs(double t, const ConstRef& y, Eigen::Ref<Vector> f) const;
  /// The same with the constraint forces `forces` (constraint_size(), N) of a Kirchhoff rod.
  void rhs(double t, const ConstRef& y, const ConstRef& forces, Eigen::Ref<Vector> f) const;
  /// The same with the actuator unknowns x (unknown_size()) given apart from y.
  void rhs(double t, const ConstRef& y, const ConstRef& forces, const ConstRef& x,
           Eigen::Ref<Vector> f) const;
  /// IDA's residual of the semi-discrete rod (the ODE above as a DAE): F = y' - f(t, y) for the
  /// node and ledger rows ((3.38)-(3.41), (3.8)), and the muscles' algebraic rows
  /// (Delta - L(y)) / L (actuator_rows). Kirchhoff rods and length control use
  /// ida_residual_stabilised instead.
  void ida_residual(double t, const ConstRef& y, const ConstRef& yp, Eigen::Ref<Vector> r) const;
  /// c_k(y) = nu(log(g_k^-1 g_(k+1))) / ds - nu* into c (constraint_size()), Kirchhoff rods.
  void constraint(const ConstRef& y, Eigen::Ref<Vector> c) const;

  /// Structural pattern of a Newton matrix a I - b df/dy: block tridiagonal node blocks and, with
  /// the ledger, the two ledger rows over every node column and the ledger diagonal; then the
  /// actuator unknowns' columns (dense over the eta rows and the ledger rows) and rows (dense
  /// over the p, q columns, and their own diagonal).
  SparseMatrix pattern(bool with_ledger) const;

  /// How newton_matrix() forms df/dy: `automatic` takes the analytic linearisation
  /// (semi_discrete_jacobian.cpp; docs/dynamics.md "The analytic Jacobian of the semi-discrete
  /// rod") where it covers the scene (analytic_jacobian()), else coloured finite differences;
  /// `finite_differences` always differences (the reference the analytic one is tested against).
  enum class JacobianMethod { automatic, finite_differences };
  /// Whether `automatic` is analytic here: Cosserat rods without muscles, actuator unknowns or
  /// cable entry loads (force-driven actuators, gravity, drag, distributed and tip loads are
  /// covered; their per-segment and per-node terms are differenced locally).
  bool analytic_jacobian() const;

  /// J = a I - b df/dy at (t, y), on a matrix with the pattern of pattern(J.rows() == size())
  /// (values overwritten; y of size() or node_size(); the actuator unknowns come from y's tail
  /// with the ledger; their rows are d(actuator_rows)/d(y, x), the muscles' at y: -dL/dy / L and
  /// 1 / L). Finite differences: three node colours (above).
  void newton_matrix(double t, const ConstRef& y, double a, double b, SparseMatrix& J,
                     JacobianMethod method = JacobianMethod::automatic) const;

  /// Rods with constraints at the end of the step (Kirchhoff rods, length control) or actuator
  /// unknowns: the pattern of the constrained Newton matrix (no ledger)
  ///   [ a I - b df/dy (t, y, forces, x)   - b df/dforces   - b df/dx ]  node rows
  ///   [ cy dc/dy (y_c)                     0                0        ]  c_k (Kirchhoff)
  ///   [ d(actuator_rows)/dy                0                1/L, 0   ]  actuator unknowns
  /// (c_k sees p, q of nodes k and k + 1; f_k the eta rows of nodes k and k + 1; muscle rows
  /// -dL/dy(y) / L, length rows cy dL/dy(y_c) / L).
  SparseMatrix constrained_pattern() const;
  /// Fills that matrix by coloured finite differences (three node colours for the node
  /// columns, perturbing y and y_c together; two segment colours for the forces; one
  /// evaluation per actuator unknown).
  void constrained_newton_matrix(double t, const ConstRef& y, const ConstRef& forces, double a,
                                 double b, const ConstRef& y_c, double cy, SparseMatrix& J) const;
  void constrained_newton_matrix(double t, const ConstRef& y, const ConstRef& forces,
                                 const ConstRef& x, double a, double b, const ConstRef& y_c,
                                 double cy, SparseMatrix& J) const;

  // --- the stabilised index-2 form (ida with Kirchhoff rods or length control) ---------------
  // Gear-Gupta-Leimkuhler (docs/dynamics.md "ida: Kirchhoff rods and length control";
  // semi_discrete_rod_stabilised.cpp). Unknowns, in this order (stabilised_size() in all):
  //   [nodes; D; W; f (constraint_size()); x (unknown_size()); mu (constraint_size());
  //    mu_x (one per length-controlled unknown)],
  // f, x and the multipliers mu, mu_x algebraic. Rows:
  //   nodes, D, W  y' - f(t, y; f, x) - K (mu, mu_x)   K: the pose rates of the velocity
  //                W C^T (mu, mu_x), C the constraint gradient, W = (M w_j)^-1 per node
  //   at f         c_k(y) = nu_k - nu*                           position level, Kirchhoff
  //   at x         muscles (x - L(y)) / L; length (L(y) - L_target(t)) / L    position level
  //   at mu        [xi_dot_k]_nu / omega_1 = (C eta)_k / omega_1   velocity level, Kirchhoff
  //   at mu_x      (dL/dt - L_target'(t)) / (L omega_1)           velocity level, length
  // The targets are the linear piece of their (piecewise linear) schedule that starts at
  // t_piece: L_target(t_piece) + L_target'(t_piece) (t - t_piece), so that the rows stay smooth up
  // to the end of the piece (a kink is a restart: stabilised_consistent_state()).
  /// Kirchhoff rod or length control (position-level constraints).
  bool has_position_constraints() const { return kirchhoff_ || length_control_; }
  int stabilised_size() const;
  int stabilised_force_index() const;       ///< f
  int stabilised_unknown_index() const;     ///< x
  int stabilised_multiplier_index() const;  ///< mu, then mu_x
  /// 1 for the differential components (nodes, D, W), 0 for the algebraic ones (IDASetId).
  Vector stabilised_id() const;
  /// tolerance_scale() extended: f and F by force_scale(), muscle lengths by L, multipliers by
  /// force_scale() / omega_1 (an impulse).
  Vector stabilised_tolerance_scale() const;
  /// The stabilised layout of a rest_state() vector (forces and multipliers 0).
  Vector stabilised_from_rest(const ConstRef& rest) const;
  /// IDA's residual in the stabilised index-2 form (above).
  void ida_residual_stabilised(double t, double t_piece, const ConstRef& y, const ConstRef& yp,
                           Eigen::Ref<Vector> r) const;
  /// The pattern of IDA's Newton matrix dF/dy + cj dF/dy' for this residual.
  SparseMatrix stabilised_pattern() const;
  /// Fills it: the constrained finite differences of constrained_newton_matrix() for the node,
  /// ledger, position-constraint and actuator rows; the velocity rows by node colours; the
  /// multiplier columns exactly (K is linear in mu).
  void stabilised_newton_matrix(double t, double t_piece, const ConstRef& y, double cj,
                                SparseMatrix& J) const;
  /// Consistent (y, yp) at t from the poses, velocities, D and W of y: poses projected onto the
  /// position constraints when they are off by more than rounding (g_j <- g_j exp(K_j nu), Newton);
  /// velocities projected onto the velocity constraints (eta <- eta + K lambda: the impulse that
  /// a kink of a prescribed length gives); f and the length-controlled forces from the
  /// acceleration-level constraints d/dt (C eta) = 0 (affine in them: Newton with a dense
  /// finite-difference Jacobian, 3 (N - 1) + m columns); muscle lengths L(y); mu = 0; yp the
  /// rates. Throws std::runtime_error when a projection does not converge.
  void stabilised_consistent_state(double t, double t_piece, Vector& y, Vector& yp) const;
  /// The times where a length-controlled actuator's schedule has a kink or a jump (restarts).
  std::vector<double> stabilised_breakpoints() const;

  /// Whether f evaluates a plain rod's segments in pairs (packed_pair.hpp; default true, the
  /// same f to rounding: tests/dynamics/test_semi_discrete_packed.cpp); false: one by one.
  void set_packed(bool packed) { packed_ = packed; }

  /// Poses, velocities and strains of y for the reports below (y: size() or node_size()).
  void set_state(const ConstRef& y) const;
  /// Node poses and velocities (N each, base first) and segment strains xi_j (N - 1, (3.38)) of
  /// the state last set; every evaluation of f or of a Newton matrix overwrites them.
  std::span<const SE3> poses() const { return g_; }
  std::span<const Vector6> velocities() const { return eta_; }
  std::span<const Vector6> strains() const { return xi_; }
  /// Writes the node rows of y (p, q, eta of the unknown nodes; a clamped tip's are not) from
  /// node poses g and velocities eta (N each, base first). Each quaternion takes the sign of the
  /// one y holds (R(q) = R(-q)), so that the node rows stay on the branch they were on.
  void pack_nodes(std::span<const SE3> g, std::span<const Vector6> eta,
                  Eigen::Ref<Vector> y) const;
  /// Energies of the state last set; dissipated and work_in as given.
  Energy energy(double dissipated, double work_in) const;
  Vector3 tip_position() const { return g_.back().translation(); }
  double max_det_deviation() const;
  std::vector<result::CenterlineSample> centerline() const;

 private:
  /// Where the blocks of a Newton matrix start: node unknowns at 0, the ledger pair (ida), the
  /// Kirchhoff forces, the actuator unknowns; n columns in all.
  struct Layout {
    bool ledger = false, forces = false;
    int iF = 0, iX = 0, n = 0;
  };
  Layout layout(bool ledger, bool forces) const;
  SparseMatrix build_pattern(const Layout& lay) const;
  void fill_newton_matrix(const Layout& lay, double t, const ConstRef& y, const double* forces,
                          const double* x, double a, double b, const ConstRef& y_c, double cy,
                          SparseMatrix& J) const;
  void unpack_nodes(const double* y) const;
  /// The analytic J = a I - b df/dy (semi_discrete_jacobian.cpp), node rows and, with
  /// lay.ledger, the ledger rows; only where analytic_jacobian().
  void analytic_newton_matrix(const Layout& lay, double t, const ConstRef& y, double a, double b,
                              SparseMatrix& J) const;
  /// d(lambda_j), d(Ad^T lambda_j) and the ledger powers' gradients of segment j by its four
  /// inputs (pose perturbations of nodes j, j + 1, then their velocities), at the last evaluate().
  static constexpr int kNearPose = 0, kFarPose = 1, kNearVelocity = 2, kFarVelocity = 3;
  struct SegmentLinearisation {
    std::array<lie::Matrix6, 4> lambda, moved;
    std::array<Vector6, 4> diss, work;
  };
  void linearise_segment(int j, SegmentLinearisation& out) const;
  /// Node j's own terms: d(eta_dot) by its pose perturbation and velocity (without the segment
  /// stresses), d(p_dot) by its pose, and its ledger powers' gradients.
  struct NodeLinearisation {
    lie::Matrix6 eta_pose, eta_velocity;
    Vector6 diss_pose, diss_velocity, work_pose, work_velocity;
  };
  void linearise_node(int j, double t, NodeLinearisation& out) const;
  mutable std::vector<SegmentLinearisation> seg_lin_;
  mutable std::vector<NodeLinearisation> node_lin_;
  /// f of the node rows into f (node_size()); the ledger powers into diss, work; the rates of
  /// the unknowns' path lengths into rates_ and their per-segment terms into seg_len_.
  void evaluate(double t, const double* y, double* f, double& diss, double& work,
                const double* forces = nullptr, const double* x = nullptr) const;
  /// Segment j's strain xi_, rate xi_dot_, stress wrench lambda_, its Ad_G^T (moved_) and its
  /// ledger terms at the poses and velocities of g_, eta_.
  void segment(int j, double t, bool actuators, const double* forces) const;
  /// The same for segments j and k at once on packed_pair.hpp's two lanes (the plain rod: no
  /// actuators, muscles or Kirchhoff constraint); false, with nothing stored, where a lane's
  /// angle is above the small-angle kernels' bound.
  bool segment_pair(int j, int k) const;
  void constraint(const double* y, double* c) const;
  /// Per-segment path-length terms of the unknowns at y into seg (m x (N - 1)); returns nothing.
  void segment_lengths(const double* y, std::vector<double>& seg) const;
  // The stabilised form (semi_discrete_rod_stabilised.cpp).
  int length_count() const;
  double piece_target(int e, double t, double t_piece) const;
  /// Adds K (mu, mu_x) to the pose rates f (node rows) at the poses of the last evaluate().
  void add_pose_correction(const double* mu, const double* mu_x, double* f) const;
  /// The node velocities K (mu, mu_x) into out (6 per node j >= 1), same poses.
  void pose_correction(const double* mu, const double* mu_x, std::vector<Vector6>& out) const;
  /// The velocity rows of the last evaluate() into kin (constraint_size()) and len (length_count()).
  void velocity_rows(double t_piece, double* kin, double* len) const;
  /// The per-segment terms of the length rates of the last evaluate() (length_count() x (N - 1)).
  void segment_rates(std::vector<double>& seg) const;
  mutable std::vector<Vector6> corr_lambda_, corr_moved_, corr_node_;
  mutable SparseMatrix stab_base_;

  /// Node j's weight per unit length, at the half cell's centre of mass at a corrected tip.
  Vector6 node_gravity(int j, const SO3& R) const {
    const Vector6 weight = P_.gravity_load(R);
    return tip_cell_ && j == n_ - 1 ? tip_cell_->at_centre_of_mass(weight) : weight;
  }

  /// Segment j's strain as the stresses see it (Kirchhoff: nu = nu* of its span).
  Vector6 model_strain(const Vector6& xi, int j) const {
    if (!kirchhoff_) return xi;
    Vector6 x = xi;
    x.tail<3>() = xi_star_[j].tail<3>();
    return x;
  }

  const DynamicProblem& P_;
  int n_;
  double ds_ = 0.0, omega1_ = 0.0, force_scale_ = 1.0;
  bool kirchhoff_ = false;
  bool clamped_ = false;  ///< the tip node is held by a clamp (not an unknown)
  int last_ = 0;          ///< the last unknown node: N - 1, or N - 2 with a clamped tip
  std::vector<Vector6> xi_star_;  ///< per segment: RodModel::segment_xi_star
  bool packed_ = true;            ///< segment_pair where the scene allows it
  int dim_ = 0, iD_ = 0, iW_ = 0, iX_ = 0, m_ = 0;
  Vector6 M_, V_;
  // Actuator unknowns and embedded muscles (see above).
  bool muscles_ = false, length_control_ = false;
  std::vector<int> unknown_act_;               ///< actuator index of unknown e
  std::vector<char> is_muscle_;                ///< unknown e is a muscle length
  std::vector<double> rest_, seg_weight_;      ///< rest lengths; overlaps (m x (N - 1))
  // Node inertia densities where they are not the rod's diagonal M_ (full_inertia_): muscles,
  // or the corrected grid's tip half cell (tip_cell_).
  bool full_inertia_ = false;
  std::vector<lie::Matrix6> inertia_, inertia_inv_;
  std::optional<TipHalfCell> tip_cell_;
  mutable DynamicProblem::Forces F_{};
  mutable std::vector<double> seg_len_, seg_len0_, seg_lenc_, seg_lenc0_;  ///< m x (N - 1)
  mutable Vector rates_, lengths_, xtmp_;
  Vector scale_;
  std::vector<DynamicProblem::EntryNode> entries_;
  // Work arrays of evaluate() (mutable: the reports unpack the current state).
  mutable std::vector<SE3> g_;
  mutable std::vector<Vector6> eta_, xi_, xi_dot_, lambda_, moved_;
  mutable std::vector<double> seg_diss_, seg_work_, node_diss_, node_work_;
  // Finite-difference work arrays.
  mutable Vector f0_, f1_, ytmp_, yctmp_, c0_, c1_, ftmp_;
  mutable std::vector<double> seg0_diss_, seg0_work_, node0_diss_, node0_work_;
};

}  // namespace rodlab::solvers::dynamics
