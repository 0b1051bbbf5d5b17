#include "almost_block_diagonal_solver.hpp"

#include <new>
#include <stdexcept>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "almost_block_diagonal_lu.hpp"
#include "direct_solver_shell.hpp"

namespace rodlab::solvers::sundials {
namespace {

using BlockLU = AlmostBlockDiagonalLU<kAbdBlock, kAbdTop>;

struct Content {
  explicit Content(int blocks) : lu(blocks) {}
  BlockLU lu;
  int last_flag = SUNLS_SUCCESS;
};

Content& content(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

int initialize(SUNLinearSolver S) { return content(S).last_flag = SUNLS_SUCCESS; }

int setup(SUNLinearSolver S, SUNMatrix A) {
  Content& c = content(S);
  if (SUNSparseMatrix_SparseType(A) != CSC_MAT || SUNSparseMatrix_Columns(A) != c.lu.size())
    return c.last_flag = SUNLS_ILL_INPUT;
  return c.last_flag = c.lu.factor(SUNSparseMatrix_Data(A)) ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, double) {
  Content& c = content(S);
  if (!c.lu.factored()) return c.last_flag = SUNLS_MEM_NULL;
  N_VScale(1.0, b, x);
  c.lu.solve(N_VGetArrayPointer(x));
  return c.last_flag = SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver make_almost_block_diagonal_solver(SUNMatrix pattern, SUNContext ctx) {
  const sunindextype n = SUNSparseMatrix_Columns(pattern);
  if (SUNSparseMatrix_SparseType(pattern) != CSC_MAT || n < kAbdBlock || n % kAbdBlock != 0 ||
      SUNSparseMatrix_Rows(pattern) != n)
    return nullptr;
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  Content* c = nullptr;
  try {
    c = new Content(static_cast<int>(n / kAbdBlock));
    if (!c->lu.map_pattern(SUNSparseMatrix_IndexPointers(pattern),
                           SUNSparseMatrix_IndexValues(pattern)))
      throw std::invalid_argument("not almost block diagonal");
  } catch (...) {
    delete c;
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  install_direct_solver(S, c, {initialize, setup, solve});
  return S;
}

void assign_almost_block_diagonal(SUNLinearSolver dst, SUNLinearSolver src) {
  Content& d = content(dst);
  const Content& s = content(src);
  if (&d == &s) return;
  if (d.lu.size() != s.lu.size())
    throw std::invalid_argument("assign_almost_block_diagonal: solvers of different sizes");
  d.lu = s.lu;  // vectors of the same sizes: element-wise copies, no allocation
  d.last_flag = s.last_flag;
}

}  // namespace rodlab::solvers::sundials
