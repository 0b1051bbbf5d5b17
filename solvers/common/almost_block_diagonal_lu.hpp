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
// A row operation runs over the whole fixed-size 2B-wide panel row (its entries left of the
// pivot column are zero): 2 B^2 (2T + B - 1) flops per block to factorise, 8.8 kflop for
// kinsol's B = 13, T = 7, in vectorised fixed-size loops, and about 4 B (T + B) to solve; a
// sparse LU of the same matrix (KLU) does fewer flops but spends more on its index work (docs/
// statics.md "Cost"). Fixed-size panels: no
// allocation after construction. Private to solvers/common; Eigen only (tests/common
// instantiate it at small sizes).
#include <array>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace rodlab::solvers {

template <int B, int T>
class AlmostBlockDiagonalLU {
  static_assert(0 < T && T < B, "the first block row has T rows, the last B - T");

 public:
  static constexpr int R = T + B;  ///< rows of a panel
  using Panel = Eigen::Matrix<double, R, 2 * B, Eigen::RowMajor>;
  using Lower = Eigen::Matrix<double, R, B>;  ///< a panel's multipliers, zero on and above k = r
  using Pivots = std::array<int, B>;          ///< LAPACK's ipiv: row k swapped with pivots[k]

  /// A solver for `blocks` >= 1 blocks (the matrix is B * blocks square).
  explicit AlmostBlockDiagonalLU(int blocks)
      : nb_(blocks), panels_(blocks, Panel::Zero()), lower_(blocks), pivots_(blocks) {}

  int blocks() const { return nb_; }
  int size() const { return B * nb_; }

  /// Where the entries of a CSC pattern (column pointers Ap, row indices Ai, size() columns) go
  /// in the panels. False, and nothing mapped, if an entry lies outside the staircase above.
  template <class Index>
  bool map_pattern(const Index* Ap, const Index* Ai) {
    const std::size_t nnz = static_cast<std::size_t>(Ap[size()]);
    std::vector<std::size_t> target(nnz);
    for (int c = 0; c < size(); ++c) {
      const int j = c / B, k = c % B;
      for (Index e = Ap[c]; e < Ap[c + 1]; ++e) {
        const long r = static_cast<long>(Ai[e]);
        int panel = 0, row = 0, column = k;
        if (r < 0 || r >= size()) return false;
        if (r < T) {  // A_top
          if (j != 0) return false;
          row = static_cast<int>(r);
        } else if (r < T + static_cast<long>(B) * (nb_ - 1)) {  // interval i's rows
          panel = static_cast<int>((r - T) / B);
          row = T + static_cast<int>((r - T) % B);
          if (j != panel && j != panel + 1) return false;
          column += B * (j - panel);
        } else {  // A_bot
          if (j != nb_ - 1) return false;
          panel = nb_ - 1;
          row = T + static_cast<int>(r - T - static_cast<long>(B) * (nb_ - 1));
        }
        target[static_cast<std::size_t>(e)] =
            static_cast<std::size_t>(panel) * R * 2 * B + static_cast<std::size_t>(row) * 2 * B +
            static_cast<std::size_t>(column);
      }
    }
    const std::size_t dense = static_cast<std::size_t>(B) * (T + 2 * B * (nb_ - 1) + (B - T));
    dense_ = nnz == dense;  // then every position the values own is in the pattern
    target_ = std::move(target);
    return true;
  }

  /// Factorises the matrix with the mapped pattern's values (CSC order). False for a singular
  /// matrix (a pivot column without a non-zero) or an infinite pivot.
  bool factor(const double* values) {
    factored_ = false;
    for (int j = 0; j < nb_; ++j) clear_unowned(j);
    double* base = panels_.front().data();
    for (std::size_t e = 0; e < target_.size(); ++e) base[target_[e]] = values[e];
    for (int j = 0; j < nb_; ++j) {
      Panel& P = panels_[j];
      if (!eliminate(P, lower_[j], pivots_[j])) return false;
      if (j + 1 < nb_) panels_[j + 1].template topLeftCorner<T, B>() = P.template bottomRightCorner<T, B>();
    }
    return factored_ = true;
  }

  bool factored() const { return factored_; }

  /// U's diagonal entry i (the i-th pivot), after factor(): the tests compare it with dense
  /// partial pivoting's.
  double pivot(int i) const { return panels_[i / B](i % B, i % B); }

  /// Solves A x = b in place (x holds b on entry). Needs factor().
  void solve(double* x) const {
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

 private:
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
      int best = k;
      double largest = std::abs(P(k, k));
      for (int r = k + 1; r < R; ++r)
        if (std::abs(P(r, k)) > largest) {
          largest = std::abs(P(r, k));
          best = r;
        }
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

  int nb_;
  bool dense_ = false;
  bool factored_ = false;
  std::vector<std::size_t> target_;  // a pattern entry's offset in panels_' doubles
  std::vector<Panel> panels_;        // after factor(): U's block rows on top, the rest zero
  std::vector<Lower> lower_;
  std::vector<Pivots> pivots_;
};

}  // namespace rodlab::solvers
