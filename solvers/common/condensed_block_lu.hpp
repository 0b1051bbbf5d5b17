#pragma once
// LU of a block-tridiagonal matrix whose blocks of B = L + C unknowns have L "local" rows: rows
// whose entries all lie in their own block's columns. The semi-discrete rod's Newton matrix
// a I - df/dy is one (semi_discrete_rod.hpp): a node's 7 pose rows, a z_p - R kappa and
// a z_q - q (x) [0; psi] / 2, involve its own q and eta alone; its 6 velocity rows see the
// neighbours through the segments' strains. Written per block k, unknowns u_k = [l_k; c_k]:
//
//     P_k l_k + Q_k c_k                                          = r_k    (local rows)
//     sum_(j = k-1..k+1) (E_kj l_j + F_kj c_j)                   = s_k    (coupled rows)
//
// The local rows give l_k = P_k^-1 (r_k - Q_k c_k) block by block (static condensation), which
// leaves the C x C block-tridiagonal Schur system
//
//     sum_j S_kj c_j = s_k - sum_j E_kj P_j^-1 r_j,    S_kj = F_kj - E_kj W_j,  W_j = P_j^-1 Q_j,
//
// solved by block LU without pivoting across blocks (the block Thomas algorithm):
// D_k = S_kk - S_k,k-1 X_(k-1), X_k = D_k^-1 S_k,k+1. P_k^-1 and D_k^-1 are kept as matrices
// (each from a partial-pivoting LU), so that a solve is fixed-size matrix-vector products (a
// solve through Eigen's fixed-size LU objects runs its generic triangular kernels: the
// collocation step at N = 20 was 5 % slower). For the rod (B = 13 = 7 + 6) that is 6 x 6 pivots
// where a sparse LU of the whole matrix works with 13-wide bands: about 3 kflop per node to
// factorise and 0.5 kflop to solve.
//
// A border of `tail` rows and columns may follow the blocks: rows that see any block column
// (dense) and, among the tail columns, only those up to their own (lower triangular), while the
// tail columns appear in no block row. That is `ida`'s Newton matrix with its ledger rows:
// D' = P_diss(y) and W' = P_in(y) depend on every node, nothing depends on D or W. The tail
// unknowns follow by forward substitution once the blocks are solved.
//
// Block elimination without pivoting across blocks is stable where the Schur system is block
// diagonally dominant or close to symmetric positive definite (the rod's (2/dt)^2 M + K +
// (2/dt) V, scaled by M^-1); factor() refuses a matrix whose pivot blocks look ill-conditioned
// (KLU's estimate min |U_ii| / max |U_ii| below eps^(2/3), the test of SUNLinSol_KLU and
// kept_klu_solver), and the caller
// falls back to a general sparse LU (condensed_block_solver.cpp). Fixed-size blocks: no
// allocation after construction. Private to solvers/common; Eigen only (tests/common
// instantiate it at small sizes).
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

namespace rodlab::solvers {

template <int L, int C>
class CondensedBlockLU {
 public:
  static constexpr int B = L + C;
  using Block = Eigen::Matrix<double, B, B>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1>;

  /// A solver for `blocks` blocks and `tail` bordering rows and columns (the matrix is
  /// B * blocks + tail square).
  explicit CondensedBlockLU(int blocks, int tail = 0)
      : nb_(blocks),
        tail_(tail),
        border_(static_cast<std::size_t>(tail) * (B * blocks + tail), 0.0),
        band_(3 * static_cast<std::size_t>(blocks), Block::Zero()),
        local_inverse_(blocks),
        pivot_inverse_(blocks),
        W_(blocks),
        X_(blocks),
        lower_(blocks),
        v_(blocks) {}

  int blocks() const { return nb_; }
  int size() const { return B * nb_ + tail_; }

