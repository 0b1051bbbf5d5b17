#include "rodlab/solvers/common/kinsol_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <string>
#include <type_traits>
#include <vector>

#include <kinsol/kinsol.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

namespace rodlab::solvers {
namespace {

// --- flag names and checks ------------------------------------------------------------------

/// The names of kinsol.h. KINGetReturnFlagName (6.4) answers "NONE" for the system-function
/// and context flags, so the table is spelled out; unknown flags fall back to it.
std::string kin_flag_name(long flag) {
  switch (flag) {
    case KIN_SUCCESS: return "KIN_SUCCESS";
    case KIN_INITIAL_GUESS_OK: return "KIN_INITIAL_GUESS_OK";
    case KIN_STEP_LT_STPTOL: return "KIN_STEP_LT_STPTOL";
    case KIN_WARNING: return "KIN_WARNING";
    case KIN_MEM_NULL: return "KIN_MEM_NULL";
    case KIN_ILL_INPUT: return "KIN_ILL_INPUT";
    case KIN_NO_MALLOC: return "KIN_NO_MALLOC";
    case KIN_MEM_FAIL: return "KIN_MEM_FAIL";
    case KIN_LINESEARCH_NONCONV: return "KIN_LINESEARCH_NONCONV";
    case KIN_MAXITER_REACHED: return "KIN_MAXITER_REACHED";
    case KIN_MXNEWT_5X_EXCEEDED: return "KIN_MXNEWT_5X_EXCEEDED";
    case KIN_LINESEARCH_BCFAIL: return "KIN_LINESEARCH_BCFAIL";
    case KIN_LINSOLV_NO_RECOVERY: return "KIN_LINSOLV_NO_RECOVERY";
    case KIN_LINIT_FAIL: return "KIN_LINIT_FAIL";
    case KIN_LSETUP_FAIL: return "KIN_LSETUP_FAIL";
    case KIN_LSOLVE_FAIL: return "KIN_LSOLVE_FAIL";
    case KIN_SYSFUNC_FAIL: return "KIN_SYSFUNC_FAIL";
    case KIN_FIRST_SYSFUNC_ERR: return "KIN_FIRST_SYSFUNC_ERR";
    case KIN_REPTD_SYSFUNC_ERR: return "KIN_REPTD_SYSFUNC_ERR";
    case KIN_VECTOROP_ERR: return "KIN_VECTOROP_ERR";
    case KIN_CONTEXT_ERR: return "KIN_CONTEXT_ERR";
    default: break;
  }
  // KINGetReturnFlagName returns a malloc'ed string that the caller frees.
  char* name = KINGetReturnFlagName(flag);
  if (!name) return "KINSOL flag " + std::to_string(flag);
  std::string out(name);
  std::free(name);
  return out;
}

std::string kinls_flag_name(long flag) {
  char* name = KINGetLinReturnFlagName(flag);
  if (!name) return "KINLS flag " + std::to_string(flag);
  std::string out(name);
  std::free(name);
  return out;
}

void check_kin(int flag, const char* call) {
  if (flag != KIN_SUCCESS)
    throw std::runtime_error(std::string("KINSOL: ") + call + " failed with " + kin_flag_name(flag));
}

void check_kinls(int flag, const char* call) {
  if (flag != KINLS_SUCCESS)
    throw std::runtime_error(std::string("KINSOL: ") + call + " failed with " + kinls_flag_name(flag));
}

template <class T>
T check_created(T object, const char* call) {
  if (object == nullptr) throw std::runtime_error(std::string("KINSOL: ") + call + " returned NULL");
  return object;
}

// --- RAII owners ----------------------------------------------------------------------------

struct ContextDeleter {
  void operator()(SUNContext ctx) const { SUNContext_Free(&ctx); }
};
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(SUNMatrix A) const { SUNMatDestroy(A); }
};
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver LS) const { SUNLinSolFree(LS); }
};
struct KinsolMemoryDeleter {
  void operator()(void* mem) const { KINFree(&mem); }
};

