#pragma once
// A block-tridiagonal linear system with fixed-size B x B blocks, factorised once and solved
// many times by the block Thomas algorithm (block LU without pivoting between blocks; each
// diagonal block of the factor is inverted by Eigen's fixed-size inverse). Storage is allocated
// by resize() and never afterwards: factor() and solve() allocate nothing.
//
//   Lo[k] x[k-1] + Di[k] x[k] + Up[k] x[k+1] = b[k],  k = 0..m-1  (Lo[0], Up[m-1] unused)
//
// Block elimination without pivoting is stable for block diagonally dominant matrices and, more
// generally, when the Schur complements stay well conditioned; factor() reports a singular or
// non-finite pivot block.
#include <cmath>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

namespace rodlab::solvers {

template <int B>
class BlockTridiagonal {
 public:
  using Block = Eigen::Matrix<double, B, B>;
  using Vector = Eigen::Matrix<double, B, 1>;

  void resize(int m) {
    Lo.assign(m, Block::Zero());
    Di.assign(m, Block::Zero());
    Up.assign(m, Block::Zero());
    pivot_inv_.assign(m, Block::Zero());
  }
  int size() const { return static_cast<int>(Di.size()); }

  /// Forward elimination of the matrix: the inverses of the Schur-complement pivots. Returns
  /// false for a singular or non-finite pivot.
  bool factor() {
    const int m = size();
    for (int k = 0; k < m; ++k) {
      Block pivot = Di[k];
      if (k > 0) pivot -= Lo[k] * pivot_inv_[k - 1] * Up[k - 1];
      bool invertible = false;
      double det = 0.0;
      pivot.computeInverseAndDetWithCheck(pivot_inv_[k], det, invertible, 0.0);
      if (!invertible || !pivot_inv_[k].allFinite()) return false;
    }
    return true;
  }

  /// Solves in place: b holds the right-hand side on entry, the solution on exit.
  void solve(std::vector<Vector>& b) const {
    const int m = size();
    for (int k = 1; k < m; ++k) b[k] -= Lo[k] * (pivot_inv_[k - 1] * b[k - 1]);
    b[m - 1] = pivot_inv_[m - 1] * b[m - 1];
    for (int k = m - 2; k >= 0; --k) b[k] = pivot_inv_[k] * (b[k] - Up[k] * b[k + 1]);
  }

  std::vector<Block> Lo, Di, Up;

 private:
  std::vector<Block> pivot_inv_;
};

}  // namespace rodlab::solvers
