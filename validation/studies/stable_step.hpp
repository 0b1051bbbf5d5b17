#pragma once
// The largest stable time step, measured: one bisection for `rodlab study stability` and the
// dynamics checks of `rodlab validate` (each with its own runs; `stable(dt)` says whether a run
// at dt stayed stable, solve_dynamic reporting a blow-up as converged = false).
#include <functional>

namespace rodlab::validation::study {

struct StepBracket {
  double stable = 0.0;    ///< largest step measured stable
  double unstable = 0.0;  ///< smallest step measured unstable
  int runs = 0;           ///< calls of stable()
};

/// Geometric bisection of [lo, hi], lo stable and hi unstable (not checked), until
/// hi / lo <= ratio.
StepBracket bisect_stable_step(const std::function<bool(double)>& stable, double lo, double hi,
                               double ratio);

}  // namespace rodlab::validation::study
