#pragma once
// A SUNLinearSolver for almost block diagonal Jacobians (almost_block_diagonal_lu.hpp): kinsol
// statics' collocation, blocks of a node's 13 unknowns, 7 base rows on the first block and 6 tip
// rows on the last, optionally bordered by dense rows and columns (its extra unknowns). Every
// setup factorises: without a border by partial pivoting panel by panel (dense partial
// pivoting's factors, so a singular matrix is a recoverable failure, SUNLS_LUFACT_FAIL, as
// KLU's is); with one by block LU on those factors, and a kept KLU solver factorises the
// matrices whose pivots look ill-conditioned (fallback_solver_shell.hpp).
// Private to solvers/common (includes SUNDIALS headers).
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

namespace rodlab::solvers::sundials {

/// Unknowns per block and the rows of the first block row (the base conditions).
inline constexpr int kAbdBlock = 13, kAbdTop = 7;

/// A new solver owned by the caller (SUNLinSolFree releases it), for CSC SUNSparseMatrix
/// Jacobians with the pattern of `pattern`: the border is its trailing columns that hold every
/// row (at most 32), the rest 13 per block. `natural_order`, `keep_factors`: as for the kept KLU
/// solver that a bordered pattern's fallback is (kept_klu_solver.hpp), and the factors carry over
/// from one KINSol call to the next. NULL when the pattern is not of that form or on allocation
/// failure.
SUNLinearSolver make_almost_block_diagonal_solver(SUNMatrix pattern, SUNContext ctx,
                                                  bool natural_order, bool keep_factors);

/// Makes dst's factors a copy of src's, both solvers of the same size (KinsolSolver::assign).
/// Throws std::invalid_argument for solvers of different sizes.
void assign_almost_block_diagonal(SUNLinearSolver dst, SUNLinearSolver src);

}  // namespace rodlab::solvers::sundials
