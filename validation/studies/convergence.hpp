#pragma once
// `rodlab study convergence`: every scheme at every resolution against a reference solution,
// and the observed order of each scheme (study_fit.hpp). work-precision and recommend use the
// same sweep with timed repeats.
//
// With several grids (Settings::grids) each grid is a sweep of its own, on the scene with that
// grid and against its own reference; the rows and orders name their grid.
// Reference (said in the output): statics `kinsol` at max(4 x finest N, 200) nodes, or
// `chebyshev` at max(2 x finest N, 48) nodes (--reference chebyshev), solved at tolerance
// min(tol, 1e-12). Dynamics: `ida` at the same N (at min(tol, 1e-10), stepping to the finest
// step of that N) when the catalogue has it, else the finest step of the same scheme and N
// (Richardson: that run is the reference row and has no error).
// Error: statics, the distance of the tip position from the reference's [m]; dynamics, the
// same at t_end, and max_error the largest tip distance over the output times the run shares
// with its reference (within 1e-9 t_end; t_end at least).
#include <string>
#include <vector>

#include "studies/executor.hpp"
#include "studies/fit.hpp"
#include "studies/runs.hpp"
#include "studies/settings.hpp"

namespace rodlab::validation::study {

struct SweepRow {
  std::string role;  ///< "study" or "reference"
  RunSpec spec;
  std::string grid;  ///< dynamics: the spatial grid of the run (Settings::grids, or the scene's)
  RunRecord run;
  double h = 0.0;          ///< L / (N - 1) (statics) or the step used (dynamics)
  double error = 0.0;      ///< NaN when it cannot be measured
  double max_error = 0.0;  ///< dynamics; NaN for statics
  bool in_fit = false;
  std::string note;  ///< e.g. why the error is missing
};

struct SchemeOrder {
  std::string scheme;
  std::string grid;      ///< dynamics: the grid of the runs fitted
  int nodes = 0;         ///< dynamics: the N of this time refinement; 0 for statics
  std::string variable;  ///< "ds" or "dt"
  std::string expected;  ///< the catalogue's order
  OrderFit fit;
  double h_max = 0.0, h_min = 0.0;  ///< the range of the points used
};

struct Sweep {
  Json reference;  ///< what the errors are measured against
  std::vector<SweepRow> rows;
  std::vector<SchemeOrder> orders;
  double rounding_floor = 0.0;
  int failed = 0;        ///< study rows that did not converge
  bool by_grid = false;  ///< several grids swept (Settings::grids): the tables show each row's
};

/// Runs the sweep (collective under MPI; the result is complete on rank 0 only).
Sweep run_sweep(const Settings& settings, const Executor& executor);

/// DIR/convergence.csv and DIR/convergence_orders.csv contents.
std::string convergence_csv(const Sweep& sweep);
std::string orders_csv(const Sweep& sweep);
/// study.json (schema rodlab.study/1) for a sweep of `kind`.
Json sweep_json(const Sweep& sweep, const Settings& settings, const std::string& kind);
/// "scheme", or "scheme (grid)" in a sweep of several grids.
std::string scheme_label(const Sweep& sweep, const std::string& scheme, const std::string& grid);
/// The text tables printed on stdout.
std::string sweep_table(const Sweep& sweep, bool timing);
std::string orders_table(const Sweep& sweep);

}  // namespace rodlab::validation::study
