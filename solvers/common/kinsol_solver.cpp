#include "rodlab/solvers/common/kinsol_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <string>
#include <utility>

#include <kinsol/kinsol.h>
#include <sunlinsol/sunlinsol_klu.h>

#include "rodlab/check.hpp"

#include "almost_block_diagonal_solver.hpp"
#include "broyden_steps.hpp"
#include "condensed_block_solver.hpp"
#include "kept_klu_solver.hpp"
#include "sundials_support.hpp"

namespace rodlab::solvers {
namespace {

using sundials::view;

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
  if (!name) return rodlab::format("KINSOL flag {}", flag);
  std::string out(name);
  std::free(name);
  return out;
}

std::string kinls_flag_name(long flag) {
  char* name = KINGetLinReturnFlagName(flag);
  if (!name) return rodlab::format("KINLS flag {}", flag);
  std::string out(name);
  std::free(name);
  return out;
}

void check_kin(int flag, const char* call) {
  if (flag != KIN_SUCCESS)
    throw std::runtime_error(
        rodlab::format("KINSOL: {} failed with {}", call, kin_flag_name(flag)));
}

void check_kinls(int flag, const char* call) {
  if (flag != KINLS_SUCCESS)
    throw std::runtime_error(
        rodlab::format("KINSOL: {} failed with {}", call, kinls_flag_name(flag)));
}

}  // namespace

struct KinsolSolver::Impl {
  Impl(sundials::JacobianPattern pattern, KluReuse reuse, KluOrder order,
       NewtonLinearSolver linear)
      : pattern(std::move(pattern)), order(order), reuse(reuse), linear(linear) {
    if (linear == NewtonLinearSolver::condensed_rod_blocks && reuse == KluReuse::none)
      throw std::invalid_argument("KinsolSolver: condensed_rod_blocks needs KluReuse analysis or "
                                  "factors");
    create();
  }

  /// The SUNDIALS objects for a system of the pattern's size.
  void create() {
    const int n = pattern.size();
    context = sundials::make_context("KINSOL");
    SUNContext ctx = context.get();
    u = sundials::make_vector(n, ctx, "KINSOL");
    rhs = sundials::make_vector(n, ctx, "KINSOL");
    step = sundials::make_vector(n, ctx, "KINSOL");
    u_scale = sundials::make_vector(n, ctx, "KINSOL");
    f_scale = sundials::make_vector(n, ctx, "KINSOL");
    A = pattern.make_matrix(ctx);
    const bool natural = order == KluOrder::natural;
    const bool kept = reuse != KluReuse::none;
    const bool keep_factors = reuse == KluReuse::factors;
    if (linear != NewtonLinearSolver::klu) {  // a structured LU with a KLU fallback
      const bool condensed = linear == NewtonLinearSolver::condensed_rod_blocks;
      linear_solver.reset(
          condensed ? sundials::make_condensed_block_solver(A.get(), ctx, keep_factors)
                    : sundials::make_almost_block_diagonal_solver(A.get(), ctx, natural,
                                                                  keep_factors));
      if (!linear_solver)
        throw std::invalid_argument(rodlab::format(
            "KinsolSolver: {} needs a pattern of its form (newton_linear_solver.hpp)",
            condensed ? "condensed_rod_blocks" : "almost_block_diagonal"));
      return;
    }
    linear_solver.reset(
        kept ? sundials::check_created(
                   sundials::make_kept_klu_solver(n, ctx, natural, keep_factors),
                   "KINSOL", "make_kept_klu_solver")
             : sundials::check_created(SUNLinSol_KLU(u.get(), A.get(), ctx), "KINSOL",
                                       "SUNLinSol_KLU"));
    if (!kept && natural && SUNLinSol_KLUSetOrdering(linear_solver.get(), 2) != SUNLS_SUCCESS)
      throw std::runtime_error("KINSOL: SUNLinSol_KLUSetOrdering failed");
  }

