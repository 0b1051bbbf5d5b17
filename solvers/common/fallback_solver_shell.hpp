#pragma once
// The SUNLinearSolver of a structured LU with a kept KLU solver to fall back on
// (condensed_block_solver.cpp, almost_block_diagonal_solver.cpp): every setup factorises with
// the structured LU, and KLU factorises a matrix it refuses (a structure the values break, pivots
// that look ill-conditioned); without a KLU a refusal is a recoverable failure
// (SUNLS_LUFACT_FAIL). The solves go to whichever factorised last. An LU type provides size(),
// `bool factor(SUNMatrix)` and `void solve(double*)`. Private to solvers/common (includes
// SUNDIALS headers).
#include <memory>
#include <stdexcept>
#include <utility>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "direct_solver_shell.hpp"
#include "kept_klu_solver.hpp"

namespace rodlab::solvers::sundials {

template <class LU>
struct FallbackContent {
  template <class... Args>
  explicit FallbackContent(Args&&... args) : lu(std::forward<Args>(args)...) {}
  FallbackContent(const FallbackContent&) = delete;
  FallbackContent& operator=(const FallbackContent&) = delete;
  ~FallbackContent() { SUNLinSolFree(klu); }

  LU lu;
  SUNLinearSolver klu = nullptr;  ///< the fallback (none: refusals fail), analysed on first use
  bool use_klu = false;           ///< the last factorisation was KLU's
  bool factored = false;          ///< the factors are valid
  bool keep_factors = true;       ///< across KINSol calls
  int last_flag = SUNLS_SUCCESS;

  /// Makes this content's kept state a copy of s's (control snapshots): no allocation once the
  /// arrays hold s's. Throws std::invalid_argument for another size.
  void assign(const FallbackContent& s) {
    if (this == &s) return;
    if (lu.size() != s.lu.size() || !klu != !s.klu)
      throw std::invalid_argument("assign: solvers of different sizes");
    lu = s.lu;  // vectors of the same sizes: element-wise copies
    if (klu) assign_kept_klu(klu, s.klu);
    use_klu = s.use_klu;
    factored = s.factored;
    last_flag = s.last_flag;
  }
};

/// The content of a solver made by make_fallback_solver<LU>.
template <class LU>
FallbackContent<LU>& fallback_content(SUNLinearSolver S) {
  return *static_cast<FallbackContent<LU>*>(S->content);
}

/// A new solver owned by the caller (SUNLinSolFree releases it) with the content `make()`
/// returns; NULL when make throws (a pattern not of the LU's form) or on allocation failure.
template <class LU, class Make>
SUNLinearSolver make_fallback_solver(SUNContext ctx, Make&& make) {
  using Content = FallbackContent<LU>;
  SUNLinearSolver S = SUNLinSolNewEmpty(ctx);
  if (!S) return nullptr;
  std::unique_ptr<Content> c;
  try {
    c = make();
  } catch (...) {
    SUNLinSolFreeEmpty(S);
    return nullptr;
  }
  DirectSolverOps ops;
  ops.initialize = [](SUNLinearSolver s) {
    Content& c = fallback_content<LU>(s);
    if (!c.keep_factors) c.factored = false;
    if (c.klu) SUNLinSolInitialize(c.klu);
    return c.last_flag = SUNLS_SUCCESS;
  };
  ops.setup = [](SUNLinearSolver s, SUNMatrix A) {
    Content& c = fallback_content<LU>(s);
    if (SUNSparseMatrix_SparseType(A) != CSC_MAT || SUNSparseMatrix_Columns(A) != c.lu.size())
      return c.last_flag = SUNLS_ILL_INPUT;
    // Every setup factorises: its users call it for new values only (a kept Jacobian's factors
    // are kept by not calling it: KINSetNoInitSetup, collocation's reuse_factorisation).
    c.factored = c.lu.factor(A);
    c.use_klu = !c.factored && c.klu;
    if (!c.use_klu) return c.last_flag = c.factored ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
    const int flag = SUNLinSolSetup(c.klu, A);
    c.factored = flag == SUNLS_SUCCESS;
    return c.last_flag = flag;
  };
  ops.solve = [](SUNLinearSolver s, SUNMatrix A, N_Vector x, N_Vector b, double tol) {
    Content& c = fallback_content<LU>(s);
    if (!c.factored) return c.last_flag = SUNLS_MEM_NULL;
    if (c.use_klu) return c.last_flag = SUNLinSolSolve(c.klu, A, x, b, tol);
    N_VScale(1.0, b, x);
    c.lu.solve(N_VGetArrayPointer(x));
    return c.last_flag = SUNLS_SUCCESS;
  };
  install_direct_solver(S, c.release(), ops);
  return S;
}

}  // namespace rodlab::solvers::sundials
