#include "almost_block_diagonal_solver.hpp"

#include <new>
#include <stdexcept>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "almost_block_diagonal_lu.hpp"
#include "direct_solver_shell.hpp"
#include "kept_klu_solver.hpp"

namespace rodlab::solvers::sundials {
namespace {

using BlockLU = AlmostBlockDiagonalLU<kAbdBlock, kAbdTop>;

struct Content {
  Content(int blocks, int border) : lu(blocks, border) {}
  Content(const Content&) = delete;
  Content& operator=(const Content&) = delete;
  ~Content() { SUNLinSolFree(klu); }
  BlockLU lu;
  SUNLinearSolver klu = nullptr;  ///< the fallback for a bordered matrix the LU refuses
  bool use_klu = false;           ///< the last factorisation was KLU's
  bool factored = false;
  int last_flag = SUNLS_SUCCESS;
};

Content& content(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

int initialize(SUNLinearSolver S) {
  Content& c = content(S);
  if (c.klu) SUNLinSolInitialize(c.klu);
  return c.last_flag = SUNLS_SUCCESS;
}

int setup(SUNLinearSolver S, SUNMatrix A) {
  Content& c = content(S);
  if (SUNSparseMatrix_SparseType(A) != CSC_MAT || SUNSparseMatrix_Columns(A) != c.lu.size())
    return c.last_flag = SUNLS_ILL_INPUT;
  c.factored = c.lu.factor(SUNSparseMatrix_IndexPointers(A), SUNSparseMatrix_IndexValues(A),
                           SUNSparseMatrix_Data(A));
  c.use_klu = !c.factored && c.klu;
  if (c.use_klu) {
    const int flag = SUNLinSolSetup(c.klu, A);
    c.factored = flag == SUNLS_SUCCESS;
    return c.last_flag = flag;
  }
  return c.last_flag = c.factored ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
}

int solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, double tol) {
  Content& c = content(S);
  if (!c.factored) return c.last_flag = SUNLS_MEM_NULL;
  if (c.use_klu) return c.last_flag = SUNLinSolSolve(c.klu, A, x, b, tol);
  N_VScale(1.0, b, x);
  c.lu.solve(N_VGetArrayPointer(x));
  return c.last_flag = SUNLS_SUCCESS;
}

/// The border: the trailing columns that hold every row (kinsol's extra unknowns), at most
/// kMaxBorder and leaving a multiple of kAbdBlock.
int border_of(SUNMatrix pattern) {
  const sunindextype n = SUNSparseMatrix_Columns(pattern);
  const sunindextype* Ap = SUNSparseMatrix_IndexPointers(pattern);
  int m = 0;
  while (m < BlockLU::kMaxBorder && m < n && Ap[n - m] - Ap[n - m - 1] == n) ++m;
  return (n - m) % kAbdBlock == 0 ? m : -1;
}

}  // namespace

SUNLinearSolver make_almost_block_diagonal_solver(SUNMatrix pattern, SUNContext ctx) {
  const sunindextype n = SUNSparseMatrix_Columns(pattern);
  if (SUNSparseMatrix_SparseType(pattern) != CSC_MAT || SUNSparseMatrix_Rows(pattern) != n)
    return nullptr;
  const int border = border_of(pattern);
  if (border < 0 || n - border < kAbdBlock) return nullptr;
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  Content* c = nullptr;
  try {
    c = new Content(static_cast<int>((n - border) / kAbdBlock), border);
    if (!c->lu.accept_pattern(SUNSparseMatrix_IndexPointers(pattern),
                              SUNSparseMatrix_IndexValues(pattern)))
      throw std::invalid_argument("not almost block diagonal");
    if (border) {
      c->klu = make_kept_klu_solver(n, ctx, true, false);
      if (!c->klu) throw std::bad_alloc();
    }
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
  if (d.lu.size() != s.lu.size() || d.lu.border() != s.lu.border())
    throw std::invalid_argument("assign_almost_block_diagonal: solvers of different sizes");
  d.lu = s.lu;  // vectors and matrices of the same sizes: element-wise copies, no allocation
  if (d.klu) assign_kept_klu(d.klu, s.klu);
  d.use_klu = s.use_klu;
  d.factored = s.factored;
  d.last_flag = s.last_flag;
}

}  // namespace rodlab::solvers::sundials