using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
using KinsolMemoryPtr = std::unique_ptr<void, KinsolMemoryDeleter>;

Eigen::Map<Eigen::VectorXd> view(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

}  // namespace

struct KinsolSolver::Impl {
  // Declaration order is destruction order reversed: the context outlives everything.
  ContextPtr context;
  VectorPtr u, u_scale, f_scale;
  MatrixPtr A;
  LinearSolverPtr linear_solver;
  int n = 0;
  SparseMatrix J;  // the fixed pattern; the Jacobian callback writes its values
  std::vector<sunindextype> column_pointers, row_indices;

  /// What the C callbacks need during one solve.
  struct Call {
    Impl* self;
    const Residual* residual;
    const Jacobian* jacobian;
    std::exception_ptr error;
    std::string message;
  };

  /// Runs a callback body: a KinsolRecoverableError becomes the recoverable flag 1 with its
  /// message; any other exception is kept for rethrowing after KINSol returns (flag -1).
  template <class Body>
  static int guarded(Call* call, Body&& body) {
    try {
      return body();
    } catch (const KinsolRecoverableError& e) {
      call->message = e.what();
      return 1;
    } catch (...) {
      call->error = std::current_exception();
      return -1;
    }
  }

  static int residual_callback(N_Vector u, N_Vector F, void* user_data) {
    auto* call = static_cast<Call*>(user_data);
    return guarded(call, [&] {
      auto Fv = view(F);
      (*call->residual)(view(u), Fv);
      return Fv.allFinite() ? 0 : 1;  // non-finite: recoverable (KINSOL may retry)
    });
  }

  static int jacobian_callback(N_Vector u, N_Vector F, SUNMatrix A, void* user_data, N_Vector,
                               N_Vector) {
    auto* call = static_cast<Call*>(user_data);
    Impl& self = *call->self;
    return guarded(call, [&] {
      SparseMatrix& J = self.J;
      std::fill(J.valuePtr(), J.valuePtr() + J.nonZeros(), 0.0);
      (*call->jacobian)(view(u), view(F), J);
      self.check_pattern();
      const double* values = J.valuePtr();
      if (!std::all_of(values, values + J.nonZeros(), [](double v) { return std::isfinite(v); })) {
        call->message = "the Jacobian has non-finite entries";
        return 1;
      }
      // KINLS zeroes the matrix, index arrays included (SUNMatZero_Sparse), before this call.
      std::copy(self.column_pointers.begin(), self.column_pointers.end(), SUNSparseMatrix_IndexPointers(A));
      std::copy(self.row_indices.begin(), self.row_indices.end(), SUNSparseMatrix_IndexValues(A));
      std::copy(values, values + J.nonZeros(), SUNSparseMatrix_Data(A));
      return 0;
    });
  }

  static void error_handler(int, const char* module, const char* function, char* msg, void* user_data) {
    auto* call = static_cast<Call*>(user_data);
    call->message = std::string(module ? module : "") + "::" + (function ? function : "") + ": " +
                    (msg ? msg : "");
  }

  void check_pattern() const {
    const auto nnz = static_cast<std::size_t>(J.nonZeros());
    bool same = J.isCompressed() && nnz == row_indices.size() && J.rows() == n && J.cols() == n;
    for (int j = 0; same && j <= n; ++j) same = J.outerIndexPtr()[j] == column_pointers[j];
    for (std::size_t k = 0; same && k < nnz; ++k) same = J.innerIndexPtr()[k] == row_indices[k];
    if (!same)
      throw std::logic_error(
          "KinsolSolver: the Jacobian callback changed the sparsity pattern (only values may be set)");
  }
};

