#pragma once
// `rodlab study stability` (dynamics): where the time steppers stop working.
//
// (a) Explicit schemes (catalogue: dynamics, not implicit, not the reference): for every
//     Young's modulus E (settings.moduli; G scaled with E, so Poisson's ratio is kept) and
//     every N, the largest stable step, bisected (geometric midpoints, to 0.5 %) between a
//     stable and an unstable step. A run is kExplicitSteps steps from the scene's initial
//     state; stable = converged (solve_dynamic reports a blow-up as converged = false,
//     "unstable: ..."). Reported against the linear limit variational_stable_step: the ratio
//     is the safety factor `dt: auto` may use.
// (b, c) Implicit schemes (every available implicit non-reference dynamics scheme: single
//     shooting, collocation, ...): from the scheme's `dt: auto`, the step is divided by 3 until
//     a run fails or dt < kScanMin, and multiplied by 3 until a run fails or dt > kScanMax
//     (or the run length). A run covers min(t_end, kScanSteps dt). This gives single shooting's
//     lower bound and collocation's behaviour at both ends.
#include <string>
#include <vector>

#include "studies/executor.hpp"
#include "studies/settings.hpp"

namespace rodlab::validation::study {

inline constexpr long kExplicitSteps = 2000;
inline constexpr long kScanSteps = 2000;
inline constexpr double kScanMin = 1e-6, kScanMax = 1e-1, kScanFactor = 3.0;
inline constexpr double kBisectionRatio = 1.005;

/// The default moduli of part (a) [Pa].
std::vector<double> default_moduli();
/// Part (a)'s default node counts.
std::vector<int> default_stability_nodes();

struct ExplicitLimit {
  std::string scheme;
  double E = 0.0;
  int nodes = 0;
  double dt_linear = 0.0;    ///< variational_stable_step
  double dt_max = 0.0;       ///< largest step measured stable (0: none found)
  double dt_unstable = 0.0;  ///< smallest step measured unstable (0: none found)
  int runs = 0;
  double wall_time_s = 0.0;  ///< all runs of the bisection
  std::string note;
};

struct ScanPoint {
  std::string scheme;
  int nodes = 0;
  double dt_auto = 0.0;
  double dt = 0.0;
  std::string direction;  ///< "down" or "up" from dt_auto
  bool converged = false;
  std::string reason;
  double t_run = 0.0;
  long steps = 0;
  double wall_time_s = 0.0;
};

struct ScanSummary {
  std::string scheme;
  int nodes = 0;
  double dt_auto = 0.0;
  double smallest_ok = 0.0, first_failed_below = 0.0;  ///< 0: none
  double largest_ok = 0.0, first_failed_above = 0.0;   ///< 0: none
};

struct Stability {
  std::vector<ExplicitLimit> limits;
  std::vector<ScanPoint> scan;
  std::vector<ScanSummary> summaries;
};

/// Collective under MPI; complete on rank 0 only.
Stability run_stability(const Settings& settings, const Executor& executor);

std::string explicit_csv(const Stability& study);
std::string implicit_csv(const Stability& study);
Json stability_json(const Stability& study, const Settings& settings);
std::string stability_table(const Stability& study);

}  // namespace rodlab::validation::study
