#pragma once
// The SUNLinearSolver shell of rodlab's own direct solvers (kept_klu_solver.cpp, and the
// structured LUs with a KLU fallback of fallback_solver_shell.hpp): a content object that the
// solver owns, and the operations that every direct solver of custom ID has alike. Private to
// solvers/common (includes SUNDIALS headers).
#include <sundials/sundials_linearsolver.h>

namespace rodlab::solvers::sundials {

/// The operations a direct solver implements itself; the shell adds its type (direct), its ID
/// (custom), the last flag (Content::last_flag) and the release (Content's destructor).
struct DirectSolverOps {
  int (*initialize)(SUNLinearSolver);
  int (*setup)(SUNLinearSolver, SUNMatrix);
  int (*solve)(SUNLinearSolver, SUNMatrix, N_Vector, N_Vector, sunrealtype);
};

/// Gives S (from SUNLinSolNewEmpty) its content, which SUNLinSolFree(S) then deletes, and its
/// operations.
template <class Content>
void install_direct_solver(SUNLinearSolver S, Content* content, const DirectSolverOps& ops) {
  S->content = content;
  S->ops->gettype = [](SUNLinearSolver) { return SUNLINEARSOLVER_DIRECT; };
  S->ops->getid = [](SUNLinearSolver) { return SUNLINEARSOLVER_CUSTOM; };
  S->ops->initialize = ops.initialize;
  S->ops->setup = ops.setup;
  S->ops->solve = ops.solve;
  S->ops->lastflag = [](SUNLinearSolver s) -> sunindextype {
    return static_cast<const Content*>(s->content)->last_flag;
  };
  S->ops->free = [](SUNLinearSolver s) {
    if (!s) return SUNLS_SUCCESS;
    delete static_cast<Content*>(s->content);
    s->content = nullptr;
    SUNLinSolFreeEmpty(s);
    return SUNLS_SUCCESS;
  };
}

}  // namespace rodlab::solvers::sundials
