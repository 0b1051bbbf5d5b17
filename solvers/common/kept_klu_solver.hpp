#pragma once
// A KLU SUNLinearSolver for a Jacobian whose sparsity pattern never changes, for callers that
// solve many nearby systems (a time stepper calls KINSol once per step). Unlike SUNDIALS'
// SUNLinSol_KLU, which analyses the pattern again on the first setup of every KINSol call
// (KINSOL's solver initialisation forces a full factorisation), it
//   - analyses the pattern once (KLU's defaults: BTF and AMD ordering) and keeps the analysis
//     for the life of the solver;
//   - refactors numerically on the kept pivot order (klu_refactor), falling back to a fresh
//     factorisation with new pivots when the refactored matrix looks ill-conditioned (klu_rcond
//     below eps^(2/3), the test SUNLinSol_KLU uses) or the refactorisation fails;
//   - keeps the numeric factorisation across KINSol calls (`keep_factors`), or factorises the
//     first matrix of every KINSol call afresh (pivots chosen for it, as SUNLinSol_KLU does), so
//     that a solve does not depend on the ones before;
//   - skips the factorisation altogether when the matrix values equal those it factorised
//     last (a Jacobian reused across steps), so the solves use the same factors bit for bit.
// Private to solvers/common (includes SUNDIALS and KLU headers).
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

namespace rodlab::solvers::sundials {

/// A new solver owned by the caller (SUNLinSolFree releases it); NULL on allocation failure.
/// `n` is the system size; the matrix passed to setup must be a CSC SUNSparseMatrix with the
/// same pattern at every call. `natural_order`: KLU keeps the pattern's column order (no AMD).
/// `keep_factors`: the factors carry over from one KINSol call to the next.
SUNLinearSolver make_kept_klu_solver(long n, SUNContext ctx, bool natural_order = false,
                                     bool keep_factors = true);

/// Numeric factorisations done by the solver (fresh and refactored) and setups it skipped.
struct KeptKluCounts {
  long factorisations = 0, refactorisations = 0, skipped = 0;
};
KeptKluCounts kept_klu_counts(SUNLinearSolver S);

/// Makes dst's kept state (analysis, factors, the values factorised last, counts) a copy of
/// src's, both kept KLU solvers of the same size, so that dst's next setups and solves repeat
/// src's bit for bit (a control snapshot of a time stepper: stepper.hpp). The copy reuses dst's
/// arrays wherever they can hold src's (the analysis of the same pattern is the same; the factors
/// fit unless src has since factorised afresh with a larger fill-in); only otherwise it
/// allocates. Throws std::invalid_argument for solvers of different sizes.
void assign_kept_klu(SUNLinearSolver dst, SUNLinearSolver src);

}  // namespace rodlab::solvers::sundials
