#include "studies/stable_step.hpp"

#include <cmath>

namespace rodlab::validation::study {

StepBracket bisect_stable_step(const std::function<bool(double)>& stable, double lo, double hi,
                               double ratio) {
  StepBracket b{lo, hi, 0};
  while (b.unstable / b.stable > ratio) {
    const double mid = std::sqrt(b.stable * b.unstable);
    ++b.runs;
    (stable(mid) ? b.stable : b.unstable) = mid;
  }
  return b;
}

}  // namespace rodlab::validation::study
