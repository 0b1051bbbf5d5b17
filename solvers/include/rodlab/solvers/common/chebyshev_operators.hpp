#pragma once
// Chebyshev-Lobatto collocation operators (thesis 2.6.2, (2.94)-(2.102); Trefethen, "Spectral
// Methods in MATLAB", ch. 6 and 12).
//
// With n points (n >= 2, m = n - 1 intervals) the nodes are the extrema of T_m,
//     x_j = cos(j pi / m),   j = 0..m,
// stored here in INCREASING order, t_j = -x_j = -cos(j pi / m), so that t_0 = -1 is the base of
// a rod and t_m = +1 its tip. They are evaluated as t_j = sin(pi (2j - m) / (2m)), which is
// exactly antisymmetric (t_{m-j} = -t_j) in floating point.
//
// Differentiation matrix (2.102), for the increasing order: with c_0 = c_m = 2, c_j = 1 else,
//     D_ij = (c_i / c_j) (-1)^(i+j) / (t_i - t_j),   i != j,
// where t_i - t_j = 2 sin(pi (i + j) / (2m)) sin(pi (i - j) / (2m)) is evaluated without
// cancellation. The diagonal is NOT the closed form of (2.102), -x_j / (2 (1 - x_j^2)) and
// +-(2 m^2 + 1)/6, which suffers from cancellation in t_i - t_j and is inconsistent with the
// rounded off-diagonal entries; instead it is the negative row sum, D_ii = -sum_{j != i} D_ij
// (Baltensperger & Trummer, SIAM J. Sci. Comput. 24 (2003) 1465), so that D annihilates
// constants exactly, summed smallest magnitude first. Rows in the upper half are computed and the
// others mirrored by the centro-antisymmetry D_{m-i, m-j} = -D_ij ("flipping trick"), which the
// exact matrix has.
//
// Clenshaw-Curtis weights w_j integrate every polynomial of degree <= m exactly (degree m + 1
// for even m) on [-1, 1]: int f = sum_j w_j f(t_j) (Waldvogel's explicit cosine sums, as in
// Trefethen's clencurt).
//
// On an interval [a, b] the nodes are s_j = (a + b)/2 + (b - a)/2 t_j, d/ds = 2/(b - a) d/dt and
// the weights scale by (b - a)/2 (chebyshev_lobatto below).
#include <Eigen/Core>

namespace rodlab::solvers {

/// The n Chebyshev-Lobatto points on [-1, 1], increasing. Throws std::invalid_argument for n < 2.
Eigen::VectorXd chebyshev_lobatto_points(int n);

/// d/dt on those points (n x n): (D f)_i = p'(t_i) for the interpolant p of degree n - 1.
Eigen::MatrixXd chebyshev_differentiation_matrix(int n);

/// Integration consistent with D (n x n): the inverse of D with its first row replaced by
/// e_0^T. u = S [u_0; g_1; ...; g_{n-1}] is the polynomial of degree n - 1 with u(-1) = u_0 and
/// u'(t_j) = g_j for j >= 1, i.e. u_0 plus the integral from -1 of the polynomial of degree n - 2
/// through (t_j, g_j), j >= 1: the collocation of u' = g with an initial value.
Eigen::MatrixXd chebyshev_integration_matrix(int n);

/// Clenshaw-Curtis quadrature weights on [-1, 1] for those points.
Eigen::VectorXd clenshaw_curtis_weights(int n);

/// Barycentric interpolation from the n points to arbitrary t in [-1, 1]: row k of the result
/// holds the cardinal functions C_j(t_k) (2.99)-(2.100) (barycentric weights (-1)^j / c_j).
Eigen::MatrixXd chebyshev_interpolation_matrix(int n, const Eigen::VectorXd& t);

/// All of the above mapped to an interval [a, b] (a < b).
struct ChebyshevLobatto {
  Eigen::VectorXd s;  ///< nodes, increasing, s_0 = a, s_{n-1} = b
  Eigen::MatrixXd D;  ///< d/ds on the nodes
  Eigen::VectorXd w;  ///< quadrature weights, sum = b - a
};
ChebyshevLobatto chebyshev_lobatto(int n, double a, double b);

}  // namespace rodlab::solvers
