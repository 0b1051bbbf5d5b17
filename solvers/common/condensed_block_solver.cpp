#include "condensed_block_solver.hpp"

#include <memory>
#include <new>
#include <stdexcept>

#include <sunmatrix/sunmatrix_sparse.h>

#include "condensed_block_lu.hpp"
#include "fallback_solver_shell.hpp"

namespace rodlab::solvers::sundials {
namespace {

struct BlockLU : CondensedBlockLU<kCondensedLocal, kCondensedBlock - kCondensedLocal> {
  using CondensedBlockLU::CondensedBlockLU;
  bool factor(SUNMatrix A) { return CondensedBlockLU::factor(SUNSparseMatrix_Data(A)); }
};

}  // namespace

SUNLinearSolver make_condensed_block_solver(SUNMatrix pattern, SUNContext ctx, bool keep_factors) {
  const sunindextype n = SUNSparseMatrix_Columns(pattern);
  if (SUNSparseMatrix_SparseType(pattern) != CSC_MAT || n < kCondensedBlock) return nullptr;
  return make_fallback_solver<BlockLU>(ctx, [&] {
    auto c = std::make_unique<FallbackContent<BlockLU>>(static_cast<int>(n / kCondensedBlock),
                                                        static_cast<int>(n % kCondensedBlock));
    c->keep_factors = keep_factors;
    if (!c->lu.map_pattern(SUNSparseMatrix_IndexPointers(pattern),
                           SUNSparseMatrix_IndexValues(pattern)))
      throw std::invalid_argument("not block tridiagonal");
    c->klu = make_kept_klu_solver(n, ctx, false, keep_factors);
    if (!c->klu) throw std::bad_alloc();
    return c;
  });
}

void assign_condensed_block(SUNLinearSolver dst, SUNLinearSolver src) {
  fallback_content<BlockLU>(dst).assign(fallback_content<BlockLU>(src));
}

}  // namespace rodlab::solvers::sundials
