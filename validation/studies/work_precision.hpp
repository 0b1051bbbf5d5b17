#pragma once
// `rodlab study work-precision`: the convergence sweep with timed runs (median of --repeats),
// and the Pareto front of error against wall time over every scheme and resolution.
// `rodlab study recommend`: from such measurements, the fastest run that meets a tolerance.
#include <optional>
#include <string>
#include <vector>

#include "studies/convergence.hpp"

namespace rodlab::validation::study {

/// Per sweep row: on the Pareto front (a converged study run with a measured error that no
/// other such run beats in both error and median wall time).
std::vector<bool> pareto_front(const Sweep& sweep);

/// DIR/work_precision.csv.
std::string work_precision_csv(const Sweep& sweep, const std::vector<bool>& pareto);
/// study.json of a work-precision sweep (sweep_json plus the pareto flags).
Json work_precision_json(const Sweep& sweep, const std::vector<bool>& pareto,
                         const Settings& settings);

struct Candidate {
  std::string scheme;
  std::string grid;  ///< dynamics: the run's spatial grid (empty in rows written before it)
  int nodes = 0;
  std::optional<double> dt;
  double error = 0.0;
  double wall_time_s = 0.0;
  int repeats = 0;
};

struct Recommendation {
  std::optional<Candidate> best;           ///< fastest with error <= tol within the budget
  std::optional<Candidate> most_accurate;  ///< smallest error measured (when none qualifies)
  std::optional<Candidate> fastest_meeting_tol;  ///< ignoring the budget
  int candidates = 0;                            ///< converged study runs considered
};

/// Which error of a row recommend() compares with tol: the tip error at t_end (statics, and the
/// per-N time refinement), or its largest value over the run (`max_error`: the grid
/// refinement, whose error is that of space and time together).
enum class ErrorMeasure { at_end, over_the_run };

/// From the rows of a work-precision study.json.
Recommendation recommend(const Json& rows, double tol, std::optional<double> budget_ms,
                         ErrorMeasure measure = ErrorMeasure::at_end);

}  // namespace rodlab::validation::study
