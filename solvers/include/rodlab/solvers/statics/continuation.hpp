#pragma once
// Load continuation shared by the statics schemes (shooting, chebyshev): walks the problem's load
// factor from 0, where the caller's start state solves exactly, to 1. Each step predicts the
// state at the next load factor (the caller's predictor for the first step, then the secant
// through the last two solutions), corrects it with the caller's solver, grows the step by 1.5
// (up to 0.5) after a success and halves it after a failure; it gives up when the step falls
// below 1e-4 ("stalled at load factor ...") or after 400 attempts.
//
// The state is whatever vector the caller solves for (scaled unknowns); the driver only forms
// linear combinations of states.
#include <functional>
#include <string>

#include <Eigen/Core>

namespace rodlab::solvers::statics {

/// One corrector solve at a load factor from a predicted state.
struct CorrectorResult {
  bool converged = false;
  Eigen::VectorXd state;       ///< the solution when converged (else the last iterate)
  double residual_norm = 0.0;
  std::string reason;          ///< why not, when not converged
};

struct ContinuationResult {
  bool converged = false;      ///< reached load factor 1
  Eigen::VectorXd state;       ///< solution at `load_factor`, the last one reached
  double load_factor = 0.0;    ///< last load factor solved (1 when converged)
  double residual_norm = 0.0;  ///< of the last corrector solve
  std::string reason;          ///< when not converged
};

struct ContinuationSteps {
  double first = 0.25, max = 0.5, growth = 1.5, min = 1e-4;
  int max_attempts = 400;
};

struct Continuation {
  /// Solves at load factor `lf` from `guess`.
  std::function<CorrectorResult(double lf, const Eigen::VectorXd& guess)> correct;
  /// Predicts the first step from (from, state) to `to`; the secant takes over afterwards.
  std::function<Eigen::VectorXd(double from, double to, const Eigen::VectorXd& state)> first_predictor;
  /// Optional: called after each converged step; returning true stops the walk there (the result
  /// is then not converged, with the reason the callback wrote).
  std::function<bool(double lf, const Eigen::VectorXd& state, std::string& reason)> stop;
  ContinuationSteps steps;
};

/// Walks from load factor 0 with state `start` (an exact solution there) to 1.
ContinuationResult continue_load(const Continuation& walk, Eigen::VectorXd start);

/// The corrector tolerance of continue_load_to's second walk.
inline constexpr double kWalkTol = 1e-9;

/// The walk walk_at(tol), whose correctors solve to `tol`; if it fails and tol < kWalkTol, the
/// walk walk_at(kWalkTol), and its solution polished at load factor 1 by `polish` (Newton from
/// within kWalkTol of the branch stays on it). Correctors held to a tolerance near the rounding
/// level cut line-search steps in the noise, which the walk takes for leaving the branch (soft
/// cantilevers at tol 1e-12, docs/statics.md "Tolerances near the rounding level"); walks that
/// pass at `tol` are unchanged. A failed polish returns load factor 1 and the polished state,
/// not converged; a failed second walk returns the first walk's result, both reasons named.
ContinuationResult continue_load_to(
    double tol, const std::function<Continuation(double corrector_tol)>& walk_at,
    const Eigen::VectorXd& start,
    const std::function<CorrectorResult(const Eigen::VectorXd& state)>& polish);

}  // namespace rodlab::solvers::statics
