#pragma once
// The `kinsol` statics reference: a global collocation of the statics BVP (2.33)-(2.34),
// solved at once by SUNDIALS KINSOL (Newton with a line search) with a sparse Jacobian.
//
// Scheme: Runge-Kutta-Munthe-Kaas with the 3-stage Lobatto IIIA tableau (Hermite-Simpson),
// written as a collocation. N uniform nodes s_i = i h, h = L / (N - 1) (with actuators, also
// nodes at the breakpoints: see "Actuators" below). On the interval [s_i, s_{i+1}] the pose is
// g = g_i exp(Theta(s)) and, in that chart, the BVP is an ODE in a vector space (thesis
// (2.83)-(2.84), docs/conventions.md for the dexp convention):
//
//   Theta'  = F(Theta, Lambda) = dexp^-1_{-Theta} xi,          Theta(s_i) = 0
//   Lambda' = ad_xi^T Lambda - W_bar(R_i exp(Theta_omega))     (2.34), xi = problem.strain(Lambda)
//
// which Hermite-Simpson integrates in its compressed form (the midpoint stage from the cubic
// Hermite interpolants of the end values and slopes):
//
//   Theta_b  = log(g_i^-1 g_{i+1})                 (known from the node unknowns)
//   F_a = xi_i,  F_b = dexp^-1_{-Theta_b} xi_{i+1}
//   Theta_m  = Theta_b / 2 + h/8 (F_a - F_b),   Lambda_m = (Lambda_i + Lambda_{i+1}) / 2 + h/8 (Lambda'_i - Lambda'_{i+1})
//   F_m = dexp^-1_{-Theta_m} xi(Lambda_m),      Lambda'_m = (2.34) at (R_i exp(Theta_m), Lambda_m)
//   pose rows (6):   Theta_b - h/6 (F_a + 4 F_m + F_b) = 0
//   wrench rows (6): Lambda_{i+1} - Lambda_i - h/6 (Lambda'_i + 4 Lambda'_m + Lambda'_{i+1}) = 0
//
// dexp^-1 is the closed form (se3::dexp_inv_apply), so the method keeps the order 4 of Lobatto
// IIIA at the nodes (stage order 3); measured 3.999 on the gravity cantilever. It stays on the
// group: node poses are exact SE(3) elements, and a rod of constant strain xi (pure bending,
// constant-twist loads, clamped at an arc's end) is reproduced to rounding, because Theta = s xi,
// F = xi and ad_xi xi = 0 make every stage exact.
//
// Unknowns per node (13): a quaternion q_i (4, R_i = R(q_i / |q_i|)), p_i (3), Lambda_i (6).
// Equations (13 N): per interval 6 pose + 6 wrench rows + |q_{i+1}|^2 - 1 = 0 (the quaternion
// has one component more than the rotation it stands for); base (7): q_0 = q_base (all four
// components, which also fixes |q_0| = 1) and p_0 = p_base; tip (6):
//   free tip:    problem.tip_residual(g_N, Lambda_N), i.e. (Lambda_N - W_tip(R_N)) / wrench scale
//                in the body frame of the tip;
//   clamped tip: [2 vec(q_target^* q_N / |q_N|); (p_N - p_target) / L] (2 vec(.) is the rotation
//                error in rad to first order, smooth everywhere, zero only when R_N = R_target).
// 13 (N - 1) + 7 + 6 = 13 N. max ||q_i| - 1| is reported (it is solved to the tolerance).
//
// Scaling. Unknowns: q, p / L, Lambda ./ wrench_scale. Rows: rotation rows times L / h,
// translation rows divided by h, wrench rows times L / h and divided by wrench_scale, so every
// row is a dimensionless O(1) derivative and KINSOL's fnormtol (options.tol) means the same for
// every N. A tolerance below the rows' rounding floor (~ 64 eps (N - 1) max|x|) is met at that
// floor (KIN_STEP_LT_STPTOL there counts as converged).
//
// Jacobian. Node j enters only intervals j-1 and j (and the base or tip rows), so the columns
// of node j hold one contiguous block of at most 26 rows: a block-bidiagonal pattern, fixed once,
// factorised by the almost block diagonal LU (partial pivoting panel by panel; the extra
// unknowns' dense rows and columns by block LU, KLU where that looks ill-conditioned:
// almost_block_diagonal_lu.hpp). The values are forward differences node by node that
// re-evaluate only the node's data and the two intervals it touches (the same values as a
// 3-colour grouping of node blocks at a third of the cost: 13 columns x ~3 stage evaluations per
// node); the base rows are exact. The Jacobian is re-evaluated at every third iteration
// (kinsol_collocation.cpp: fewer Jacobians for one more iteration, 2.2 against 3.6 ms at N = 100).
//
// Actuators (docs/statics.md). The mesh has a node at every StaticProblem::breakpoints() value
// (span ends, routing knots): the N - 1 intervals are shared among the stretches between
// breakpoints in proportion to their lengths (at least one each; N >= breakpoints + 2, else
// std::invalid_argument), uniform within a stretch, so each interval has one active set
// (active_mask at its midpoint) and a smooth integrand. Without breakpoints the mesh is the
// uniform one above. The strain is the tendon law problem.strain(Lambda, s, mask) (a Newton
// solve; its derivative enters through the finite differences). A node's Lambda unknown is its
// left value; at a breakpoint the interval to its right sees Lambda + entry_jump(s, xi_left)
// (cables pulled from outside where they enter), and each side evaluates the routing's one-sided
// r' (at s - 1e-12 L on the left, and at the tip). Actuators with an unknown (displacement- or
// volume-controlled, muscles) add one unknown each (scaled as in StaticProblem) and one row,
// problem.extra_residuals of the path lengths integrated by the scheme's own Simpson quadrature
// h/6 (|u_a| + 4 |u_m| + |u_b|) per interval (order 4, with the collocation's midpoint strain);
// their columns are dense (a full residual per column), and every node column has the extra
// rows. A displacement-controlled cable that would need to push is reported as not converged
// ("slack"), as in shooting. Measured (tests/statics/test_kinsol_actuators.cpp) against rkmk-rk4
// at N = 401: tip errors O(h^4) over N = 21, 41, 81 (observed 3.5-4.6 per doubling on the
// non-nested meshes, 4.00 on a uniform one; mean over the two doublings 3.9-4.2).
//
// Initial guesses: free tip, the reference configuration g(s) = base exp(s xi*) with the wrench of
// the undeformed rod in equilibrium with the loads ((2.34) marched back from W_tip with RK4 along
// it, minus the pull of cables entering at breakpoints; extra unknowns at their initial guess);
// clamped tip, the constant-strain rod to the target (xi_c = log(base^-1 g_target) / L,
// Lambda = K (xi_c - xi*)) and the reference configuration with zero wrench.
//
// Solve:
//   1. direct: KINSOL with its line search (KIN_LINESEARCH) at load factor 1 from the guess(es),
//      at most 15 iterations, accepted when the line search never had to cut a step (the guess
//      was inside Newton's basin; from further away Newton can converge to another equilibrium
//      than the one the load path reaches, e.g. a coiled rod under a large dead tip load);
//   2. otherwise load continuation on problem.load_factor() from 0 (where the guess is exact) to 1
//      through the shared driver (continuation.hpp), each corrector at most 8 iterations without
//      backtracking (else the step is halved, so the walk does not jump branches);
//   3. if that fails too, the direct solves with the full budget (options.max_iterations),
//      backtracking allowed.
#include <string>