  // Declaration order is destruction order reversed: the context outlives everything.
  sundials::ContextPtr context;
  sundials::VectorPtr u, u_scale, f_scale;
  sundials::VectorPtr rhs, step;  ///< solve_broyden's linear systems
  sundials::MatrixPtr A;
  sundials::LinearSolverPtr linear_solver;
  sundials::JacobianPattern pattern;  // the callback writes its values
  KluOrder order = KluOrder::fill_reducing;
  KluReuse reuse = KluReuse::none;
  NewtonLinearSolver linear = NewtonLinearSolver::klu;
  Vector F;               ///< solve_broyden's residual
  BroydenSteps broyden;   ///< solve_broyden's secant steps

  /// What the C callbacks need during one solve.
  struct Call {
    Impl* self;
    const Residual* residual;
    const Jacobian* jacobian;
    std::exception_ptr error;
    std::string message;
  };

  template <class Body>
  static int guarded(Call* call, Body&& body) {
    return sundials::guarded<KinsolRecoverableError>(call->message, call->error, body);
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
    return guarded(call, [&] {
      const bool finite = call->self->pattern.fill(
          A, [&](SparseMatrix& J) { (*call->jacobian)(view(u), view(F), J); });
      if (finite) return 0;
      call->message = "the Jacobian has non-finite entries";
      return 1;
    });
  }

  static void error_handler(int, const char* module, const char* function, char* msg, void* user_data) {
    static_cast<Call*>(user_data)->message = sundials::error_text(module, function, msg);
  }
};

KinsolSolver::KinsolSolver(const SparseMatrix& pattern, KluReuse reuse, KluOrder order,
                           NewtonLinearSolver linear)
    : impl_(std::make_unique<Impl>(sundials::JacobianPattern(pattern, "KinsolSolver"), reuse,
                                   order, linear)) {}

KinsolSolver::KinsolSolver(const KinsolSolver& other)
    : impl_(std::make_unique<Impl>(other.impl_->pattern, other.impl_->reuse,
                                   other.impl_->order, other.impl_->linear)) {
  assign(other);
}

void KinsolSolver::assign(const KinsolSolver& other) {
  Impl& d = *impl_;
  const Impl& o = *other.impl_;
  if (&d == &o) return;
  const sunindextype nnz = SUNSparseMatrix_NNZ(d.A.get());
  if (d.pattern.size() != o.pattern.size() || nnz != SUNSparseMatrix_NNZ(o.A.get()) ||
      d.reuse != o.reuse || d.linear != o.linear)
    throw std::invalid_argument(
        "KinsolSolver::assign: from a solver of another size or factorisation mode");
  N_VScale(1.0, o.u.get(), d.u.get());
  N_VScale(1.0, o.u_scale.get(), d.u_scale.get());
  N_VScale(1.0, o.f_scale.get(), d.f_scale.get());
  const double* values = SUNSparseMatrix_Data(o.A.get());
  std::copy(values, values + nnz, SUNSparseMatrix_Data(d.A.get()));
  // SUNLinSol_KLU analyses and factorises afresh at the start of every solve: nothing is kept.
  if (d.linear == NewtonLinearSolver::condensed_rod_blocks)
    sundials::assign_condensed_block(d.linear_solver.get(), o.linear_solver.get());
  else if (d.linear == NewtonLinearSolver::almost_block_diagonal)
    sundials::assign_almost_block_diagonal(d.linear_solver.get(), o.linear_solver.get());
  else if (d.reuse != KluReuse::none)
    sundials::assign_kept_klu(d.linear_solver.get(), o.linear_solver.get());
}

KinsolSolver::~KinsolSolver() = default;
KinsolSolver::KinsolSolver(KinsolSolver&&) noexcept = default;
KinsolSolver& KinsolSolver::operator=(KinsolSolver&&) noexcept = default;

int KinsolSolver::size() const { return impl_->pattern.size(); }

