#pragma once
// LU with partial pivoting of an almost block diagonal (ABD) matrix: the Jacobian of a two-point
// boundary-value problem discretised interval by interval, kinsol statics' collocation
// (kinsol_collocation.cpp). n = B N unknowns in N blocks of B, the rows in a staircase:
//
//     [ A_top                       ]   T rows on block 0 alone (the base conditions)
//     [ A_0   C_0                   ]   B rows per interval i, on blocks i and i + 1
//     [       A_1   C_1             ]
//     [              ...            ]
//     [             A_N-2   C_N-2   ]
//     [                     A_bot   ]   B - T rows on block N - 1 alone (the tip conditions)
//
// Gaussian elimination with partial pivoting of the whole matrix keeps that form. When block j's
// columns are eliminated, the only rows with entries in them are the T rows left over from
// block j - 1 (entries in block j alone) and interval j's B rows (blocks j and j + 1). So the
// elimination runs panel by panel, each panel a dense (T + B) x 2B matrix: for each of block
// j's B columns it pivots among the panel's rows (exactly the rows dense partial pivoting
// would choose among, so the factors are dense GEPP's, with its stability), keeps the B pivot
// rows as U's block row j and carries the T rows that remain, with entries in block j + 1
// alone, into panel j + 1. The last panel holds the carried rows and A_bot: B x B. This is the
// row-pivoting form of the ABD solvers (de Boor and Weiss' SOLVEBLOK, ACM TOMS 6 (1980) 80-87;
// Amodio et al., "Almost block diagonal linear systems", Numer. Linear Algebra Appl. 7 (2000)
// 275-317), without their column pivoting, which saves the carried rows' fill but needs
// interchanges of unknowns between blocks.
//
// A border of m <= kMaxBorder rows and columns may follow the blocks (kinsol's extra unknowns,
// actuator forces or muscle lengths, and their path-length rows: dense), [A E; F G]. It is
// eliminated by block LU on A's factors: W = A^-1 E (m solves), the Schur complement
// S = G - F W by dense partial pivoting, then x2 = S^-1 (b2 - F A^-1 b1), x1 = A^-1 b1 - W x2.
// That is stable when A is well conditioned (the rod with its actuators held); factor() refuses
// a bordered matrix whose pivots of A or of S look ill-conditioned (min |U_ii| / max |U_ii|
// below eps^(2/3), KLU's test in SUNLinSol_KLU), and the caller falls back to KLU
// (almost_block_diagonal_solver.cpp).
//
// A row operation runs over the whole fixed-size 2B-wide panel row (its entries left of the
// pivot column are zero): 2 B^2 (2T + B - 1) flops per block to factorise, 8.8 kflop for
// kinsol's B = 13, T = 7, in vectorised fixed-size loops, and about 4 B (T + B) to solve; a
// sparse LU of the same matrix (KLU) does fewer flops but spends more on its index work
// (docs/statics.md "Cost"). Fixed-size panels and a border of at most kMaxBorder: no allocation
// after construction. Private to solvers/common; Eigen only (tests/common instantiate it at
// small sizes).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "rodlab/solvers/common/small_lu.hpp"

namespace rodlab::solvers {

template <int B, int T>
class AlmostBlockDiagonalLU {
  static_assert(0 < T && T < B, "the first block row has T rows, the last B - T");

 public:
  static constexpr int R = T + B;  ///< rows of a panel
  using Panel = Eigen::Matrix<double, R, 2 * B, Eigen::RowMajor>;
  using Lower = Eigen::Matrix<double, R, B>;  ///< a panel's multipliers, zero on and above k = r
  using Pivots = std::array<int, B>;          ///< LAPACK's ipiv: row k swapped with pivots[k]

  static constexpr int kMaxBorder = 32;
  using BorderVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBorder, 1>;
  using BorderMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBorder,
                                     kMaxBorder>;

  /// A solver for `blocks` >= 1 blocks and `border` <= kMaxBorder bordering rows and columns
  /// (the matrix is B * blocks + border square).
  explicit AlmostBlockDiagonalLU(int blocks, int border = 0)
      : nb_(blocks),
        m_(border),
        panels_(blocks, Panel::Zero()),
        lower_(blocks),
        pivots_(blocks),
        E_(B * blocks, border),
        F_(border, B * blocks),
        W_(B * blocks, border),
        G_(border, border),
        schur_(border) {
    if (blocks < 1 || border < 0 || border > kMaxBorder)
      throw std::invalid_argument("AlmostBlockDiagonalLU: blocks >= 1, border 0..32");
  }

  int blocks() const { return nb_; }
  int border() const { return m_; }
  int size() const { return B * nb_ + m_; }

