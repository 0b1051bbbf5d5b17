#pragma once
// A SUNLinearSolver for the semi-discrete rod's Newton matrix a I - df/dy: block tridiagonal
// in nodes of 13 unknowns (p, q, eta), whose 7 pose rows involve their own node alone. It
// condenses the pose rows and solves the 6 x 6 block-tridiagonal Schur system by block LU
// (condensed_block_lu.hpp), and falls back to the kept KLU solver (kept_klu_solver.hpp) for a
// matrix that breaks that structure or whose pivot blocks look ill-conditioned. Like the kept
// KLU solver it keeps its factors across KINSol calls (`keep_factors`); unlike it, every setup
// factorises (its callers call setup for new values only, and refactoring a matrix gives the
// same factors: the KLU fallback compares values because its refactorisation keeps pivots).
// Private to solvers/common (includes SUNDIALS headers).
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace rodlab::solvers::sundials {

/// Unknowns per node block and the pose rows among them (the first ones of each block).
inline constexpr int kCondensedBlock = 13, kCondensedLocal = 7;

/// A new solver owned by the caller (SUNLinSolFree releases it), for CSC SUNSparseMatrix
/// Jacobians with the pattern of `pattern`: n x n, floor(n / 13) blocks of 13 and a border of
/// n mod 13 rows (condensed_block_lu.hpp; `ida`'s two ledger rows). NULL when the pattern is not
/// of that form or on allocation failure.
SUNLinearSolver make_condensed_block_solver(SUNMatrix pattern, SUNContext ctx, bool keep_factors);

/// Makes dst's kept state (factors, the fallback's analysis, factors and values factorised
/// last) a copy of src's, both condensed block solvers of the same pattern, so that
/// dst's next setups and solves repeat src's bit for bit (control snapshots); no allocation once
/// dst's arrays hold src's. Throws std::invalid_argument for solvers of different sizes.
void assign_condensed_block(SUNLinearSolver dst, SUNLinearSolver src);

}  // namespace rodlab::solvers::sundials
