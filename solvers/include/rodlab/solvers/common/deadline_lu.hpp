#pragma once
// Eigen's dense LU with partial pivoting, in place, that polls the run's wall-time guard
// (deadline.hpp) between its column blocks. Eigen::PartialPivLU cannot be interrupted: at
// chebyshev N = 1000 the LU of the reduced Newton matrix (6000 x 6000) is about 8 s of an 11 s
// factorisation, and `rodlab static` with `--max-wall-time` 1, 3 or 5 s stopped after 11.0-11.1 s.
// Here the factorisation is Eigen's own blocked right-looking algorithm (Eigen 3.4,
// Eigen/src/LU/PartialPivLU.h, partial_lu_impl::blocked_lu): the same block size, each panel
// factorised by Eigen's kernel (internal::partial_lu_impl, as PartialPivLU's top level calls it),
// the same row swaps, triangular solve and product. So the factors, the permutation and every
// solve are PartialPivLU's bit for bit (tests/common/test_deadline_lu.cpp), and the deadline is
// checked before each block: with the checks between the Newton matrix's stages
// (chebyshev_newton_matrix.cpp), the same runs stop 0.13-0.75 s after limits of 1-8 s.
#include <algorithm>

#include <Eigen/Core>
#include <Eigen/LU>

#include "rodlab/solvers/common/deadline.hpp"

namespace rodlab::solvers {

class DeadlineLu {
 public:
  /// Factorises the square matrix `a` in place (it holds L and U afterwards, as PartialPivLU's
  /// matrixLU()). The solves read a's storage, as PartialPivLU<Ref<MatrixXd>> does: it must not
  /// be resized or freed while they are used, and moving the matrix (its buffer goes along: the
  /// chebyshev Collocation that holds it is moved into ChebyshevTracker) keeps them valid.
  /// Throws WallTimeExceeded between blocks once the thread's deadline has passed (then `a` is
  /// partly factorised and must not be solved with).
  void compute(Eigen::MatrixXd& a) {
    data_ = a.data();
    n_ = a.rows();
    const Eigen::Index n = n_;
    transpositions_.resize(n);
    using Panel = Eigen::internal::partial_lu_impl<double, Eigen::ColMajor, int>;
    int* piv = transpositions_.indices().data();
    int swaps = 0;
    check_deadline();
    if (n <= Panel::UnBlockedBound) {  // unblocked in one piece, as blocked_lu does
      Panel::blocked_lu(n, n, a.data(), a.outerStride(), piv, swaps);
      permutation_ = transpositions_;
      return;
    }
    // Eigen's top-level block size (blocked_lu): n / 8 rounded down to a multiple of 16, in
    // [8, 256].
    const Eigen::Index block = std::clamp<Eigen::Index>(n / 8 / 16 * 16, 8, 256);
    for (Eigen::Index k = 0; k < n; k += block) {
      if (k > 0) check_deadline();
      const Eigen::Index bs = std::min(n - k, block), trailing = n - k - bs;
      Panel::blocked_lu(n - k, bs, &a.coeffRef(k, k), a.outerStride(), piv + k, swaps, 16);
      auto left = a.leftCols(k);
      for (Eigen::Index i = k; i < k + bs; ++i) {
        piv[i] += static_cast<int>(k);
        left.row(i).swap(left.row(piv[i]));
      }
      if (trailing == 0) continue;
      auto right = a.rightCols(trailing);
      for (Eigen::Index i = k; i < k + bs; ++i) right.row(i).swap(right.row(piv[i]));
      auto A12 = a.block(k, k + bs, bs, trailing);
      a.block(k, k, bs, bs).triangularView<Eigen::UnitLower>().solveInPlace(A12);
      a.block(k + bs, k + bs, trailing, trailing).noalias() -=
          a.block(k + bs, k, trailing, bs) * A12;
    }
    permutation_ = transpositions_;
  }

  /// L (unit lower, below the diagonal) and U, in the factorised matrix.
  Eigen::Map<const Eigen::MatrixXd> matrixLU() const { return {data_, n_, n_}; }
  const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>& permutationP() const {
    return permutation_;
  }

  /// x = A^-1 b, as PartialPivLU::solve: P b, then L and U by substitution.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x.noalias() = permutation_ * b;
    matrixLU().triangularView<Eigen::UnitLower>().solveInPlace(x);
    matrixLU().triangularView<Eigen::Upper>().solveInPlace(x);
  }

 private:
  const double* data_ = nullptr;  ///< the factorised matrix's storage (column major, n_ x n_)
  Eigen::Index n_ = 0;
  Eigen::Transpositions<Eigen::Dynamic, Eigen::Dynamic, int> transpositions_;
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> permutation_;
};

}  // namespace rodlab::solvers
