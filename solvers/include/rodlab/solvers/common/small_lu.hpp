#pragma once
// A x = b for a small fixed-size A by Gaussian elimination with partial pivoting (the pivots of
// Eigen's PartialPivLU), in fixed-size row operations. Eigen's PartialPivLU runs its generic
// unblocked kernel with run-time loops for every size: on a 6 x 6 system it took 206 ns per
// solve against 105 ns here (one core, -O2), and the tendon law's 6 x 6 Newton solves
// (tendon_law.hpp) were a quarter of an actuated kinsol solve (bench_statics kinsol_muscle,
// perf). The result agrees with PartialPivLU's to rounding, not bit for bit (another order of
// the same operations). A singular A gives non-finite entries, as PartialPivLU's solve does.
#include <cmath>
#include <utility>

#include <Eigen/Core>

namespace rodlab::solvers {

/// Partial pivoting's choice in column k: the row r in [k, rows) of the largest |A(r, k)|, the
/// first of equals (almost_block_diagonal_lu.hpp's panels use it too).
template <class Matrix>
int pivot_row(const Matrix& A, int k, int rows) {
  int pivot = k;
  double largest = std::abs(A(k, k));
  for (int r = k + 1; r < rows; ++r)
    if (std::abs(A(r, k)) > largest) {
      largest = std::abs(A(r, k));
      pivot = r;
    }
  return pivot;
}

template <int N>
Eigen::Matrix<double, N, 1> solve_partial_pivoting(const Eigen::Matrix<double, N, N>& matrix,
                                                    Eigen::Matrix<double, N, 1> b) {
  Eigen::Matrix<double, N, N, Eigen::RowMajor> A = matrix;
  for (int k = 0; k < N; ++k) {
    const int pivot = pivot_row(A, k, N);
    if (pivot != k) {
      A.row(k).swap(A.row(pivot));
      std::swap(b[k], b[pivot]);
    }
    const double inverse = 1.0 / A(k, k);
    for (int r = k + 1; r < N; ++r) {
      const double m = A(r, k) * inverse;
      A.row(r) -= m * A.row(k);  // the whole row: A(k, c < k) = 0
      b[r] -= m * b[k];
    }
  }
  for (int i = N - 1; i >= 0; --i) {
    double sum = b[i];
    for (int c = i + 1; c < N; ++c) sum -= A(i, c) * b[c];
    b[i] = sum / A(i, i);
  }
  return b;
}

}  // namespace rodlab::solvers
