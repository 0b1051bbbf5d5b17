#pragma once
// The wall-time guard of a run (`--max-wall-time`, DynamicSolveOptions / StaticSolveOptions
// ::max_wall_time): a deadline per thread, set for the length of a solve by DeadlineScope and
// checked inside every long computation (the residual callbacks of KINSOL and IDA, the Newton
// loops of shooting and Chebyshev collocation, and inside Chebyshev's Newton matrix factorisation
// between its stages and LU blocks, deadline_lu.hpp), so that no single step or solve can overrun
// it by more than one residual evaluation or one block of a factorisation. solve_dynamic and
// solve_static turn WallTimeExceeded into a not-converged result whose reason names the limit.
#include <chrono>
#include <optional>
#include <stdexcept>

namespace rodlab::solvers {

/// Thrown by check_deadline() once the current thread's deadline has passed.
class WallTimeExceeded : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Sets the current thread's deadline to now + seconds (none when seconds <= 0) for its
/// lifetime; restores the previous one on destruction.
class DeadlineScope {
 public:
  explicit DeadlineScope(double seconds);
  ~DeadlineScope();
  DeadlineScope(const DeadlineScope&) = delete;
  DeadlineScope& operator=(const DeadlineScope&) = delete;

 private:
  std::optional<std::chrono::steady_clock::time_point> previous_deadline_;
  double previous_seconds_;
};

/// Throws WallTimeExceeded ("the wall-time limit of S s was reached") when the current thread
/// has a deadline and it has passed; otherwise nothing (a clock read).
void check_deadline();

}  // namespace rodlab::solvers
