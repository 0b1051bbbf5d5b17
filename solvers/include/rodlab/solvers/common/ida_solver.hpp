#pragma once
// The SUNDIALS IDA adapter: variable-order BDF integration of an implicit system
// F(t, y, y') = 0 with the Newton matrix dF/dy + cj dF/dy' factorised by KLU (or, for the
// semi-discrete rod, the condensed block solver: newton_linear_solver.hpp). This is the only
// code in rodlab that talks to IDA; its header exposes Eigen and std types only (the SUNDIALS
// headers stay in ida_solver.cpp). It follows kinsol_solver.hpp:
//   - RAII owners for the SUNContext, the N_Vectors, the sparse (CSC) SUNMatrix, the KLU
//     SUNLinearSolver and the IDA memory; nothing leaks on any path, including exceptions;
//   - residual and Jacobian are std::function over Eigen views of the SUNDIALS storage;
//   - an exception thrown inside a callback is caught there (the callback returns an
//     unrecoverable flag, so IDA stops) and rethrown from advance() after IDASolve returns; a
//     residual with non-finite entries, or an IdaRecoverableError, is reported to IDA as a
//     recoverable failure instead (IDA retries with a smaller step);
//   - every SUNDIALS return code is checked: a set-up failure throws std::runtime_error naming
//     the call and its flag; a failed integration (too much work, repeated error-test or
//     convergence failures) is a status in IdaStats, never an exception;
//   - the solver statistics are returned to the caller.
//
// Unlike KINSOL the IDA memory lives across calls: initialize() once (or again to restart),
// then advance() repeatedly. The Jacobian has a sparsity pattern fixed at construction; the
// Jacobian callback receives a matrix with that pattern and zero values and must only overwrite
// values (coeffRef on existing entries, InnerIterator::valueRef, or valuePtr()); a changed
// pattern throws std::logic_error from advance().
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "rodlab/solvers/common/newton_linear_solver.hpp"

namespace rodlab::solvers {

/// Thrown by a residual (or Jacobian) callback that cannot be evaluated at this (t, y, y') but
/// may be at a smaller step: IDA is told the failure is recoverable and the error is not rethrown.
class IdaRecoverableError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct IdaSolverOptions {
  double rtol = 1e-10;        ///< relative tolerance (IDASVtolerances)
  Eigen::VectorXd atol;       ///< absolute tolerance per component, finite and > 0
  long max_steps = 100000;    ///< internal steps per advance() call (IDASetMaxNumSteps)
  int max_order = 5;          ///< BDF order bound 1..5 (IDASetMaxOrd)
  double max_step = 0.0;      ///< bound on |h|; 0: none (IDASetMaxStep)
  double initial_step = 0.0;  ///< first step; 0: IDA's estimate (IDASetInitStep)
  /// Differential (1) or algebraic (0) per component (IDASetId); empty: all differential.
  Eigen::VectorXd id;
  /// Leave the algebraic components (id 0) out of the local error test (IDASetSuppressAlg):
  /// the usual setting for index-2 systems, whose multipliers are not smooth enough for it.
  bool suppress_algebraic = false;
  /// The Newton systems' linear solver (newton_linear_solver.hpp); condensed_rod_blocks throws
  /// std::invalid_argument for a pattern not of its form.
  NewtonLinearSolver linear_solver = NewtonLinearSolver::klu;
};

struct IdaStats {
  bool ok = false;        ///< IDA_SUCCESS or IDA_TSTOP_RETURN
  int flag = 0;           ///< IDASolve's return flag
  std::string flag_name;  ///< e.g. "IDA_SUCCESS", "IDA_TOO_MUCH_WORK", "IDA_CONV_FAIL"
  std::string message;    ///< IDA's last error message during the call (empty if none)
  double t = 0.0;         ///< the time reached
  // Counters of the call (advance()) or since initialize() (statistics()).
  long steps = 0;
  long residual_evaluations = 0;  ///< by IDA (not by the Jacobian callback)
  long jacobian_evaluations = 0;
  long linear_setups = 0;         ///< linear solver setups (factorisations)
  long nonlinear_iterations = 0;
  long nonlinear_convergence_failures = 0;
  long error_test_failures = 0;
  int last_order = 0;       ///< BDF order of the last step
  double last_step = 0.0;   ///< size of the last step
};

class IdaSolver {
 public:
  using Vector = Eigen::VectorXd;
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor>;
  /// F(t, y, y'); must write every entry of r.
  using Residual = std::function<void(double t, const Eigen::Ref<const Vector>& y,
                                      const Eigen::Ref<const Vector>& yp, Eigen::Ref<Vector> r)>;
  /// dF/dy + cj dF/dy' at (t, y, y'), where r = F(t, y, y'); J has the fixed pattern.
  using Jacobian = std::function<void(double t, double cj, const Eigen::Ref<const Vector>& y,
                                      const Eigen::Ref<const Vector>& yp,
                                      const Eigen::Ref<const Vector>& r, SparseMatrix& J)>;

  /// A solver for systems whose Newton matrix has the structural non-zeros of `pattern` (values
  /// are ignored). Throws std::invalid_argument for a non-square or empty pattern, empty
  /// callbacks or bad options, and std::runtime_error when SUNDIALS cannot create its objects.
  IdaSolver(const SparseMatrix& pattern, Residual residual, Jacobian jacobian,
            const IdaSolverOptions& options);
  ~IdaSolver();
  IdaSolver(const IdaSolver&) = delete;
  IdaSolver& operator=(const IdaSolver&) = delete;
  IdaSolver(IdaSolver&&) noexcept;
  IdaSolver& operator=(IdaSolver&&) noexcept;

  int size() const;

  /// Starts the integration at t0 from a consistent (y0, y0') (IDAInit the first time,
  /// IDAReInit afterwards: the history and counters are reset). Throws std::invalid_argument
  /// for bad sizes or non-finite values.
  void initialize(double t0, const Vector& y0, const Vector& yp0);

  /// IDASolve in IDA_NORMAL mode to tout with the stop time at tout, so the solution at tout is
  /// a computed step, not an interpolant. Returns this call's status and counters. Throws
  /// std::logic_error before initialize(), rethrows a callback's exception, and throws
  /// std::runtime_error for set-up errors (IDA_ILL_INPUT, IDA_MEM_NULL, ...).
  IdaStats advance(double tout);

  /// The current time, solution and derivative (after the last successful or failed advance).
  double time() const;
  Eigen::Map<const Vector> y() const;
  Eigen::Map<const Vector> yp() const;

  /// Counters since initialize(); flag and message are those of the last advance().
  IdaStats statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rodlab::solvers
