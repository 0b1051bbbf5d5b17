#pragma once
// What the two SUNDIALS adapters (kinsol_solver.cpp, ida_solver.cpp) share, so that neither
// repeats the other: RAII owners of the SUNDIALS objects, Eigen views of serial N_Vectors, the
// guard that turns a callback's exception into a SUNDIALS flag, and the fixed CSC sparsity
// pattern that an Eigen Jacobian callback fills and that is copied into the KLU SUNMatrix.
// Private to solvers/common: together with the two adapters, the only code that includes
// SUNDIALS headers.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <Eigen/Core>

#include "rodlab/solvers/common/deadline.hpp"
#include <Eigen/SparseCore>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "rodlab/check.hpp"

#include "serial_vector_ops.hpp"

namespace rodlab::solvers::sundials {

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
/// KINFree and IDAFree take the address of the memory pointer.
template <void (*Free)(void**)>
struct MemoryDeleter {
  void operator()(void* mem) const { Free(&mem); }
};

using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolverPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;
template <void (*Free)(void**)>
using MemoryPtr = std::unique_ptr<void, MemoryDeleter<Free>>;

/// `object`, or std::runtime_error("<module>: <call> returned NULL").
template <class T>
T check_created(T object, std::string_view module, const char* call) {
  if (object == nullptr)
    throw std::runtime_error(rodlab::format("{}: {} returned NULL", module, call));
  return object;
}

inline ContextPtr make_context(std::string_view module) {
  SUNContext ctx = nullptr;
  if (const int flag = SUNContext_Create(nullptr, &ctx); flag != 0 || ctx == nullptr)
    throw std::runtime_error(
        rodlab::format("{}: SUNContext_Create failed with flag {}", module, flag));
  return ContextPtr(ctx);
}

/// A serial vector with the compiled operations (serial_vector_ops.hpp); its clones inherit them.
inline VectorPtr make_vector(int n, SUNContext ctx, std::string_view module) {
  VectorPtr v(check_created(N_VNew_Serial(n, ctx), module, "N_VNew_Serial"));
  use_compiled_serial_ops(v.get());
  return v;
}

/// The storage of a serial N_Vector as an Eigen vector.
inline Eigen::Map<Eigen::VectorXd> view(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<Eigen::Index>(N_VGetLength(v))};
}

// --- callbacks --------------------------------------------------------------------------------

/// Runs a callback body (returning a SUNDIALS flag): an exception of type Recoverable becomes
/// the recoverable flag 1 with its message; any other exception is kept in `error` for
/// rethrowing once the SUNDIALS call has returned (flag -1: unrecoverable, the solver stops).
/// deal.II's pattern: C code never unwinds a C++ exception.
template <class Recoverable, class Body>
int guarded(std::string& message, std::exception_ptr& error, Body&& body) {
  try {
    check_deadline();  // the run's wall-time guard (deadline.hpp): unrecoverable, rethrown
    return body();
  } catch (const Recoverable& e) {
    message = e.what();
    return 1;
  } catch (...) {
    error = std::current_exception();
    return -1;
  }
}

/// The text of a SUNDIALS error-handler call: "module::function: message".
inline std::string error_text(const char* module, const char* function, const char* msg) {
  return std::string(module ? module : "") + "::" + (function ? function : "") + ": " +
         (msg ? msg : "");
}

// --- the Jacobian's sparsity pattern ----------------------------------------------------------

/// A square CSC sparsity pattern fixed at construction. The callback fills the values of an
/// Eigen matrix with exactly this pattern; fill() checks the pattern, the finiteness of the
/// values, and copies them into the SUNMatrix. The SUNMatrix gets its index arrays once, in
/// make_matrix(), whose zero operation is a no-op: KINSOL and IDA call SUNMatZero before every
/// Jacobian callback of a direct linear solver, and SUNMatZero_Sparse clears the values and
/// both index arrays, which fill() then had to copy back (with the zeroing, 6 % of a kinsol
/// statics solve at N = 100, bench_statics). fill() writes every value, and nothing else
/// writes the indices.
class JacobianPattern {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor>;