namespace {

/// Deuflhard's bound on the contraction of QNERR's steps (broyden_steps.hpp).
constexpr double kBroydenMaxContraction = 0.5;
/// Below this many times fnormtol, solve_broyden sets no Jacobian up for a step that does not
/// contract: collocation's residual at N = 20, 1 ms stalls at 1-2 fnormtol (f's rounding), where
/// theta is 0.5-1.6 with a fresh Jacobian too; such steps set up 0.12 Jacobians per step
/// against 0.058 with this rule, at the same 6.1 iterations (bench_dynamics).
constexpr double kBroydenNoise = 4.0;

/// The arguments' checks of solve() and solve_broyden(); sets the scalings.
void check_arguments(int size, const Eigen::VectorXd& x, bool callbacks,
                     const KinsolOptions& options, N_Vector u_scale, N_Vector f_scale) {
  const auto n = static_cast<Eigen::Index>(size);
  auto expect_size = [&](const Eigen::VectorXd& v, const char* what) {
    RODLAB_THROW_UNLESS(v.size() == n, "KinsolSolver::solve: {}: expected size {}, got {}", what,
                        n, v.size());
  };
  expect_size(x, "x");
  if (!x.allFinite()) throw std::invalid_argument("KinsolSolver::solve: the initial guess is not finite");
  if (!callbacks) throw std::invalid_argument("KinsolSolver::solve: empty residual or Jacobian");
  RODLAB_THROW_UNLESS(options.fnormtol > 0.0 && options.scsteptol > 0.0,
                      "KinsolSolver::solve: fnormtol and scsteptol must be > 0, got {:g}, {:g}",
                      options.fnormtol, options.scsteptol);
  RODLAB_THROW_UNLESS(
      options.max_iterations >= 1 && options.max_setup_calls >= 1,
      "KinsolSolver::solve: max_iterations and max_setup_calls must be >= 1, got {}, {}",
      options.max_iterations, options.max_setup_calls);
  RODLAB_THROW_UNLESS(options.print_level >= 0 && options.print_level <= 3,
                      "KinsolSolver::solve: print_level must be 0..3, got {}", options.print_level);
  if (!(options.max_newton_step >= 0.0))
    throw std::invalid_argument("KinsolSolver::solve: max_newton_step must be >= 0");
  auto set_scale = [&](const Eigen::VectorXd& scale, N_Vector target, const char* what) {
    auto out = view(target);
    if (scale.size() == 0) {
      out.setOnes();
      return;
    }
    expect_size(scale, what);
    RODLAB_THROW_UNLESS(scale.allFinite() && scale.minCoeff() > 0.0,
                        "KinsolSolver::solve: {} must be finite and > 0", what);
    out = scale;
  };
  set_scale(options.u_scale, u_scale, "u_scale");
  set_scale(options.f_scale, f_scale, "f_scale");
}

}  // namespace

