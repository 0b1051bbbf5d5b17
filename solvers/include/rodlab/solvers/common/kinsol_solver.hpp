#pragma once
// The SUNDIALS KINSOL adapter: Newton's method with a line search (or full steps) on a large
// sparse nonlinear system F(x) = 0, with the Jacobian factorised by KLU (or, for the
// semi-discrete rod, the condensed block solver: newton_linear_solver.hpp). This is the only code
// in rodlab that talks to KINSOL; its header exposes Eigen and std types only (the SUNDIALS
// headers stay in kinsol_solver.cpp).
//
// Following the SUNDIALS lessons of the architecture guide:
//   - RAII owners for the SUNContext, the N_Vectors, the sparse (CSC) SUNMatrix, the KLU
//     SUNLinearSolver and the KINSOL memory; nothing leaks on any path, including exceptions;
//   - residual and Jacobian are std::function over Eigen views of the SUNDIALS storage;
//   - an exception thrown inside a callback is caught there (the callback returns an
//     unrecoverable flag, so KINSOL stops) and rethrown from solve() after KINSol returns
//     (deal.II's pattern); a residual with non-finite entries, or a KinsolRecoverableError,
//     is reported to KINSOL as a recoverable failure instead;
//   - every SUNDIALS return code is checked: a set-up failure throws std::runtime_error naming
//     the call and its flag; non-convergence is a status in KinsolStats, never an exception;
//   - the solver statistics are returned to the caller.
//
// The Jacobian has a sparsity pattern fixed at construction. The Jacobian callback receives a
// matrix with that pattern and zero values and must only overwrite values (coeffRef on
// existing entries, InnerIterator::valueRef, or valuePtr()); a changed pattern throws
// std::logic_error from solve().
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "rodlab/solvers/common/newton_linear_solver.hpp"

namespace rodlab::solvers {

/// Thrown by a residual (or Jacobian) callback that cannot be evaluated at this x but may be
/// at a shorter step: KINSOL is told the failure is recoverable and the error is not rethrown.
class KinsolRecoverableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct KinsolOptions {
  double fnormtol = 1e-10;     ///< stop when |f_scale .* F|_inf <= fnormtol (KINSetFuncNormTol)
  double scsteptol = 1e-14;    ///< stop when the scaled step is below this (KINSetScaledStepTol)
  int max_iterations = 200;    ///< nonlinear iterations (KINSetNumMaxIters)
  bool line_search = true;     ///< KIN_LINESEARCH; false: full Newton steps (KIN_NONE)
  int max_setup_calls = 1;     ///< iterations between Jacobian evaluations (1: exact Newton;
                               ///< KINSOL's default is 10, a modified Newton method)
  double max_newton_step = 0;  ///< scaled length bound of a Newton step; 0: KINSOL's default
  Eigen::VectorXd u_scale;     ///< diagonal scaling of the unknowns; empty: ones
  Eigen::VectorXd f_scale;     ///< diagonal scaling of the residual; empty: ones
  int print_level = 0;         ///< KINSetPrintLevel 0-3: KINSOL's own iteration log on stdout
  bool reuse_factorisation = false;  ///< start with the previous solve's factorised Jacobian
                                     ///< (KINSetNoInitSetup); only with KluReuse::factors and
                                     ///< after a solve that factorised one
  /// solve_broyden: Jacobians set up at most per solve (the first one counted where the solve
  /// does not start from kept factors); solve() ignores it.
  int broyden_jacobians = 3;
};

struct KinsolStats {
  bool converged = false;  ///< KIN_SUCCESS or KIN_INITIAL_GUESS_OK
  int flag = 0;            ///< KINSol's return flag
  std::string flag_name;   ///< e.g. "KIN_SUCCESS", "KIN_LINESEARCH_NONCONV"
  std::string message;     ///< KINSOL's last error message (empty if none)
  long nonlinear_iterations = 0;
  long function_evaluations = 0;  ///< residual calls made by KINSOL (not by the Jacobian callback)
  long jacobian_evaluations = 0;
  long backtracks = 0;             ///< line-search backtracking steps
  long beta_condition_failures = 0;
  double fnorm = 0.0;  ///< KINSOL's scaled L2 norm of the final residual, |f_scale .* F|_2
};

/// KLU's column order. `fill_reducing`: its default analysis (COLAMD in SUNLinSol_KLU, AMD in
/// the kept solver). `natural`: the pattern's own order, for block-banded patterns (unknowns
/// numbered node by node along the rod), whose fill stays in the band either way: the
/// analysis that SUNLinSol_KLU repeats at every solve() is saved, and the factors are as sparse
/// (kinsol statics, N = 100: 3.3 -> 2.7 ms per solve, docs/statics.md "kinsol").
enum class KluOrder { fill_reducing, natural };

/// What KLU keeps from one solve() to the next (kept_klu_solver.hpp).
/// `none`: SUNDIALS' SUNLinSol_KLU, which analyses and factorises afresh at every solve().
/// `analysis`: the pattern is analysed once; every solve() factorises its first Jacobian afresh
/// (pivots chosen for it) and refactorises the later ones on those pivots, so a solve does not
/// depend on the ones before (repeated static solves: kinsol statics).
/// `factors`: the factors too (for callers that solve many nearby systems, e.g. once per time
/// step): every Jacobian is refactorised numerically on the kept pivot order (a fresh
/// factorisation when that looks ill-conditioned), and one whose values equal the last
/// factorised one is not factorised again.
enum class KluReuse { none, analysis, factors };


class KinsolSolver {
 public:
  using Vector = Eigen::VectorXd;
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor>;
  /// F(x); must write every entry of F.
  using Residual = std::function<void(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> F)>;
  /// dF/dx at x, where F = F(x) (handy for finite differences); J has the fixed pattern.
  using Jacobian = std::function<void(const Eigen::Ref<const Vector>& x,
                                      const Eigen::Ref<const Vector>& F, SparseMatrix& J)>;

