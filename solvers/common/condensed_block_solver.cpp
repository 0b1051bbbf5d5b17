#include "condensed_block_solver.hpp"

#include <new>
#include <stdexcept>

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "condensed_block_lu.hpp"
#include "direct_solver_shell.hpp"
#include "kept_klu_solver.hpp"

namespace rodlab::solvers::sundials {
namespace {

using BlockLU = CondensedBlockLU<kCondensedLocal, kCondensedBlock - kCondensedLocal>;

struct Content {
  Content(int blocks, int tail) : lu(blocks, tail) {}
  Content(const Content&) = delete;
  Content& operator=(const Content&) = delete;
  ~Content() { SUNLinSolFree(klu); }
  BlockLU lu;
  SUNLinearSolver klu = nullptr;  ///< the fallback, analysed on first use
  bool use_klu = false;           ///< the last factorisation was KLU's
  bool factored = false;          ///< the factors are valid
  bool keep_factors = true;       ///< across KINSol calls
  int last_flag = SUNLS_SUCCESS;
};

Content& content(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

int initialize(SUNLinearSolver S) {
  Content& c = content(S);
  if (!c.keep_factors) c.factored = false;
  SUNLinSolInitialize(c.klu);
  return c.last_flag = SUNLS_SUCCESS;
}

int setup(SUNLinearSolver S, SUNMatrix A) {
  Content& c = content(S);
  if (SUNSparseMatrix_SparseType(A) != CSC_MAT || SUNSparseMatrix_Columns(A) != c.lu.size())
    return c.last_flag = SUNLS_ILL_INPUT;
  // Every setup factorises: its users call it for new values only (a kept Jacobian's factors
  // are kept by not calling it: KINSetNoInitSetup, collocation's reuse_factorisation).
  c.factored = false;
  c.use_klu = !c.lu.factor(SUNSparseMatrix_Data(A));
  if (c.use_klu) {
    const int flag = SUNLinSolSetup(c.klu, A);
    if (flag != SUNLS_SUCCESS) return c.last_flag = flag;
  }
  c.factored = true;
  return c.last_flag = SUNLS_SUCCESS;
}

int solve(SUNLinearSolver S, SUNMatrix A, N_Vector x, N_Vector b, double tol) {
  Content& c = content(S);
  if (!c.factored) return c.last_flag = SUNLS_MEM_NULL;
  if (c.use_klu) return c.last_flag = SUNLinSolSolve(c.klu, A, x, b, tol);
  N_VScale(1.0, b, x);
  c.lu.solve(N_VGetArrayPointer(x));
  return c.last_flag = SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver make_condensed_block_solver(SUNMatrix pattern, SUNContext ctx, bool keep_factors) {
  const sunindextype n = SUNSparseMatrix_Columns(pattern);
  if (SUNSparseMatrix_SparseType(pattern) != CSC_MAT || n < kCondensedBlock) return nullptr;
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  Content* c = nullptr;
  try {
    c = new Content(static_cast<int>(n / kCondensedBlock), static_cast<int>(n % kCondensedBlock));
    c->keep_factors = keep_factors;
    if (!c->lu.map_pattern(SUNSparseMatrix_IndexPointers(pattern),
                           SUNSparseMatrix_IndexValues(pattern)))
      throw std::invalid_argument("not block tridiagonal");
    c->klu = make_kept_klu_solver(n, ctx, false, keep_factors);
    if (!c->klu) throw std::bad_alloc();
  } catch (...) {
    delete c;
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  install_direct_solver(S, c, {initialize, setup, solve});
  return S;
}

void assign_condensed_block(SUNLinearSolver dst, SUNLinearSolver src) {
  Content& d = content(dst);
  const Content& s = content(src);
  if (&d == &s) return;
  if (d.lu.size() != s.lu.size())
    throw std::invalid_argument("assign_condensed_block: solvers of different sizes");
  d.lu = s.lu;  // vectors of the same sizes: element-wise copies, no allocation
  assign_kept_klu(d.klu, s.klu);
  d.use_klu = s.use_klu;
  d.factored = s.factored;
  d.last_flag = s.last_flag;
}

}  // namespace rodlab::solvers::sundials