  /// Whether a CSC pattern (column pointers Ap, row indices Ai, size() columns) has its block
  /// part in the staircase above (the border rows and columns may hold anything). factor()
  /// takes the matrices of an accepted pattern.
  template <class Index>
  bool accept_pattern(const Index* Ap, const Index* Ai) {
    const long n = B * nb_;
    long staircase = 0;
    for (int c = 0; c < n; ++c) {
      bool border_rows = false;  // factor() reads a column's border rows after its block rows
      for (Index e = Ap[c]; e < Ap[c + 1]; ++e) {
        const long r = static_cast<long>(Ai[e]);
        if (r >= n && r < size()) {
          border_rows = true;
          continue;
        }
        if (border_rows || !in_staircase(r, c)) return false;
        ++staircase;
      }
    }
    for (Index e = Ap[n]; e < Ap[size()]; ++e)
      if (Ai[e] < 0 || Ai[e] >= size()) return false;
    const long dense = static_cast<long>(B) * (T + 2 * B * (nb_ - 1) + (B - T));
    dense_ = staircase == dense;  // every position the values own
    return true;
  }

  /// Factorises the CSC matrix (Ap, Ai, values) of an accepted pattern. False for a singular
  /// matrix (a pivot column without a non-zero), an infinite pivot, or with a border,
  /// ill-conditioned pivots of A or of the Schur complement.
  template <class Index>
  bool factor(const Index* Ap, const Index* Ai, const double* values) {
    factored_ = false;
    const long n = B * nb_;
    for (int j = 0; j < nb_; ++j) clear_unowned(j);
    if (m_) {
      E_.setZero();
      F_.setZero();
      G_.setZero();
    }
    // Entry (r, c) of block column j lies in panel p = j - 1 (rows of interval j - 1) or j, at
    // row r - B p and column c - B p: offset 2B r + B (2T - 1) p + c in the panels' doubles (they
    // are consecutive row-major R x 2B matrices). The border rows come last in a column.
    double* base = panels_.front().data();
    for (int c = 0; c < n; ++c) {
      const long j = c / B, split = j > 0 ? T + B * j : 0;  // rows above: panel j - 1
      const long here = static_cast<long>(B) * (2 * T - 1) * j + c;
      const long before = here - static_cast<long>(B) * (2 * T - 1);
      Index e = Ap[c];
      for (; e < Ap[c + 1] && Ai[e] < n; ++e) {
        const long r = static_cast<long>(Ai[e]);
        base[2 * B * r + (r < split ? before : here)] = values[e];
      }
      for (; e < Ap[c + 1]; ++e) F_(static_cast<long>(Ai[e]) - n, c) = values[e];
    }
    for (long c = n; c < size(); ++c)
      for (Index e = Ap[c]; e < Ap[c + 1]; ++e) {
        const long r = static_cast<long>(Ai[e]);
        if (r < n)
          E_(r, c - n) = values[e];
        else
          G_(r - n, c - n) = values[e];
      }
    for (int j = 0; j < nb_; ++j) {
      Panel& P = panels_[j];
      if (!eliminate(P, lower_[j], pivots_[j])) return false;
      if (j + 1 < nb_)  // the carried rows
        panels_[j + 1].template topLeftCorner<T, B>() = P.template bottomRightCorner<T, B>();
    }
    if (m_) {
      if (!well_conditioned(false)) return false;
      W_ = E_;
      for (int i = 0; i < m_; ++i) solve_blocks(W_.col(i).data());
      BorderMatrix S = G_;
      S.noalias() -= F_.lazyProduct(W_);
      schur_.compute(S);
      if (!well_conditioned(true)) return false;
    }
    return factored_ = true;
  }

  bool factored() const { return factored_; }

  /// U's diagonal entry i (the i-th pivot), after factor(): the tests compare it with dense
  /// partial pivoting's.
  double pivot(int i) const { return panels_[i / B](i % B, i % B); }

  /// Solves A x = b in place (x holds b on entry). Needs factor().
  void solve(double* x) const {
    solve_blocks(x);  // x1 = A^-1 b1
    if (!m_) return;
    const long n = B * nb_;
    Eigen::Map<Eigen::VectorXd> x1(x, n), x2(x + n, m_);
    BorderVector rhs = x2;
    rhs.noalias() -= F_.lazyProduct(x1);
    const BorderVector border = schur_.solve(rhs);
    x2 = border;
    x1.noalias() -= W_.lazyProduct(border);
  }

