#include "rodlab/solvers/common/ida_solver.hpp"

#include <cmath>
#include <cstdlib>
#include <exception>
#include <string>
#include <utility>

#include <ida/ida.h>

#include "rodlab/check.hpp"

#include "condensed_block_solver.hpp"
#include "sundials_support.hpp"

namespace rodlab::solvers {
namespace {

using sundials::view;

// --- flag names and checks ------------------------------------------------------------------

/// The names of ida.h, spelled out as in kinsol_solver.cpp; unknown flags fall back to
/// IDAGetReturnFlagName.
std::string ida_flag_name(long flag) {
  switch (flag) {
    case IDA_SUCCESS: return "IDA_SUCCESS";
    case IDA_TSTOP_RETURN: return "IDA_TSTOP_RETURN";
    case IDA_ROOT_RETURN: return "IDA_ROOT_RETURN";
    case IDA_WARNING: return "IDA_WARNING";
    case IDA_TOO_MUCH_WORK: return "IDA_TOO_MUCH_WORK";
    case IDA_TOO_MUCH_ACC: return "IDA_TOO_MUCH_ACC";
    case IDA_ERR_FAIL: return "IDA_ERR_FAIL";
    case IDA_CONV_FAIL: return "IDA_CONV_FAIL";
    case IDA_LINIT_FAIL: return "IDA_LINIT_FAIL";
    case IDA_LSETUP_FAIL: return "IDA_LSETUP_FAIL";
    case IDA_LSOLVE_FAIL: return "IDA_LSOLVE_FAIL";
    case IDA_RES_FAIL: return "IDA_RES_FAIL";
    case IDA_REP_RES_ERR: return "IDA_REP_RES_ERR";
    case IDA_RTFUNC_FAIL: return "IDA_RTFUNC_FAIL";
    case IDA_CONSTR_FAIL: return "IDA_CONSTR_FAIL";
    case IDA_FIRST_RES_FAIL: return "IDA_FIRST_RES_FAIL";
    case IDA_LINESEARCH_FAIL: return "IDA_LINESEARCH_FAIL";
    case IDA_NO_RECOVERY: return "IDA_NO_RECOVERY";
    case IDA_NLS_INIT_FAIL: return "IDA_NLS_INIT_FAIL";
    case IDA_NLS_SETUP_FAIL: return "IDA_NLS_SETUP_FAIL";
    case IDA_NLS_FAIL: return "IDA_NLS_FAIL";
    case IDA_MEM_NULL: return "IDA_MEM_NULL";
    case IDA_MEM_FAIL: return "IDA_MEM_FAIL";
    case IDA_ILL_INPUT: return "IDA_ILL_INPUT";
    case IDA_NO_MALLOC: return "IDA_NO_MALLOC";
    case IDA_BAD_EWT: return "IDA_BAD_EWT";
    case IDA_BAD_K: return "IDA_BAD_K";
    case IDA_BAD_T: return "IDA_BAD_T";
    case IDA_BAD_DKY: return "IDA_BAD_DKY";
    case IDA_VECTOROP_ERR: return "IDA_VECTOROP_ERR";
    case IDA_CONTEXT_ERR: return "IDA_CONTEXT_ERR";
    default: break;
  }
  // IDAGetReturnFlagName returns a malloc'ed string that the caller frees.
  char* name = IDAGetReturnFlagName(flag);
  if (!name) return rodlab::format("IDA flag {}", flag);
  std::string out(name);
  std::free(name);
  return out;
}

std::string idals_flag_name(long flag) {
  char* name = IDAGetLinReturnFlagName(flag);
  if (!name) return rodlab::format("IDALS flag {}", flag);
  std::string out(name);
  std::free(name);
  return out;
}

void check_ida(int flag, const char* call) {
  if (flag != IDA_SUCCESS)
    throw std::runtime_error(rodlab::format("IDA: {} failed with {}", call, ida_flag_name(flag)));
}

void check_idals(int flag, const char* call) {
  if (flag != IDALS_SUCCESS)
    throw std::runtime_error(rodlab::format("IDA: {} failed with {}", call, idals_flag_name(flag)));
}

}  // namespace

struct IdaSolver::Impl {
  explicit Impl(const SparseMatrix& pattern) : pattern(pattern, "IdaSolver") {}