  /// Where the entries of a CSC pattern (column pointers Ap, row indices Ai, size() columns)
  /// go. False, and nothing mapped, if a block row's entry lies outside the tridiagonal band of
  /// blocks. Entries that the values must leave zero are allowed in the pattern (a pattern may
  /// be structurally wider than the values): local rows outside their own block, tail columns
  /// in block rows, tail rows above the diagonal among the tail columns; factor() checks them.
  template <class Index>
  bool map_pattern(const Index* Ap, const Index* Ai) {
    const Index n_blocks = B * nb_;
    std::vector<std::size_t> target;
    std::vector<std::size_t> must_be_zero;
    for (Index col = 0; col < size(); ++col)
      for (Index e = Ap[col]; e < Ap[col + 1]; ++e) {
        const Index row = Ai[e];
        if (row < 0 || row >= size()) return false;
        if (row >= n_blocks || col >= n_blocks) {  // the border: row-major rows of size()
          const bool zero = row < n_blocks || col > row;
          target.push_back(zero ? kNowhere
                                : kBorder + static_cast<std::size_t>(row - n_blocks) * size() +
                                      static_cast<std::size_t>(col));
          if (zero) must_be_zero.push_back(static_cast<std::size_t>(e));
          continue;
        }
        // 0, 1, 2: the block left of, on, right of the diagonal
        const Index off = col / B - row / B + 1;
        if (off < 0 || off > 2) return false;
        target.push_back(((static_cast<std::size_t>(row / B) * 3 + off) * B + col % B) * B +
                         row % B);
        if (row % B < L && off != 1) must_be_zero.push_back(static_cast<std::size_t>(e));
      }
    target_.swap(target);
    must_be_zero_.swap(must_be_zero);
    return true;
  }

  /// Factorises the matrix with the mapped pattern's values Ax. False (the factors unusable)
  /// when a local row has a non-zero outside its block or a pivot block is ill-conditioned.
  bool factor(const double* Ax) {
    for (const std::size_t e : must_be_zero_)
      if (Ax[e] != 0.0) return false;
    double* band = band_.data()->data();
    for (std::size_t e = 0; e < target_.size(); ++e) {
      const std::size_t t = target_[e];
      if (t < kBorder)
        band[t] = Ax[e];
      else if (t != kNowhere)
        border_[t - kBorder] = Ax[e];
    }
    for (int r = 0; r < tail_; ++r)  // the border's diagonal
      if (!(std::abs(border(r, B * nb_ + r)) > 0.0) || !std::isfinite(border(r, B * nb_ + r)))
        return false;
    for (int k = 0; k < nb_; ++k) {
      const Eigen::PartialPivLU<Eigen::Matrix<double, L, L>> lu(
          block(k, k).template topLeftCorner<L, L>());
      if (!well_conditioned(lu)) return false;
      local_inverse_[k] = lu.inverse();
      W_[k].noalias() = local_inverse_[k] * block(k, k).template topRightCorner<L, C>();
    }
    for (int k = 0; k < nb_; ++k) {
      Eigen::Matrix<double, C, C> D = schur(k, k);
      if (k > 0) {
        lower_[k] = schur(k, k - 1);
        D.noalias() -= lower_[k] * X_[k - 1];
      }
      const Eigen::PartialPivLU<Eigen::Matrix<double, C, C>> lu(D);
      if (!well_conditioned(lu)) return false;
      pivot_inverse_[k] = lu.inverse();
      if (k + 1 < nb_) X_[k].noalias() = pivot_inverse_[k] * schur(k, k + 1);
    }
    return true;
  }

