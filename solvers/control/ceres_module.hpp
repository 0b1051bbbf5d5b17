#pragma once
// The interface between inverse statics' method `ceres` (inverse_statics.cpp) and the Ceres
// module (solvers/ceres/ceres_module.cpp, built as the shared module librodlab_ceres.so). The
// module is loaded (rodlab/module.hpp) only by a solve with that method, so no other run maps
// Ceres' dependencies (glog, gflags, SuiteSparse's CHOLMOD and SPQR, LAPACK, BLAS: 17 shared
// objects; with the MPI module's, 4.2 of the 8.3 ms `rodlab --version` took, docs/performance.md
// "Process start-up").
//
// C linkage and plain C types: the table is all the two sides share, and the module is the only
// code compiled against Ceres' headers.

extern "C" {

/// A bounded nonlinear least-squares problem min 1/2 |r(x)|^2, lower <= x <= upper, solved by
/// Ceres' trust-region Levenberg-Marquardt with a dense QR step.
struct RodlabLeastSquares {
  int residuals;   ///< size of r
  int parameters;  ///< size of x
  double* x;       ///< the start on entry, the result on return
  const double* lower;
  const double* upper;
  /// r(x) into `r`, and dr/dx (row-major, residuals x parameters) into `jacobian` unless it is
  /// null; returns 0 when x cannot be evaluated (Ceres then shrinks its step).
  int (*evaluate)(void* user, const double* x, double* r, double* jacobian);
  /// Called after each accepted step with its norm; returns 1 to stop successfully.
  int (*accepted_step)(void* user, double step_norm);
  void* user;
  double initial_trust_region_radius;
  int max_iterations;
  double function_tolerance, gradient_tolerance, parameter_tolerance;
};

struct RodlabLeastSquaresSummary {
  int usable;          ///< Ceres' Summary::IsSolutionUsable()
  int no_convergence;  ///< the termination type was NO_CONVERGENCE
  char message[512];   ///< Ceres' Summary::message, truncated
};

struct RodlabCeresApi {
  void (*solve)(const RodlabLeastSquares* problem, RodlabLeastSquaresSummary* summary);
};

/// The module's one exported symbol.
const RodlabCeresApi* rodlab_ceres_api();
}

/// Its name, for rodlab::load_module (rodlab/module.hpp).
inline constexpr const char* kRodlabCeresApiSymbol = "rodlab_ceres_api";
