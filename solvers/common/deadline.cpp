#include "rodlab/solvers/common/deadline.hpp"

#include "rodlab/check.hpp"

namespace rodlab::solvers {
namespace {

thread_local std::optional<std::chrono::steady_clock::time_point> t_deadline;
thread_local double t_seconds = 0.0;

}  // namespace

DeadlineScope::DeadlineScope(double seconds)
    : previous_deadline_(t_deadline), previous_seconds_(t_seconds) {
  if (seconds > 0.0) {
    t_deadline = std::chrono::steady_clock::now() +
                 std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                     std::chrono::duration<double>(seconds));
    t_seconds = seconds;
  }
}

DeadlineScope::~DeadlineScope() {
  t_deadline = previous_deadline_;
  t_seconds = previous_seconds_;
}

void check_deadline() {
  if (t_deadline && std::chrono::steady_clock::now() > *t_deadline)
    throw WallTimeExceeded(rodlab::format("the wall-time limit of {:g} s was reached", t_seconds));
}

}  // namespace rodlab::solvers
