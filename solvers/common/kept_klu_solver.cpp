#include "kept_klu_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <type_traits>
#include <vector>

#include <klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

namespace rodlab::solvers::sundials {
namespace {

static_assert(std::is_same_v<sunindextype, SuiteSparse_long>,
              "the kept KLU solver needs SUNDIALS built with 64-bit indices (klu_l_*)");

struct Content {
  long n = 0;
  klu_l_common common{};
  klu_l_symbolic* symbolic = nullptr;
  klu_l_numeric* numeric = nullptr;
  std::vector<double> factorised;  ///< the values of the last factorised matrix
  int last_flag = SUNLS_SUCCESS;
  KeptKluCounts counts;
};

Content& content(SUNLinearSolver S) { return *static_cast<Content*>(S->content); }

SUNLinearSolver_Type get_type(SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; }
SUNLinearSolver_ID get_id(SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; }

/// KINSOL calls this at the start of every KINSol: the analysis and factors are kept.
int initialize(SUNLinearSolver S) { return content(S).last_flag = SUNLS_SUCCESS; }

/// A fresh numeric factorisation (new pivots) of the values in A.
bool factor(Content& c, sunindextype* Ap, sunindextype* Ai, double* Ax) {
  if (c.numeric) klu_l_free_numeric(&c.numeric, &c.common);
  c.numeric = klu_l_factor(Ap, Ai, Ax, c.symbolic, &c.common);
  ++c.counts.factorisations;
  return c.numeric != nullptr && c.common.status == KLU_OK;
}

int setup(SUNLinearSolver S, SUNMatrix A) {
  Content& c = content(S);
  if (SUNSparseMatrix_SparseType(A) != CSC_MAT || SUNSparseMatrix_Columns(A) != c.n)
    return c.last_flag = SUNLS_ILL_INPUT;
  sunindextype* Ap = SUNSparseMatrix_IndexPointers(A);
  sunindextype* Ai = SUNSparseMatrix_IndexValues(A);
  double* Ax = SUNSparseMatrix_Data(A);
  const auto nnz = static_cast<std::size_t>(Ap[c.n]);
  if (!c.symbolic) {
    c.symbolic = klu_l_analyze(c.n, Ap, Ai, &c.common);
    if (!c.symbolic) return c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  // The matrix factorised last (a Jacobian kept across solves): the factors are still right.
  if (c.numeric && c.factorised.size() == nnz && std::equal(Ax, Ax + nnz, c.factorised.begin())) {
    ++c.counts.skipped;
    return c.last_flag = SUNLS_SUCCESS;
  }
  bool ok = false;
  if (c.numeric) {
    ok = klu_l_refactor(Ap, Ai, Ax, c.symbolic, c.numeric, &c.common) == 1 &&
         c.common.status == KLU_OK;
    ++c.counts.refactorisations;
    // The kept pivot order may be poor for the new values (SUNLinSol_KLU's test).
    static const double threshold = std::pow(std::numeric_limits<double>::epsilon(), 2.0 / 3.0);
    if (ok) ok = klu_l_rcond(c.symbolic, c.numeric, &c.common) == 1 && c.common.rcond >= threshold;
  }
  if (!ok) ok = factor(c, Ap, Ai, Ax);
  if (!ok) {
    c.factorised.clear();
    // A singular matrix is recoverable (KINSOL may retry with a new Jacobian).
    return c.last_flag = c.common.status == KLU_SINGULAR ? SUNLS_PACKAGE_FAIL_REC
                                                        : SUNLS_PACKAGE_FAIL_UNREC;
  }
  c.factorised.assign(Ax, Ax + nnz);
  return c.last_flag = SUNLS_SUCCESS;
}

int solve(SUNLinearSolver S, SUNMatrix, N_Vector x, N_Vector b, double) {
  Content& c = content(S);
  if (!c.symbolic || !c.numeric) return c.last_flag = SUNLS_MEM_NULL;
  N_VScale(1.0, b, x);
  const int ok = klu_l_solve(c.symbolic, c.numeric, c.n, 1, N_VGetArrayPointer(x), &c.common);
  return c.last_flag = ok == 1 ? SUNLS_SUCCESS : SUNLS_PACKAGE_FAIL_REC;
}

sunindextype last_flag(SUNLinearSolver S) { return content(S).last_flag; }

int free_solver(SUNLinearSolver S) {
  if (!S) return SUNLS_SUCCESS;
  if (S->content) {
    Content& c = content(S);
    if (c.numeric) klu_l_free_numeric(&c.numeric, &c.common);
    if (c.symbolic) klu_l_free_symbolic(&c.symbolic, &c.common);
    delete &c;
    S->content = nullptr;
  }
  SUNLinSolFreeEmpty(S);
  return SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver make_kept_klu_solver(long n, SUNContext ctx) {
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  auto* c = new (std::nothrow) Content;
  if (!c) {
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  c->n = n;
  klu_l_defaults(&c->common);
  S->content = c;
  S->ops->gettype = get_type;
  S->ops->getid = get_id;
  S->ops->initialize = initialize;
  S->ops->setup = setup;
  S->ops->solve = solve;
  S->ops->lastflag = last_flag;
  S->ops->free = free_solver;
  return S;
}

KeptKluCounts kept_klu_counts(SUNLinearSolver S) { return content(S).counts; }

}  // namespace rodlab::solvers::sundials
