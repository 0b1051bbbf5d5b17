#pragma once
// Runs a study's independent tasks: split across the MPI ranks round robin (task i on rank
// i mod K), each rank's share on `jobs` threads, and every result gathered on rank 0 in task
// order. The results depend only on the tasks, never on K or `jobs` (the solvers keep no
// shared mutable state: per-solve SUNDIALS contexts, a thread_local Chebyshev cache), so a
// study's deterministic columns are the same however it is split; only timings differ.
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "studies/processes.hpp"

namespace rodlab::validation::study {

using Json = nlohmann::json;

struct Executor {
  int jobs = 1;                          ///< threads per rank
  const Processes* processes = nullptr;  ///< nullptr: one process
  /// Called after each of this rank's tasks (one call at a time): tasks done of this rank's.
  std::function<void(long done, long total)> progress;
};

/// Collective across ranks. On rank 0 (or without MPI): every task's result, in task order.
/// On the other ranks: an empty list. A task that throws yields {"error": message}.
std::vector<Json> run_tasks(const std::vector<std::function<Json()>>& tasks,
                            const Executor& executor);

}  // namespace rodlab::validation::study