  /// x := A^-1 x with the factors of the last successful factor().
  void solve(double* x_data) {
    Eigen::Map<Vector> x(x_data, size());
    for (int k = 0; k < nb_; ++k) v_[k].noalias() = local_inverse_[k] * x.template segment<L>(B * k);
    for (int k = 0; k < nb_; ++k) {  // forward: D_k y_k = s_k - E v - S_k,k-1 y_(k-1)
      Eigen::Matrix<double, C, 1> s = x.template segment<C>(B * k + L);
      for (int j = std::max(0, k - 1); j <= std::min(nb_ - 1, k + 1); ++j)
        s.noalias() -= block(k, j).template bottomLeftCorner<C, L>() * v_[j];
      if (k > 0) s.noalias() -= lower_[k] * x.template segment<C>(B * (k - 1) + L);
      x.template segment<C>(B * k + L).noalias() = pivot_inverse_[k] * s;
    }
    for (int k = nb_ - 2; k >= 0; --k)  // backward: c_k = y_k - X_k c_(k+1)
      x.template segment<C>(B * k + L).noalias() -= X_[k] * x.template segment<C>(B * (k + 1) + L);
    for (int k = 0; k < nb_; ++k)  // the local unknowns: l_k = P_k^-1 r_k - W_k c_k
      x.template segment<L>(B * k).noalias() = v_[k] - W_[k] * x.template segment<C>(B * k + L);
    for (int r = 0; r < tail_; ++r) {  // the border, by forward substitution
      const int row = B * nb_ + r;
      const Eigen::Map<const Vector> coefficients(&border_[static_cast<std::size_t>(r) * size()],
                                                  row);
      x[row] = (x[row] - coefficients.dot(x.head(row))) / border(r, row);
    }
  }

 private:
  static constexpr std::size_t kNowhere = static_cast<std::size_t>(-1);  ///< a zero entry
  static constexpr std::size_t kBorder = kNowhere / 2;  ///< targets from here on: the border

  double border(int r, int col) const {
    return border_[static_cast<std::size_t>(r) * size() + col];
  }

  /// KLU's cheap reciprocal condition estimate, min |U_ii| / max |U_ii| (klu_rcond), at least
  /// eps^(2/3) (SUNLinSol_KLU's threshold); false for non-finite pivots.
  template <class LU>
  static bool well_conditioned(const LU& lu) {
    static const double threshold = std::pow(std::numeric_limits<double>::epsilon(), 2.0 / 3.0);
    const auto pivots = lu.matrixLU().diagonal().cwiseAbs();
    return pivots.allFinite() && pivots.minCoeff() >= threshold * pivots.maxCoeff();
  }

  /// The block of rows of block k and columns of block j (|j - k| <= 1).
  const Block& block(int k, int j) const {
    return band_[3 * static_cast<std::size_t>(k) + (j - k + 1)];
  }

  /// S_kj = F_kj - E_kj W_j.
  Eigen::Matrix<double, C, C> schur(int k, int j) const {
    const Block& A = block(k, j);
    Eigen::Matrix<double, C, C> S = A.template bottomRightCorner<C, C>();
    S.noalias() -= A.template bottomLeftCorner<C, L>() * W_[j];
    return S;
  }

  int nb_ = 0, tail_ = 0;
  std::vector<double> border_;  ///< the tail rows, row-major, size() columns each
  std::vector<Block> band_;     ///< blocks (k, k-1), (k, k), (k, k+1) of every k
  std::vector<std::size_t> target_;        ///< per pattern entry: its place (band_, border_)
  std::vector<std::size_t> must_be_zero_;  ///< entries the values must leave zero (map_pattern)
  std::vector<Eigen::Matrix<double, L, L>> local_inverse_;  ///< P_k^-1
  std::vector<Eigen::Matrix<double, C, C>> pivot_inverse_;  ///< D_k^-1
  std::vector<Eigen::Matrix<double, L, C>> W_;      ///< P_k^-1 Q_k
  std::vector<Eigen::Matrix<double, C, C>> X_;      ///< D_k^-1 S_k,k+1
  std::vector<Eigen::Matrix<double, C, C>> lower_;  ///< S_k,k-1
  std::vector<Eigen::Matrix<double, L, 1>> v_;      ///< solve(): P_k^-1 r_k
};

}  // namespace rodlab::solvers