  // Declaration order is destruction order reversed: the context outlives everything, the IDA
  // memory (which refers to the vectors, matrix and linear solver) goes first.
  sundials::ContextPtr context;
  sundials::VectorPtr y, yp, atol, id;
  bool suppress_algebraic = false;
  sundials::MatrixPtr A;
  sundials::LinearSolverPtr linear_solver;
  sundials::MemoryPtr<IDAFree> memory;
  sundials::JacobianPattern pattern;  // the Jacobian callback writes its values
  bool initialized = false;
  double rtol = 0.0;  // IDASVtolerances must follow IDAInit: kept until initialize()
  double t = 0.0;
  Residual residual;
  Jacobian jacobian;
  // Per advance(): a callback's exception to rethrow, IDA's last message, the last flag.
  std::exception_ptr error;
  std::string message;
  int last_flag = 0;

  template <class Body>
  int guarded(Body&& body) {
    return sundials::guarded<IdaRecoverableError>(message, error, body);
  }

  static int residual_callback(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void* user_data) {
    auto& self = *static_cast<Impl*>(user_data);
    return self.guarded([&] {
      auto rv = view(r);
      self.residual(t, view(y), view(yp), rv);
      return rv.allFinite() ? 0 : 1;  // non-finite: recoverable (IDA retries with a smaller step)
    });
  }

  static int jacobian_callback(sunrealtype t, sunrealtype cj, N_Vector y, N_Vector yp, N_Vector r,
                               SUNMatrix A, void* user_data, N_Vector, N_Vector, N_Vector) {
    auto& self = *static_cast<Impl*>(user_data);
    return self.guarded([&] {
      const bool finite = self.pattern.fill(
          A, [&](SparseMatrix& J) { self.jacobian(t, cj, view(y), view(yp), view(r), J); });
      if (finite) return 0;
      self.message = "the Jacobian has non-finite entries";
      return 1;
    });
  }

  static void error_handler(int, const char* module, const char* function, char* msg, void* user_data) {
    static_cast<Impl*>(user_data)->message = sundials::error_text(module, function, msg);
  }

