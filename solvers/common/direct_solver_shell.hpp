#pragma once
// What rodlab's own direct SUNLinearSolvers (kept_klu_solver.cpp, condensed_block_solver.cpp)
// share: the SUNLinearSolver shell around a content object that the solver owns, and the record
// of the matrix values factorised last, by which a setup with the same values (a Jacobian kept
// across KINSol calls) keeps its factors. Private to solvers/common (includes SUNDIALS headers).
#include <algorithm>
#include <cstddef>
#include <vector>

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

/// The values of the matrix factorised last (CSC data, the pattern fixed).
class FactorisedValues {
 public:
  /// Whether `values` (nnz of them) are those factorised last.
  bool same(const double* values, std::size_t nnz) const {
    return valid_ && values_.size() == nnz && std::equal(values, values + nnz, values_.begin());
  }
  void remember(const double* values, std::size_t nnz) {
    values_.assign(values, values + nnz);  // the same size after the first: no allocation
    valid_ = true;
  }
  void forget() { valid_ = false; }

 private:
  std::vector<double> values_;
  bool valid_ = false;
};

}  // namespace rodlab::solvers::sundials
