#include "almost_block_diagonal_solver.hpp"

#include <memory>
#include <new>
#include <stdexcept>

#include <sunmatrix/sunmatrix_sparse.h>

#include "almost_block_diagonal_lu.hpp"
#include "fallback_solver_shell.hpp"

namespace rodlab::solvers::sundials {
namespace {

struct BlockLU : AlmostBlockDiagonalLU<kAbdBlock, kAbdTop> {
  using AlmostBlockDiagonalLU::AlmostBlockDiagonalLU;
  bool factor(SUNMatrix A) {
    return AlmostBlockDiagonalLU::factor(SUNSparseMatrix_IndexPointers(A),
                                         SUNSparseMatrix_IndexValues(A), SUNSparseMatrix_Data(A));
  }
};

/// The border: the trailing columns that hold every row (kinsol's extra unknowns), at most
/// kMaxBorder and leaving a multiple of kAbdBlock; -1 if none such.
int border_of(SUNMatrix pattern) {
  const sunindextype n = SUNSparseMatrix_Columns(pattern);
  const sunindextype* Ap = SUNSparseMatrix_IndexPointers(pattern);
  int m = 0;
  while (m < BlockLU::kMaxBorder && m < n && Ap[n - m] - Ap[n - m - 1] == n) ++m;
  return (n - m) % kAbdBlock == 0 ? m : -1;
}

}  // namespace

SUNLinearSolver make_almost_block_diagonal_solver(SUNMatrix pattern, SUNContext ctx,
                                                  bool natural_order, bool keep_factors) {
  const sunindextype n = SUNSparseMatrix_Columns(pattern);
  if (SUNSparseMatrix_SparseType(pattern) != CSC_MAT || SUNSparseMatrix_Rows(pattern) != n)
    return nullptr;
  const int border = border_of(pattern);
  if (border < 0 || n - border < kAbdBlock) return nullptr;
  return make_fallback_solver<BlockLU>(ctx, [&] {
    auto c = std::make_unique<FallbackContent<BlockLU>>(
        static_cast<int>((n - border) / kAbdBlock), border);
    c->keep_factors = keep_factors;
    if (!c->lu.accept_pattern(SUNSparseMatrix_IndexPointers(pattern),
                              SUNSparseMatrix_IndexValues(pattern)))
      throw std::invalid_argument("not almost block diagonal");
    if (border) {  // the block LU of a border can be unstable where the whole matrix is not
      c->klu = make_kept_klu_solver(n, ctx, natural_order, keep_factors);
      if (!c->klu) throw std::bad_alloc();
    }
    return c;
  });
}

void assign_almost_block_diagonal(SUNLinearSolver dst, SUNLinearSolver src) {
  fallback_content<BlockLU>(dst).assign(fallback_content<BlockLU>(src));
}

}  // namespace rodlab::solvers::sundials
