#pragma once
// The Newton matrix of the `chebyshev` statics collocation (chebyshev.hpp), kept by its parts,
// and its factorisation by condensation: a 6N system instead of the 12N one (N nodes).
//
// PARTS. Per node k the unknowns are theta_k = [phi; rho] (rotation, translation part of the
// chart coordinate) and Lambda_k = [m; n] (moment, force), in this order, and so are its rows:
// the theta rows (2.104) (theta_0 = 0 at an element's first node) and the Lambda rows (2.103)
// (the tip conditions, or Lambda continuity, at an element's last node). The matrix is
//     J = D part + node blocks + chart blocks:
// the D part is D_ik I_6 on theta (rows i >= 1) and on Lambda (rows i <= n - 2) of each element,
// plus -I_6 from a continuity row to the next element's first Lambda; node_block(k) (12 x 12)
// is the derivative of node k's rows, the D part excluded, with respect to node k's unknowns;
// chart_block(e) is the derivative of the rows of every node after element e with respect to
// theta of e's last node, which moves the charts of all later elements. With actuators that
// have an unknown (docs/statics.md: a length-controlled force, a muscle's length) the q extra
// unknowns z and their q length rows border the matrix: border_columns() (12N x q, the node
// rows' derivatives with respect to z), border_rows() (q x 12N) and border_corner() (q x q).
//
// STRUCTURE USED. (a) The rows theta_0 = 0 have the node block [I_6 0]. (b) The phi rows,
// (2.104)'s rotation part D phi = (L/2) A^-1(phi) omega (A = so3 dexp), involve only phi and
// Lambda (through omega); their block d/dm = -(L/2) A^-1(phi) d omega/dm (scaled; K_omega^-1
// without actuators) is invertible for Cosserat and Kirchhoff rods alike (for Kirchhoff rods
// only the force is a constraint force). Without actuators omega does not depend on n; with
// actuators the tendon law couples them (G_phi,n != 0). (c) The Lambda
// rows depend on theta only through the rotation (loads are dead or follow the body), so rho
// enters rows other than its own only through the clamped tip's position rows, directly and
// through the charts (six tip rows at most).
//
// CONDENSATION of J dx = b, per element (n nodes; the chart and continuity couplings add terms
// of the same kinds), G the node blocks:
// (0) dtheta_0 = b_theta,0 by (a); its columns move to the right-hand side.
// (1) rho_1..n-1: their rows, A_e drho = b_rho - D_.0 drho_0 - G_rho,x dx (x = phi, m, n, node
//     by node), A_e = D (x) I_3 + G_rho,rho on rows and columns 1..n-1 (3(n-1) square), are
//     factorised once. The tip rows' rho part T_rho drho becomes T_rho A^-1 (...): with
//     Z = T_rho A^-1 (6 x 3(n-1), six transposed solves) the tip rows gain -Z G_rho,x on x and
//     -Z b_rho on the right-hand side.                                                     (C1)
// (2) m_k, k >= 1: the phi row k gives, with H_k = G_phi,m(k)^-1,
//         dm_k = y_k - sum_{l>=1} Y_kl dphi_l - N_k dn_k,
//         y_k = H_k (b_phi,k - D_k0 dphi_0),  Y_kl = H_k (D_kl I_3 + delta_kl G_phi,phi(k)),
//         N_k = H_k G_phi,n(k)  (zero without actuators, and then skipped),              (C2)
//     substituted into every row holding m_k: the m rows (coefficient D_jk I_3 + delta_jk
//     G_m,m(j), whose D part gives (D (x) I_3) Y, one (n-1)^2 by (n-1) x 3(n-1) product per
//     component), the n rows, the last rows and the tip rows of (C1).
// What is left, per element: unknowns phi_1..n-1, m_0, n_0..n-1 and rows m, n 0..n-2 plus the
// six last rows, 6n of each: S dz = b_S, factorised by PartialPivLU's algorithm (DeadlineLu:
// the run's wall-time guard is checked between its blocks). A solve forms b_S from b
// (y, Z, D products), solves S, recovers dm_k by (C2) and drho by (1).
// (3) The border (extra unknowns z, rows r): with A the node part above, [A B; C E] [dx; dz] =
// [b; c] is solved by the Schur complement: V = A^-1 B (q solves per factorisation),
// (E - C V) dz = c - C A^-1 b (a q x q LU), dx = A^-1 b - V dz. At N = 24 the LUs are of
// 144 and 69 instead of 288: about a seventh of the flops (measured on one core, quiet: 0.15 and
// 0.02 ms against 1.05 ms), and a solve costs ~8 us.
//
// Exact algebra: the steps are those of Newton with the full matrix, up to rounding. A singular
// matrix (e.g. the axial mode of a straight Kirchhoff rod clamped at both ends) makes S or some
// A_e singular; factorize() then returns false and the caller falls back on the full matrix
// (assemble()) with least-squares steps.
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "rodlab/solvers/common/deadline_lu.hpp"