KinsolSolver::KinsolSolver(const SparseMatrix& pattern) : impl_(std::make_unique<Impl>()) {
  if (pattern.rows() != pattern.cols() || pattern.rows() == 0)
    throw std::invalid_argument("KinsolSolver: expected a square non-empty Jacobian pattern, got " +
                                std::to_string(pattern.rows()) + " x " + std::to_string(pattern.cols()));
  Impl& d = *impl_;
  d.n = static_cast<int>(pattern.rows());
  d.J = pattern;
  d.J.makeCompressed();
  if (d.J.nonZeros() == 0) throw std::invalid_argument("KinsolSolver: the Jacobian pattern is empty");
  std::fill(d.J.valuePtr(), d.J.valuePtr() + d.J.nonZeros(), 0.0);
  d.column_pointers.assign(d.J.outerIndexPtr(), d.J.outerIndexPtr() + d.n + 1);
  d.row_indices.assign(d.J.innerIndexPtr(), d.J.innerIndexPtr() + d.J.nonZeros());

  SUNContext ctx = nullptr;
  if (const int flag = SUNContext_Create(nullptr, &ctx); flag != 0 || ctx == nullptr)
    throw std::runtime_error("KINSOL: SUNContext_Create failed with flag " + std::to_string(flag));
  d.context.reset(ctx);
  d.u.reset(check_created(N_VNew_Serial(d.n, ctx), "N_VNew_Serial"));
  d.u_scale.reset(check_created(N_VNew_Serial(d.n, ctx), "N_VNew_Serial"));
  d.f_scale.reset(check_created(N_VNew_Serial(d.n, ctx), "N_VNew_Serial"));
  d.A.reset(check_created(SUNSparseMatrix(d.n, d.n, d.J.nonZeros(), CSC_MAT, ctx), "SUNSparseMatrix"));
  std::copy(d.column_pointers.begin(), d.column_pointers.end(), SUNSparseMatrix_IndexPointers(d.A.get()));
  std::copy(d.row_indices.begin(), d.row_indices.end(), SUNSparseMatrix_IndexValues(d.A.get()));
  d.linear_solver.reset(check_created(SUNLinSol_KLU(d.u.get(), d.A.get(), ctx), "SUNLinSol_KLU"));
}

KinsolSolver::~KinsolSolver() = default;
KinsolSolver::KinsolSolver(KinsolSolver&&) noexcept = default;
KinsolSolver& KinsolSolver::operator=(KinsolSolver&&) noexcept = default;

int KinsolSolver::size() const { return impl_->n; }

