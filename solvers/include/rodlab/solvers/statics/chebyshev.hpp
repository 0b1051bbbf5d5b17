#pragma once
// The `chebyshev` statics scheme: Chebyshev-Lobatto pseudospectral collocation of the statics
// BVP (thesis 2.6.2, (2.99)-(2.105)), solved by Newton's method with a dense Jacobian.
//
// UNKNOWNS. N Chebyshev-Lobatto nodes s_0 = 0 < ... < s_{N-1} = L (chebyshev_operators.hpp;
// s_j = L/2 (1 + t_j), t_j = -cos(j pi / (N-1))). At each node the internal wrench Lambda_j and
// the algebra element theta_j of the pose in the base's chart,
//     g_j = g_0 exp(theta_j),  g_0 = base                                        (2.105)
// (theta is the RKMK ansatz (2.83) over the whole rod). 12 N unknowns.
//
// EQUATIONS. D is the differentiation matrix on [-1, 1] (2.102), so d/ds = (2/L) D and, with
// xi_j = xi(Lambda_j) = xi* + K^-1 Lambda_j (Kirchhoff: nu = nu*) and R_j = R_0 exp(omega(theta_j)):
//     sum_k D_jk theta_k  = (L/2) dexp^-1_{-theta_j} xi_j                 j = 1..N-1   (2.104)
//     sum_k D_jk Lambda_k = (L/2) (ad_{xi_j}^T Lambda_j - W_bar(R_j))     j = 0..N-2   (2.103)
// (2.103) in the Lambda form of static_problem.hpp: the thesis writes it for xi with K Delta xi
// = Lambda, which drops the Kirchhoff constraint force. dexp^-1 is the analytic closed form
// (lie::se3::dexp_inv_apply), as the thesis requires ("to make sure there is no degradation").
// Boundary rows replace the rows left out, as in the thesis ("we replace the rows of D and f
// corresponding to the endpoints"):
//     theta row 0:     theta_0 = 0                                      (g(0) = base)
//     Lambda row N-1:  free tip     Lambda_{N-1} - W_tip(R_{N-1}) = 0
//                      clamped tip  [log(R_target^T R_{N-1}); (p_{N-1} - p_target)/L] = 0
// (StaticProblem::tip_residual). 6N + 6N equations for 12N unknowns.
//
// WHY THE CLAMPED TIP REPLACES THE Lambda ROW. D has rank N-1 (it annihilates constants), so each
// of the twelve scalar fields needs exactly one row of D replaced by a condition that fixes its
// integration constant; collocating all N rows of any field makes the Newton matrix singular in
// the linear limit. Example: y1' = y2, y2' = 0, y1(-1) = 0, y1(1) = a. With all N rows kept for
// y2 and both end rows of y1 replaced, y2 = c and y1' - c = alpha prod_{interior}(t - t_j),
// leaving one equation 2c + alpha int prod = a for two unknowns. With one row of each field
// replaced (y1 at the base, y2 at the tip by the tip condition on y1), y2' vanishes at N-1 nodes
// so y2 = c, y1' = c, and y1(1) = a fixes c. So a clamped tip uses the same row layout as a free
// one: theta is collocated at the tip and the six pose conditions take the place of Lambda's tip
// row; they fix Lambda's integration constant, as they fix Lambda(0) in shooting.
//
// SCALING. Unknowns and rows are made O(1): theta's linear part and the theta rows' linear part
// are divided by L, Lambda and the Lambda rows by StaticProblem::wrench_scale() (E I / L for
// moments, E I / L^2 for forces); the tip rows are tip_residual's, already dimensionless. The
// tolerance applies to the inf-norm of this scaled residual.
//
// NEWTON. The Jacobian: the D part is exact (linear, constant), and since row j depends
// nonlinearly only on node j's 12 unknowns (the D coupling aside) the rest is block diagonal,
// 12 x 12 node blocks: their Lambda columns exact ((2.104) is linear in xi = xi* + K^-1 Lambda,
// (2.103)'s ad_xi^T Lambda bilinear; with actuators through dxi/dLambda, below), their theta
// columns (dexp^-1 in theta, the loads in R) and the tip node's block by central differences;
// with elements, the chart blocks too (the rows of later elements against the last theta of an
// element, which moves their charts; docs/statics.md). It is
// factorised by condensation (chebyshev_newton_matrix.hpp): theta_0 is known; the translations
// rho are solved per element (the Lambda rows see only rotations, so rho reaches other rows only
// through a clamped tip's position); each node's moment is eliminated through its rotation rows.
// That leaves a dense 6N system for Eigen's PartialPivLU (LUs of 144 and 69 instead of 288 at
// N = 24), and the same Newton steps as the full matrix up to rounding. The
// factorisation is reused for chord steps while the residual drops by 10x per step; the chord
// steps allocate nothing. The line search backtracks on the residual scaled by the Newton matrix,
// |J^-1 F(x + alpha dx)| <= (1 - alpha/4) |dx| (Deuflhard's natural monotonicity test): the
// plain 2-norm of the scaled residual stalls on the clamped cases, whose first steps must build
// an axial force of ~10 E I / L^2 (E A L^2 / E I = 1600 for the Table 2.1 rod) that the
// residual norm penalises. Converged when the inf-norm of the scaled residual is <= tol, or when
// it stalls within 10x of its rounding level eps max_j sum_k |D_jk| |x_k|, which grows like
// N^2 |x| (a tight tol is out of reach at large N). A singular Newton matrix (the straight
// Kirchhoff rod with both ends clamped: its axial force is undetermined to first order) gets
// minimum-norm least-squares steps with the full 12N matrix (CompleteOrthogonalDecomposition)
// until it is regular again.
//
// GUESSES. First the reference configuration theta_j = s_j xi* with Lambda the equilibrium of the
// undeformed rod with the loads, marched along s (rigid_wrench_profile in shooting.hpp, the idea
// of shooting's rigid_base_wrench). The direct solve starts from it bent by that Lambda: theta
// from the theta rows (2.104) with Lambda fixed (two fixed-point sweeps theta = S (L/2)
// dexp^-1_{-theta} xi(Lambda), S = chebyshev_integration_matrix), the linear-elastic deflection,
// so that the first Newton matrix is evaluated near the solution (5 Newton iterations instead of
// 8 on the gravity cantilever at tol 1e-10). Only while no chart then turns by more than pi / 3:
// beyond, the undeformed rod's wrench over-bends the rod (a dead tip load PL^2/EI = 10 would bend
// it by 5 rad), and the straight configuration is kept. For a clamped tip whose direct solve
// fails, second the constant twist joining base and target, xi_c = log(g_0^-1 g_target) / L
// (thesis 2.5), with Lambda = K (xi_c - xi*); it is exact for a target at the end of a circular
// arc. Then load continuation (continuation.hpp) from load factor 0, where the reference guess
// (straight) is exact, within a budget of 4 max_iterations Newton iterations per element layout.
//
// SPECTRAL ELEMENTS FOR LARGE ROTATIONS. The chart g_0 exp(theta) ends where |omega(theta)| = 2 pi
// (dexp^-1 has its pole there) and degrades before it, so one chart cannot hold a rod that curls
// into a full circle (tip moment M L / EI = 2 pi). The rod is then split into E equal elements,
// each a Chebyshev-Lobatto collocation on its own N_e nodes in its own chart based at its first
// node, g = g_e exp(theta), g_e = g_{e-1} exp(theta^{e-1}_last) (so g is continuous by
// construction); per element theta^e_0 = 0 replaces theta's first row, and Lambda's last row is
// Lambda continuity, Lambda^e_last = Lambda^{e+1}_0, except in the last element where it is the
// tip condition. The interface nodes are duplicated, so sum_e (N_e - 1) = N - 1 keeps N distinct
// nodes in the result; N_e differ by at most one. E is chosen automatically: E = 1 (the thesis's
// method, which is what runs for ordinary loads); if the converged solution, or the last iterate
// of a failed attempt, turns some chart by more than 2 pi / 3, E is doubled and the problem
// solved again: from the converged solution resampled (spectral interpolation of theta and
// Lambda, theta = log(g_e^-1 g) in the new charts) when there is one, keeping it if the finer
// solve fails; from the guesses above otherwise. Elements keep at least 5 nodes, except that a
// failed attempt that cannot otherwise be split may use elements of 3 (a full circle at N = 5..8).
// A full circle ends with E = 4 (pi / 2 per chart) from N = 17 on. ChebyshevReport returns the
// final E; the result itself does not record it (its nodes are those of the elements).
//
// RESOLUTION CHECK. An under-resolved discretisation can have spurious roots (a Kirchhoff rod
// "reaching" a target farther than L at N = 11 or 21, with axial forces of 10^3 E I / L^2). After
// convergence the collocation residual is evaluated between the nodes (at the angle midpoints,
// from the interpolants of theta, Lambda and their D-derivatives); if it exceeds a quarter of the
// solution's size (scaled unknowns' inf-norm, at least 1) the result is reported as not
// converged ("not resolved ..."). Resolved solutions measure <= 0.05 even at N = 12 under 30x
// gravity; the spurious roots seen measure >= 1.5.
//
// ACTUATORS (docs/statics.md; StaticProblem, actuator_term.hpp). The strain is the tendon law
// K (xi - xi*) + sum_k [F_k c_k(xi) + K_mus,k (xi - xi*)] = Lambda over the actuators active at s
// (StaticProblem::strain, a Newton solve per node); it and the routing r(s) make the strain
// non-smooth at the breakpoints (span ends, routing knots, cable entries), which would cost the
// collocation its spectral convergence. So element boundaries sit at every breakpoint: each
// stretch between breakpoints is split into ceil(E l / L) equal elements (E the level above: 1,
// then doubled for large rotations), and the N - 1 intervals are shared among the elements in
// proportion to (l_e / L)^(1/2), at least 2 each when N allows, else 1 (N >= breakpoints + 2,
// else std::invalid_argument). Each element has one active set; its nodes evaluate the paths at
// their s, the last one just inside the element (r' jumps at a knot). Interface conditions: g
// is continuous by the charts; the last row of an element is Lambda continuity, except where a
// cable enters the rod (pulled from outside), where Lambda(b+) = Lambda(b-) + F c(xi(b-))
// (StaticProblem::entry_jump, as kinsol and shooting; the strain is continuous there). A result
// node at an interface reports the value right of it, after the entry, as kinsol does.
// Newton matrix: dxi/dLambda is StaticProblem::strain_jacobian (the inverse of the law's
// Jacobian K + sum F dc/dxi + K_mus; its moment block for Kirchhoff rods), which couples the
// rotation rows to the force n (handled in the condensation, chebyshev_newton_matrix.hpp), and
// an entry row has I + F dc/dxi dxi/dLambda. Actuators with an unknown (a displacement- or
// volume-controlled force, a muscle's length Delta; StaticProblem::extra_unknowns) add q unknowns
// after the nodes' and q rows, StaticProblem::extra_residuals of the path lengths
// int |u| ds (2.47), (2.53), (2.66)-(2.67), by Clenshaw-Curtis quadrature on each element's
// nodes (spectral like the collocation: |u| is smooth inside an element). They border the
// Newton matrix: their columns by central differences of the residual, the length rows'
// Lambda entries in closed form (d|u|/dxi = t^T [-hat(r), I] times dxi/dLambda), solved by a
// Schur complement. chebyshev_newton_matrix_error checks the whole matrix against differences
// (8e-12 .. 2e-10 with actuators; 2e-3 .. 6e-2 if the tendon law's Jacobian is left out). A
// displacement-controlled cable that would have to push is reported as slack (not converged).
#include "rodlab/result/static_result.hpp"
#include "rodlab/solvers/statics/static_problem.hpp"