KinsolStats KinsolSolver::solve(Vector& x, const Residual& residual, const Jacobian& jacobian,
                                const KinsolOptions& options) {
  Impl& d = *impl_;
  check_arguments(d.pattern.size(), x, residual && jacobian, options, d.u_scale.get(),
                  d.f_scale.get());
  view(d.u.get()) = x;

  Impl::Call call{&d, &residual, &jacobian, nullptr, {}};

  // A fresh KINSOL memory per solve: its counters are this solve's, and no state leaks between
  // solves; the context, vectors, matrix and KLU solver are reused.
  sundials::MemoryPtr<KINFree> memory(
      sundials::check_created(KINCreate(d.context.get()), "KINSOL", "KINCreate"));
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
  if (options.reuse_factorisation) {
    if (d.reuse != KluReuse::factors)
      throw std::invalid_argument(
          "KinsolSolver::solve: reuse_factorisation needs a solver constructed with "
          "KluReuse::factors");
    check_kin(KINSetNoInitSetup(mem, SUNTRUE), "KINSetNoInitSetup");
  }
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
      throw std::runtime_error(
          rodlab::format("KINSOL: KINSol failed with {}{}", stats.flag_name,
                         call.message.empty() ? "" : " (" + call.message + ")"));
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

KinsolStats KinsolSolver::solve_broyden(Vector& x, const Residual& residual,
                                        const Jacobian& jacobian, const KinsolOptions& options) {
  Impl& d = *impl_;
  check_arguments(d.pattern.size(), x, residual && jacobian, options, d.u_scale.get(),
                  d.f_scale.get());
  RODLAB_THROW_UNLESS(options.broyden_jacobians >= 1,
                      "KinsolSolver::solve_broyden: broyden_jacobians must be >= 1, got {}",
                      options.broyden_jacobians);
  if (options.reuse_factorisation && d.reuse != KluReuse::factors)
    throw std::invalid_argument(
        "KinsolSolver::solve_broyden: reuse_factorisation needs a solver constructed with "
        "KluReuse::factors");
  const auto u_scale = view(d.u_scale.get());
  const auto f_scale = view(d.f_scale.get());
  d.F.resize(x.size());
  d.broyden.reset(u_scale, options.max_iterations + 1);
  auto dx = view(d.step.get());
  KinsolStats stats;
  auto finish = [&](bool converged, const char* how) {
    stats.converged = converged;
    stats.flag_name = how;
    stats.fnorm = f_scale.cwiseProduct(d.F).norm();
    return stats;
  };
  double fnorm_inf = 0.0;  // |f_scale .* F|_inf of the last evaluation (KINSOL's test)
  // F(x) into d.F and its norm; false where it is not finite (or cannot be evaluated).
  auto evaluate = [&] {
    ++stats.function_evaluations;
    try {
      residual(x, d.F);
    } catch (const KinsolRecoverableError& e) {
      stats.message = e.what();
      return false;
    }
    if (!d.F.allFinite()) return false;
    fnorm_inf = f_scale.cwiseProduct(d.F).cwiseAbs().maxCoeff();
    return true;
  };
  // A Jacobian at x, factorised (the Jacobian callback's contract, as in KINSOL's set-up).
  auto set_up = [&] {
    ++stats.jacobian_evaluations;
    const bool finite =
        d.pattern.fill(d.A.get(), [&](SparseMatrix& J) { jacobian(x, d.F, J); });
    if (!finite) stats.message = "the Jacobian has non-finite entries";
    return finite && SUNLinSolSetup(d.linear_solver.get(), d.A.get()) == SUNLS_SUCCESS;
  };
  // dx = -J0^-1 F.
  auto simplified_step = [&] {
    view(d.rhs.get()) = -d.F;
    return SUNLinSolSolve(d.linear_solver.get(), d.A.get(), d.step.get(), d.rhs.get(), 0.0) ==
           SUNLS_SUCCESS;
  };

  if (!evaluate()) return finish(false, "broyden: the residual is not finite");
  if (fnorm_inf <= 0.01 * options.fnormtol) return finish(true, "KIN_INITIAL_GUESS_OK");
  SUNLinSolInitialize(d.linear_solver.get());
  if (!options.reuse_factorisation && !set_up())
    return finish(false, "broyden: the Jacobian's set-up failed");
  if (!simplified_step()) return finish(false, "broyden: the linear solve failed");
  d.broyden.push(dx);
  for (;;) {
    x += dx;
    ++stats.nonlinear_iterations;
    if (!evaluate()) return finish(false, "broyden: the residual is not finite");
    if (fnorm_inf <= options.fnormtol) return finish(true, "KIN_SUCCESS");
    if (stats.nonlinear_iterations >= options.max_iterations)
      return finish(false, "KIN_MAXITER_REACHED");
    if (!simplified_step()) return finish(false, "broyden: the linear solve failed");
    const double theta = d.broyden.next(dx);
    // J0 is too far: a Jacobian at x, unless the residual is at the tolerance's level, where the
    // steps are rounding and theta measures noise.
    const bool near_tolerance =
        std::isfinite(theta) && fnorm_inf <= kBroydenNoise * options.fnormtol;
    if (!(theta < kBroydenMaxContraction) && !near_tolerance) {
      if (stats.jacobian_evaluations >= options.broyden_jacobians)
        return finish(false, "broyden: no contraction within broyden_jacobians Jacobians");
      if (!set_up()) return finish(false, "broyden: the Jacobian's set-up failed");
      d.broyden.clear();
      if (!simplified_step()) return finish(false, "broyden: the linear solve failed");
    }
    d.broyden.push(dx);
  }
}

}  // namespace rodlab::solvers