  /// A solver for square systems whose Jacobian has the structural non-zeros of `pattern`
  /// (values are ignored). Throws std::invalid_argument for a non-square or empty pattern and
  /// std::runtime_error when SUNDIALS cannot create its objects. `reuse`: what KLU keeps
  /// between solves (KluReuse); `order`: KLU's column order; `linear`: the linear solver
  /// (NewtonLinearSolver; condensed_rod_blocks throws std::invalid_argument for a pattern not of
  /// its form, or with KluReuse::none).
  explicit KinsolSolver(const SparseMatrix& pattern, KluReuse reuse = KluReuse::none,
                        KluOrder order = KluOrder::fill_reducing,
                        NewtonLinearSolver linear = NewtonLinearSolver::klu);
  ~KinsolSolver();
  /// A deep copy (allocates): its own context, vectors, matrix and linear solver, in the state
  /// of `other` (with kept factors, KLU's analysis and those factors), so that its solves
  /// repeat those of `other` bit for bit (control snapshots of a time stepper, stepper.hpp). The
  /// KINSOL memory is created afresh by every solve(), so there is none to copy.
  KinsolSolver(const KinsolSolver& other);
  KinsolSolver& operator=(const KinsolSolver&) = delete;
  /// Makes this solver's state that of `other`, a solver of the same pattern and KluReuse: the
  /// vectors (N_VScale) and matrix values (copied into this solver's own), and the kept KLU
  /// analysis and factors (into its arrays when they fit, which is the steady state of a
  /// snapshot that is saved and restored: no allocation). Throws std::invalid_argument for
  /// another size or mode.
  void assign(const KinsolSolver& other);
  KinsolSolver(KinsolSolver&&) noexcept;
  KinsolSolver& operator=(KinsolSolver&&) noexcept;

  int size() const;

  /// Solves F(x) = 0 from x (in: the initial guess; out: the last iterate, converged or not).
  /// Can be called repeatedly (the context, vectors, matrix and KLU solver are reused; every
  /// call starts a fresh KINSOL run, so the statistics are those of this call). Throws
  /// std::invalid_argument for bad sizes or options, rethrows a callback's exception.
  KinsolStats solve(Vector& x, const Residual& residual, const Jacobian& jacobian,
                    const KinsolOptions& options = {});

  /// Solves F(x) = 0 like solve(), by full steps of good Broyden's method on one factorised
  /// Jacobian (broyden_steps.hpp, Deuflhard's QNERR) instead of KINSOL: the kept factors of the
  /// last solve where options.reuse_factorisation, else a Jacobian at x. Where a step's
  /// contraction theta = |J0^-1 F(x_(k+1))| / |dx_k| (after the secant updates, in u_scale's
  /// norm) is not below 1/2, a Jacobian at the current iterate replaces J0 and the updates
  /// restart, up to options.broyden_jacobians set-ups in all (none while the residual is
  /// within 4 fnormtol: its steps are rounding there). Converged when |f_scale .* F|_inf <=
  /// fnormtol (KINSOL's test; an initial guess within fnormtol / 100 needs no step); else, after
  /// max_iterations steps or a residual or Jacobian that is not finite, not converged with the
  /// last iterate in x. The same factors as solve()'s: a later solve() may start from them. A
  /// superlinear alternative to KINSOL's modified Newton (full steps, no line search) that
  /// needs no Jacobian more (docs/dynamics.md "Broyden's steps").
  KinsolStats solve_broyden(Vector& x, const Residual& residual, const Jacobian& jacobian,
                            const KinsolOptions& options);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rodlab::solvers