  /// `owner` names the adapter in messages (e.g. "KinsolSolver"). Throws std::invalid_argument
  /// for a non-square, empty or structurally empty pattern.
  JacobianPattern(const SparseMatrix& pattern, std::string_view owner) : owner_(owner) {
    RODLAB_THROW_UNLESS(pattern.rows() == pattern.cols() && pattern.rows() != 0,
                        "{}: expected a square non-empty Jacobian pattern, got {} x {}", owner_,
                        pattern.rows(), pattern.cols());
    J_ = pattern;
    J_.makeCompressed();
    RODLAB_THROW_UNLESS(J_.nonZeros() != 0, "{}: the Jacobian pattern is empty", owner_);
    std::fill(J_.valuePtr(), J_.valuePtr() + J_.nonZeros(), 0.0);
    outer_.assign(J_.outerIndexPtr(), J_.outerIndexPtr() + size() + 1);
    inner_.assign(J_.innerIndexPtr(), J_.innerIndexPtr() + J_.nonZeros());
  }

  int size() const { return static_cast<int>(J_.rows()); }

  /// A KLU-ready CSC SUNMatrix with this pattern.
  MatrixPtr make_matrix(SUNContext ctx) const {
    MatrixPtr A(check_created(SUNSparseMatrix(size(), size(), J_.nonZeros(), CSC_MAT, ctx),
                              "SUNDIALS", "SUNSparseMatrix"));
    copy_indices(A.get());
    std::fill(SUNSparseMatrix_Data(A.get()), SUNSparseMatrix_Data(A.get()) + J_.nonZeros(), 0.0);
    A->ops->zero = [](SUNMatrix) { return 0; };  // the operations are the matrix's own copy
    return A;
  }

  /// Zeroes the values, runs fill(J), and copies J into A. Returns false (A untouched) when a
  /// value is not finite; throws std::logic_error, with the pattern restored, when fill changed
  /// the pattern.
  template <class Fill>
  bool fill(SUNMatrix A, Fill&& fill_values) {
    std::fill(J_.valuePtr(), J_.valuePtr() + J_.nonZeros(), 0.0);
    fill_values(J_);
    if (!same_pattern()) {
      restore_pattern();
      throw std::logic_error(rodlab::format(
          "{}: the Jacobian callback changed the sparsity pattern (only values may be set)",
          owner_));
    }
    const double* values = J_.valuePtr();
    if (!Eigen::Map<const Eigen::ArrayXd>(values, J_.nonZeros()).allFinite())  // vectorised
      return false;
    std::copy(values, values + J_.nonZeros(), SUNSparseMatrix_Data(A));
    return true;
  }

 private:
  /// Whether J_ still has the pattern: its index arrays compared with memcmp (an element-wise
  /// loop against copies of SUNDIALS' index type was 1-2 % of a kinsol statics solve).
  bool same_pattern() const {
    const auto nnz = static_cast<std::size_t>(J_.nonZeros());
    return J_.isCompressed() && nnz == inner_.size() && J_.rows() == size() &&
           J_.cols() == size() &&
           std::memcmp(J_.outerIndexPtr(), outer_.data(), outer_.size() * sizeof(int)) == 0 &&
           std::memcmp(J_.innerIndexPtr(), inner_.data(), nnz * sizeof(int)) == 0;
  }

  /// J_ with the pattern's index arrays again (zero values), after a callback changed them.
  void restore_pattern() {
    const auto nnz = static_cast<Eigen::Index>(inner_.size());
    const std::vector<double> zeros(inner_.size(), 0.0);
    J_ = Eigen::Map<const SparseMatrix>(size(), size(), nnz, outer_.data(), inner_.data(),
                                        zeros.data());
  }

  void copy_indices(SUNMatrix A) const {  // widened to SUNDIALS' index type
    std::copy(outer_.begin(), outer_.end(), SUNSparseMatrix_IndexPointers(A));
    std::copy(inner_.begin(), inner_.end(), SUNSparseMatrix_IndexValues(A));
  }

  std::string owner_;
  SparseMatrix J_;
  std::vector<int> outer_, inner_;  // the pattern's column pointers and row indices
};

}  // namespace rodlab::solvers::sundials