  /// Counters since IDAInit / IDAReInit.
  IdaStats counters() const {
    void* mem = memory.get();
    IdaStats s;
    long value = 0;
    check_ida(IDAGetNumSteps(mem, &value), "IDAGetNumSteps");
    s.steps = value;
    check_ida(IDAGetNumResEvals(mem, &value), "IDAGetNumResEvals");
    s.residual_evaluations = value;
    check_idals(IDAGetNumJacEvals(mem, &value), "IDAGetNumJacEvals");
    s.jacobian_evaluations = value;
    check_ida(IDAGetNumLinSolvSetups(mem, &value), "IDAGetNumLinSolvSetups");
    s.linear_setups = value;
    check_ida(IDAGetNumNonlinSolvIters(mem, &value), "IDAGetNumNonlinSolvIters");
    s.nonlinear_iterations = value;
    check_ida(IDAGetNumNonlinSolvConvFails(mem, &value), "IDAGetNumNonlinSolvConvFails");
    s.nonlinear_convergence_failures = value;
    check_ida(IDAGetNumErrTestFails(mem, &value), "IDAGetNumErrTestFails");
    s.error_test_failures = value;
    if (s.steps > 0) {
      int order = 0;
      check_ida(IDAGetLastOrder(mem, &order), "IDAGetLastOrder");
      s.last_order = order;
      sunrealtype h = 0.0;
      check_ida(IDAGetLastStep(mem, &h), "IDAGetLastStep");
      s.last_step = h;
    }
    s.t = t;
    s.flag = last_flag;
    s.flag_name = ida_flag_name(last_flag);
    s.ok = last_flag == IDA_SUCCESS || last_flag == IDA_TSTOP_RETURN;
    return s;
  }
};

IdaSolver::IdaSolver(const SparseMatrix& pattern, Residual residual, Jacobian jacobian,
                     const IdaSolverOptions& options)
    : impl_(std::make_unique<Impl>(pattern)) {
  if (!residual || !jacobian) throw std::invalid_argument("IdaSolver: empty residual or Jacobian");
  const auto n = pattern.rows();
  RODLAB_THROW_UNLESS(options.atol.size() == n, "IdaSolver: atol: expected size {}, got {}", n,
                      options.atol.size());
  if (!options.atol.allFinite() || !(options.atol.minCoeff() > 0.0))
    throw std::invalid_argument("IdaSolver: atol must be finite and > 0");
  RODLAB_THROW_UNLESS(options.rtol > 0.0 && std::isfinite(options.rtol),
                      "IdaSolver: rtol must be > 0, got {:g}", options.rtol);
  RODLAB_THROW_UNLESS(options.max_steps >= 1, "IdaSolver: max_steps must be >= 1, got {}",
                      options.max_steps);
  RODLAB_THROW_UNLESS(options.max_order >= 1 && options.max_order <= 5,
                      "IdaSolver: max_order must be 1..5, got {}", options.max_order);
  if (!(options.max_step >= 0.0) || !(options.initial_step >= 0.0))
    throw std::invalid_argument("IdaSolver: max_step and initial_step must be >= 0");

  Impl& d = *impl_;
  d.residual = std::move(residual);
  d.jacobian = std::move(jacobian);
  d.context = sundials::make_context("IDA");
  SUNContext ctx = d.context.get();
  const int size = d.pattern.size();
  d.y = sundials::make_vector(size, ctx, "IDA");
  d.yp = sundials::make_vector(size, ctx, "IDA");
  d.atol = sundials::make_vector(size, ctx, "IDA");
  view(d.y.get()).setZero();
  view(d.yp.get()).setZero();
  view(d.atol.get()) = options.atol;
  if (options.id.size() != 0) {
    RODLAB_THROW_UNLESS(options.id.size() == n, "IdaSolver: id: expected size {}, got {}", n,
                        options.id.size());
    for (Eigen::Index i = 0; i < n; ++i)
      if (options.id[i] != 0.0 && options.id[i] != 1.0)
        throw std::invalid_argument("IdaSolver: id entries must be 0 (algebraic) or 1");
    d.id = sundials::make_vector(size, ctx, "IDA");
    view(d.id.get()) = options.id;
  }
  d.suppress_algebraic = options.suppress_algebraic;
  d.A = d.pattern.make_matrix(ctx);
  if (options.linear_solver == NewtonLinearSolver::condensed_rod_blocks) {
    d.linear_solver.reset(sundials::make_condensed_block_solver(d.A.get(), ctx, true));
    if (!d.linear_solver)
      throw std::invalid_argument(
          "IdaSolver: condensed_rod_blocks needs a pattern of its form (newton_linear_solver.hpp)");
  } else {
    d.linear_solver.reset(
        sundials::check_created(SUNLinSol_KLU(d.y.get(), d.A.get(), ctx), "IDA", "SUNLinSol_KLU"));
  }

  // IDAInit needs the initial state; it and everything that must follow it happen in
  // initialize(). The options that may precede it are set here.
  d.memory.reset(sundials::check_created(IDACreate(ctx), "IDA", "IDACreate"));
  void* mem = d.memory.get();
  check_ida(IDASetUserData(mem, &d), "IDASetUserData");
  check_ida(IDASetErrHandlerFn(mem, &Impl::error_handler, &d), "IDASetErrHandlerFn");
  check_ida(IDASetMaxNumSteps(mem, options.max_steps), "IDASetMaxNumSteps");
  check_ida(IDASetMaxOrd(mem, options.max_order), "IDASetMaxOrd");
  if (options.max_step > 0.0) check_ida(IDASetMaxStep(mem, options.max_step), "IDASetMaxStep");
  if (options.initial_step > 0.0) check_ida(IDASetInitStep(mem, options.initial_step), "IDASetInitStep");
  d.rtol = options.rtol;
}

IdaSolver::~IdaSolver() = default;
IdaSolver::IdaSolver(IdaSolver&&) noexcept = default;
IdaSolver& IdaSolver::operator=(IdaSolver&&) noexcept = default;

int IdaSolver::size() const { return impl_->pattern.size(); }

void IdaSolver::initialize(double t0, const Vector& y0, const Vector& yp0) {
  Impl& d = *impl_;
  const auto n = static_cast<Eigen::Index>(d.pattern.size());
  RODLAB_THROW_UNLESS(y0.size() == n && yp0.size() == n,
                      "IdaSolver::initialize: expected y0 and yp0 of size {}, got {} and {}", n,
                      y0.size(), yp0.size());
  if (!std::isfinite(t0) || !y0.allFinite() || !yp0.allFinite())
    throw std::invalid_argument("IdaSolver::initialize: t0, y0 and yp0 must be finite");
  view(d.y.get()) = y0;
  view(d.yp.get()) = yp0;
  void* mem = d.memory.get();
  if (!d.initialized) {
    check_ida(IDAInit(mem, &Impl::residual_callback, t0, d.y.get(), d.yp.get()), "IDAInit");
    check_ida(IDASVtolerances(mem, d.rtol, d.atol.get()), "IDASVtolerances");
    check_idals(IDASetLinearSolver(mem, d.linear_solver.get(), d.A.get()), "IDASetLinearSolver");
    check_idals(IDASetJacFn(mem, &Impl::jacobian_callback), "IDASetJacFn");
    if (d.id) {
      check_ida(IDASetId(mem, d.id.get()), "IDASetId");
      check_ida(IDASetSuppressAlg(mem, d.suppress_algebraic ? SUNTRUE : SUNFALSE),
                "IDASetSuppressAlg");
    }
    d.initialized = true;
  } else {
    check_ida(IDAReInit(mem, t0, d.y.get(), d.yp.get()), "IDAReInit");
  }
  d.t = t0;
  d.last_flag = IDA_SUCCESS;
  d.message.clear();
}

IdaStats IdaSolver::advance(double tout) {
  Impl& d = *impl_;
  if (!d.initialized) throw std::logic_error("IdaSolver::advance: initialize() was not called");
  RODLAB_THROW_UNLESS(std::isfinite(tout) && tout > d.t,
                      "IdaSolver::advance: tout = {:g} must be finite and after the current time "
                      "{:g}",
                      tout, d.t);
  void* mem = d.memory.get();
  const IdaStats before = d.counters();
  d.error = nullptr;
  d.message.clear();
  check_ida(IDASetStopTime(mem, tout), "IDASetStopTime");
  sunrealtype tret = d.t;
  const int flag = IDASolve(mem, tout, &tret, d.y.get(), d.yp.get(), IDA_NORMAL);
  d.t = tret;
  d.last_flag = flag;
  if (d.error) {
    std::exception_ptr e = std::exchange(d.error, nullptr);
    std::rethrow_exception(e);
  }
  switch (flag) {
    case IDA_MEM_NULL:
    case IDA_ILL_INPUT:
    case IDA_NO_MALLOC:
    case IDA_MEM_FAIL:
    case IDA_LINIT_FAIL:
    case IDA_NLS_INIT_FAIL:
    case IDA_VECTOROP_ERR:
    case IDA_CONTEXT_ERR:
      // Set-up errors, not integration failures.
      throw std::runtime_error(rodlab::format("IDA: IDASolve failed with {}{}", ida_flag_name(flag),
                                              d.message.empty() ? "" : " (" + d.message + ")"));
    default: break;
  }
  IdaStats s = d.counters();
  s.message = s.ok ? std::string() : d.message;
  s.steps -= before.steps;
  s.residual_evaluations -= before.residual_evaluations;
  s.jacobian_evaluations -= before.jacobian_evaluations;
  s.linear_setups -= before.linear_setups;
  s.nonlinear_iterations -= before.nonlinear_iterations;
  s.nonlinear_convergence_failures -= before.nonlinear_convergence_failures;
  s.error_test_failures -= before.error_test_failures;
  return s;
}

double IdaSolver::time() const { return impl_->t; }

Eigen::Map<const IdaSolver::Vector> IdaSolver::y() const {
  const N_Vector v = impl_->y.get();
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

Eigen::Map<const IdaSolver::Vector> IdaSolver::yp() const {
  const N_Vector v = impl_->yp.get();
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

IdaStats IdaSolver::statistics() const {
  if (!impl_->initialized) return {};
  IdaStats s = impl_->counters();
  s.message = impl_->message;
  return s;
}

}  // namespace rodlab::solvers