 private:
  /// Solves A x1 = b1 in place for the blocks' part (x holds b1 on entry).
  void solve_blocks(double* x) const {
    using Vec = Eigen::Matrix<double, R, 1>;
    using Block = Eigen::Matrix<double, B, 1>;
    Vec v;
    Eigen::Matrix<double, T, 1> carry = Eigen::Map<const Eigen::Matrix<double, T, 1>>(x);
    for (int j = 0; j < nb_; ++j) {  // forward: the row interchanges and L, panel by panel
      double* rows = x + T + static_cast<std::ptrdiff_t>(B) * j;
      v.template head<T>() = carry;
      if (j + 1 < nb_) {
        v.template tail<B>() = Eigen::Map<const Block>(rows);
      } else {
        v.template segment<B - T>(T) = Eigen::Map<const Eigen::Matrix<double, B - T, 1>>(rows);
        v.template tail<T>().setZero();
      }
      const Pivots& p = pivots_[j];
      for (int k = 0; k < B; ++k) std::swap(v[k], v[p[k]]);
      const Lower& L = lower_[j];
      for (int k = 0; k < B; ++k) v -= v[k] * L.col(k);
      // y_j overwrites rows already read: [B j, B j + B) lies below T + B j + B.
      Eigen::Map<Block>(x + static_cast<std::ptrdiff_t>(B) * j) = v.template head<B>();
      carry = v.template tail<T>();
    }
    Block next = Block::Zero();  // backward: x_j = U_jj^-1 (y_j - U_j,j+1 x_j+1)
    for (int j = nb_ - 1; j >= 0; --j) {
      Eigen::Map<Block> y(x + static_cast<std::ptrdiff_t>(B) * j);
      const Panel& P = panels_[j];
      if (j + 1 < nb_) y.noalias() -= P.template topRightCorner<B, B>() * next;
      P.template topLeftCorner<B, B>().template triangularView<Eigen::Upper>().solveInPlace(y);
      next = y;
    }
  }

  /// KLU's test (SUNLinSol_KLU, kept_klu_solver) on the factors' pivots |U_ii|: min / max >=
  /// eps^(2/3). `schur`: S's pivots, else A's.
  bool well_conditioned(bool schur) const {
    double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
    const int count = schur ? m_ : B * nb_;
    for (int i = 0; i < count; ++i) {
      const double u = std::abs(schur ? schur_.matrixLU()(i, i) : pivot(i));
      smallest = std::min(smallest, u);
      largest = std::max(largest, u);
    }
    const double eps = std::numeric_limits<double>::epsilon();
    return smallest >= std::cbrt(eps * eps) * largest;
  }

  /// The panel that holds row r: 0 for A_top, interval i's for its rows, the last for A_bot.
  long panel_of(long r) const { return r < T ? 0 : std::min<long>((r - T) / B, nb_ - 1); }

  /// Whether entry (r, c) lies in the staircase: on its panel's block, or an interval row on the
  /// next block.
  bool in_staircase(long r, int c) const {
    if (r < 0 || r >= B * nb_) return false;
    const long p = panel_of(r), j = c / B;
    return j == p || (r >= T && r < T + static_cast<long>(B) * (nb_ - 1) && j == p + 1);
  }

  /// Zeroes panel j's positions that neither the values nor the elimination write: all of them
  /// unless the pattern covers every position the values own (kinsol's does), else the
  /// carried rows' right half (the first panel's whole top is A_top's), and the last panel's
  /// rows and columns past B.
  void clear_unowned(int j) {
    Panel& P = panels_[j];
    if (!dense_) {
      P.setZero();
      return;
    }
    P.template topRightCorner<T, B>().setZero();
    if (j + 1 == nb_) {
      P.template rightCols<B>().setZero();
      P.template bottomRows<T>().setZero();
    }
  }

  /// Partial-pivoting elimination of P's first B columns (LAPACK's dgetf2 on a tall panel):
  /// the multipliers into L (zero on and above the diagonal), the interchanges into p.
  static bool eliminate(Panel& P, Lower& L, Pivots& p) {
    L.setZero();
    for (int k = 0; k < B; ++k) {
      const int best = pivot_row(P, k, R);
      const double largest = std::abs(P(best, k));
      if (!(largest > 0.0) || !std::isfinite(largest)) return false;
      p[k] = best;
      if (best != k) {
        P.row(k).swap(P.row(best));
        L.row(k).swap(L.row(best));
      }
      const double inverse = 1.0 / P(k, k);
      for (int r = k + 1; r < R; ++r) {
        const double m = P(r, k) * inverse;
        L(r, k) = m;
        P.row(r) -= m * P.row(k);  // the whole row: P(k, c < k) = 0
        P(r, k) = 0.0;
      }
    }
    return true;
  }

  int nb_, m_;
  bool dense_ = false;
  bool factored_ = false;
  std::vector<Panel> panels_;  // after factor(): U's block row on top, the carried rows below
  std::vector<Lower> lower_;
  std::vector<Pivots> pivots_;
  Eigen::MatrixXd E_, F_, W_;  // the border: E = A's border columns, F its rows, W = A^-1 E
  BorderMatrix G_;
  Eigen::PartialPivLU<BorderMatrix> schur_;
};

}  // namespace rodlab::solvers