namespace rodlab::solvers::statics {

struct ChebyshevOptions {
  int nodes = 24;          ///< N, distinct nodes including both ends (>= 2)
  double tol = 1e-10;      ///< on the scaled residual's inf-norm
  int max_iterations = 50; ///< Newton iterations per solve (each continuation step is a solve)
  int elements = 0;        ///< 0: automatic (see above); > 0: that level E (exactly E elements
                           ///< without actuator breakpoints)
};

/// Diagnostics that the result type does not carry.
struct ChebyshevReport {
  int elements = 1;                ///< E of the returned solution
  int factorizations = 0;          ///< LU factorisations, all attempts together
  double max_chart_rotation = 0.0; ///< max |omega(theta)| over the nodes of the returned solution
};

/// For tests: the Newton matrix (exact D part, closed-form and differenced node blocks, chart
/// blocks, border) at the Newton iterate reached on the layout of level max(1, elements) from the
/// direct guess, against central differences of the whole residual: max over columns c of
/// |J_c - J_fd,c|_inf / max(1, |J_fd,c|_inf). Small (~1e-8) when Newton's steps are exact.
double chebyshev_newton_matrix_error(const StaticProblem& problem, const ChebyshevOptions& options);

/// Solves the problem; non-convergence is reported in the result (reason), never thrown.
/// Throws std::invalid_argument for nodes < 2 or too many elements for the nodes (with actuators:
/// fewer than breakpoints + 2 nodes).
result::StaticResult solve_chebyshev(const StaticProblem& problem, const ChebyshevOptions& options,
                                     ChebyshevReport* report = nullptr);

}  // namespace rodlab::solvers::statics