namespace rodlab::solvers::statics {

class ChebyshevNewtonMatrix {
 public:
  using Matrix12 = Eigen::Matrix<double, 12, 12>;
  /// One spectral element: n >= 2 nodes from node index `first` on, d/dt on [-1, 1] (n x n).
  struct Element {
    int n;
    int first;
    const Eigen::MatrixXd* D;
  };

  /// `extra`: the number q of bordering unknowns and rows (0 without them).
  explicit ChebyshevNewtonMatrix(std::vector<Element> elements, int extra = 0);

  int size() const { return 12 * nodes_ + extra_; }
  Matrix12& node_block(int k) { return blocks_[k]; }
  const Matrix12& node_block(int k) const { return blocks_[k]; }
  /// 12 (nodes after element e) x 6; only for e + 1 < elements.
  Eigen::MatrixXd& chart_block(int e) { return chart_[e]; }
  /// The border (extra > 0): d(node rows)/dz, d(extra rows)/d(node unknowns), d(extra rows)/dz.
  Eigen::MatrixXd& border_columns() { return border_columns_; }
  Eigen::MatrixXd& border_rows() { return border_rows_; }
  Eigen::MatrixXd& border_corner() { return border_corner_; }

  /// Condenses and factorises. False if the matrix is singular (some pivot ratio below
  /// `singular_pivot`, or not finite): solve() must not be used then.
  bool factorize(double singular_pivot);
  /// x = J^-1 b (after a successful factorize()); x must not alias b. No allocation.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// The full 12N x 12N matrix.
  void assemble(Eigen::MatrixXd& J) const;

 private:
  using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  struct Layout {
    int reduced;  ///< first row/column of the element in S
    int rho;      ///< first of its 3(n-1) rho unknowns (also its offset in y)
  };
  // Indices, component-major within each field: component a of node i is a (n - 1) + i - 1 for
  // phi, rho, m (i >= 1) and the m, n rows (j <= n - 2: a (n - 1) + j), a n + i for n.
  int intervals(int e) const { return elements_[e].n - 1; }
  int phi_col(int e, int i, int a) const { return layout_[e].reduced + a * intervals(e) + i - 1; }
  int m0_col(int e, int a) const { return layout_[e].reduced + 3 * intervals(e) + a; }
  int n_col(int e, int i, int a) const {
    return layout_[e].reduced + 3 * intervals(e) + 3 + a * elements_[e].n + i;
  }
  int m_row(int e, int j, int a) const { return layout_[e].reduced + a * intervals(e) + j; }
  int n_row(int e, int j, int a) const { return m_row(e, j, a) + 3 * intervals(e); }
  int last_row(int e, int c) const { return layout_[e].reduced + 6 * intervals(e) + c; }
  int rho_col(int e, int i, int a) const { return layout_[e].rho + a * intervals(e) + i - 1; }
  /// Rows `rows` of S get -coeff * (row block k of Y): the substitution (C2) of m_k (k >= 1) in
  /// rows whose coefficient of m_k is coeff.
  template <int R>
  void substitute_moment(const int (&rows)[R], const Eigen::Matrix<double, R, 3>& coeff, int e, int k);
  void build_element_systems(bool& regular, double singular_pivot);  ///< H, Y, A_e
  void build_tip_rho_coupling();                                        ///< Z
  void build_reduced();                                                 ///< S
  /// The node part of solve(): x's first 12N entries from b's (x sized already).
  void solve_nodes(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// Rows `rows` of S get -coeff N_k on n_k (the n part of (C2)), when node k is coupled.
  template <int R>
  void substitute_force(const int (&rows)[R], const Eigen::Matrix<double, R, 3>& coeff, int e, int k);

  std::vector<Element> elements_;
  std::vector<Layout> layout_;
  int nodes_ = 0, reduced_size_ = 0, rho_size_ = 0, extra_ = 0;
  std::vector<Matrix12> blocks_;
  std::vector<Eigen::MatrixXd> chart_;
  std::vector<Eigen::Matrix3d> H_;                            ///< per node (k >= 1 of each element)
  std::vector<Eigen::Matrix3d> N_;                            ///< per node: H G_phi,n (C2)
  std::vector<char> coupled_;                                 ///< per node: G_phi,n != 0
  std::vector<RowMajorMatrix> Y_;                             ///< per element, 3(n-1) square
  std::vector<Eigen::PartialPivLU<Eigen::MatrixXd>> rho_lu_;  ///< A_e
  Eigen::MatrixXd Z_;                                         ///< 6 x rho unknowns: T_rho A^-1
  Eigen::MatrixXd S_;
  DeadlineLu S_lu_;  ///< in place in S_ (PartialPivLU's factors; polls the wall-time guard)
  // The border (3): V = A^-1 B and the Schur complement's LU.
  Eigen::MatrixXd border_columns_, border_rows_, border_corner_, V_;
  Eigen::PartialPivLU<Eigen::MatrixXd> schur_lu_;
  // Solve scratch.
  Eigen::VectorXd b_reduced_, z_, b_rho_, y_, dm_, drho_, column_, solved_, c_, dz_;
};

}  // namespace rodlab::solvers::statics