#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/statics/static_problem.hpp"

namespace rodlab::solvers::statics {

struct KinsolCollocationOptions {
  int nodes = 50;
  double tol = 1e-10;         ///< KINSOL fnormtol: max norm of the scaled residual
  double step_tol = 1e-14;    ///< KINSOL scsteptol
  int max_iterations = 50;    ///< nonlinear iterations per KINSOL solve
  bool direct = true;         ///< try the direct solves at load factor 1 first
  bool continuation = true;   ///< load continuation when the direct solves fail (or !direct)
};

struct KinsolCollocationReport {
  result::StaticResult result;
  int kinsol_solves = 0;              ///< KINSOL runs: direct and continuation correctors
  bool used_continuation = false;
  long nonlinear_iterations = 0;      ///< summed over all KINSOL solves (= result.iterations)
  long function_evaluations = 0;      ///< KINSOL's residual calls
  long jacobian_evaluations = 0;
  long backtracks = 0;
  std::string flag;                   ///< KINSOL flag of the last solve
  std::string strategy;  ///< "direct", "continuation", "direct, with backtracking" or "none"
  double max_quaternion_norm_error = 0.0;  ///< max_i ||q_i| - 1| of the solution
};

/// Solves one static equilibrium; non-convergence is reported in the result (reason starts
/// with KINSOL's flag name). Throws std::invalid_argument for nodes < 2, fewer nodes than the
/// actuator breakpoints need (breakpoints + 2), or bad options.
KinsolCollocationReport solve_kinsol_collocation_report(const StaticProblem& problem,
                                                        const KinsolCollocationOptions& options);

/// The result part of solve_kinsol_collocation_report.
result::StaticResult solve_kinsol_collocation(const StaticProblem& problem,
                                              const KinsolCollocationOptions& options);

}  // namespace rodlab::solvers::statics