KinsolStats KinsolSolver::solve(Vector& x, const Residual& residual, const Jacobian& jacobian,
                                const KinsolOptions& options) {
  Impl& d = *impl_;
  const auto n = static_cast<Eigen::Index>(d.n);
  auto expect_size = [&](const Vector& v, const char* what) {
    if (v.size() != n)
      throw std::invalid_argument(std::string("KinsolSolver::solve: ") + what + ": expected size " +
                                  std::to_string(n) + ", got " + std::to_string(v.size()));
  };
  expect_size(x, "x");
  if (!x.allFinite()) throw std::invalid_argument("KinsolSolver::solve: the initial guess is not finite");
  if (!residual || !jacobian) throw std::invalid_argument("KinsolSolver::solve: empty residual or Jacobian");
  if (!(options.fnormtol > 0.0) || !(options.scsteptol > 0.0))
    throw std::invalid_argument("KinsolSolver::solve: fnormtol and scsteptol must be > 0, got " +
                                std::to_string(options.fnormtol) + ", " + std::to_string(options.scsteptol));
  if (options.max_iterations < 1 || options.max_setup_calls < 1)
    throw std::invalid_argument("KinsolSolver::solve: max_iterations and max_setup_calls must be >= 1, got " +
                                std::to_string(options.max_iterations) + ", " +
                                std::to_string(options.max_setup_calls));
  if (options.print_level < 0 || options.print_level > 3)
    throw std::invalid_argument("KinsolSolver::solve: print_level must be 0..3, got " +
                                std::to_string(options.print_level));
  if (!(options.max_newton_step >= 0.0))
    throw std::invalid_argument("KinsolSolver::solve: max_newton_step must be >= 0");
  auto set_scale = [&](const Vector& scale, N_Vector target, const char* what) {
    auto out = view(target);
    if (scale.size() == 0) {
      out.setOnes();
      return;
    }
    expect_size(scale, what);
    if (!scale.allFinite() || !(scale.minCoeff() > 0.0))
      throw std::invalid_argument(std::string("KinsolSolver::solve: ") + what + " must be finite and > 0");
    out = scale;
  };
  set_scale(options.u_scale, d.u_scale.get(), "u_scale");
  set_scale(options.f_scale, d.f_scale.get(), "f_scale");
  view(d.u.get()) = x;

  Impl::Call call{&d, &residual, &jacobian, nullptr, {}};

  // A fresh KINSOL memory per solve: its counters are this solve's, and no state leaks between
  // solves; the context, vectors, matrix and KLU solver are reused.
  KinsolMemoryPtr memory(check_created(KINCreate(d.context.get()), "KINCreate"));
  void* mem = memory.get();
  check_kin(KINInit(mem, &Impl::residual_callback, d.u.get()), "KINInit");
  check_kin(KINSetUserData(mem, &call), "KINSetUserData");
  check_kin(KINSetErrHandlerFn(mem, &Impl::error_handler, &call), "KINSetErrHandlerFn");
  check_kinls(KINSetLinearSolver(mem, d.linear_solver.get(), d.A.get()), "KINSetLinearSolver");
  check_kinls(KINSetJacFn(mem, &Impl::jacobian_callback), "KINSetJacFn");
  check_kin(KINSetFuncNormTol(mem, options.fnormtol), "KINSetFuncNormTol");
  check_kin(KINSetScaledStepTol(mem, options.scsteptol), "KINSetScaledStepTol");
  check_kin(KINSetNumMaxIters(mem, options.max_iterations), "KINSetNumMaxIters");
  check_kin(KINSetMaxSetupCalls(mem, options.max_setup_calls), "KINSetMaxSetupCalls");
  check_kin(KINSetPrintLevel(mem, options.print_level), "KINSetPrintLevel");
  if (options.max_newton_step > 0.0)
    check_kin(KINSetMaxNewtonStep(mem, options.max_newton_step), "KINSetMaxNewtonStep");

  const int flag = KINSol(mem, d.u.get(), options.line_search ? KIN_LINESEARCH : KIN_NONE,
                          d.u_scale.get(), d.f_scale.get());
  if (call.error) std::rethrow_exception(call.error);

  KinsolStats stats;
  stats.flag = flag;
  stats.flag_name = kin_flag_name(flag);
  stats.message = call.message;
  switch (flag) {
    case KIN_MEM_NULL:
    case KIN_ILL_INPUT:
    case KIN_NO_MALLOC:
    case KIN_MEM_FAIL:
    case KIN_LINIT_FAIL:
    case KIN_VECTOROP_ERR:
    case KIN_CONTEXT_ERR:
      // Set-up errors, not convergence failures.
      throw std::runtime_error("KINSOL: KINSol failed with " + stats.flag_name +
                               (call.message.empty() ? "" : " (" + call.message + ")"));
    default: break;
  }
  stats.converged = flag == KIN_SUCCESS || flag == KIN_INITIAL_GUESS_OK;
  long value = 0;
  check_kin(KINGetNumNonlinSolvIters(mem, &value), "KINGetNumNonlinSolvIters");
  stats.nonlinear_iterations = value;
  check_kin(KINGetNumFuncEvals(mem, &value), "KINGetNumFuncEvals");
  stats.function_evaluations = value;
  check_kinls(KINGetNumJacEvals(mem, &value), "KINGetNumJacEvals");
  stats.jacobian_evaluations = value;
  check_kin(KINGetNumBacktrackOps(mem, &value), "KINGetNumBacktrackOps");
  stats.backtracks = value;
  check_kin(KINGetNumBetaCondFails(mem, &value), "KINGetNumBetaCondFails");
  stats.beta_condition_failures = value;
  sunrealtype fnorm = 0.0;
  check_kin(KINGetFuncNorm(mem, &fnorm), "KINGetFuncNorm");
  stats.fnorm = fnorm;
  x = view(d.u.get());
  return stats;
}

}  // namespace rodlab::solvers
