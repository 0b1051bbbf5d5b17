#include "rodlab/solvers/statics/continuation.hpp"

#include <algorithm>

#include "rodlab/check.hpp"

namespace rodlab::solvers::statics {

ContinuationResult continue_load(const Continuation& walk, Eigen::VectorXd start) {
  const ContinuationSteps& steps = walk.steps;
  double lf = 0.0, lf_prev = 0.0, step = steps.first;
  Eigen::VectorXd x = std::move(start), x_prev = x;
  bool have_prev = false;
  CorrectorResult last;
  auto finish = [&](bool converged, std::string reason) {
    ContinuationResult out;
    out.converged = converged;
    out.state = x;
    out.load_factor = lf;
    out.residual_norm = last.residual_norm;
    out.reason = std::move(reason);
    return out;
  };
  for (int attempt = 0; attempt < steps.max_attempts && lf < 1.0; ++attempt) {
    const double target = std::min(1.0, lf + step);
    const Eigen::VectorXd guess = have_prev
                                      ? Eigen::VectorXd(x + (x - x_prev) * ((target - lf) / (lf - lf_prev)))
                                      : walk.first_predictor(lf, target, x);
    last = walk.correct(target, guess);
    if (last.converged) {
      x_prev = x;
      lf_prev = lf;
      x = last.state;
      lf = target;
      have_prev = true;
      step = std::min(steps.growth * step, steps.max);
      std::string why;
      if (walk.stop && lf < 1.0 && walk.stop(lf, x, why)) return finish(false, why);
    } else {
      step *= 0.5;
      if (step < steps.min)
        return finish(false, rodlab::format("stalled at load factor {:g} ({})", lf, last.reason));
    }
  }
  if (lf < 1.0) return finish(false, last.reason);
  return finish(true, last.reason);
}

ContinuationResult continue_load_to(
    double tol, const std::function<Continuation(double corrector_tol)>& walk_at,
    const Eigen::VectorXd& start,
    const std::function<CorrectorResult(const Eigen::VectorXd& state)>& polish) {
  ContinuationResult first = continue_load(walk_at(tol), start);
  if (first.converged || tol >= kWalkTol) return first;
  ContinuationResult loose = continue_load(walk_at(kWalkTol), start);
  const std::string walked = "; walked to " + rodlab::format("{:g}", kWalkTol);
  if (!loose.converged) {
    first.reason += walked + ": " + loose.reason;
    return first;
  }
  const CorrectorResult polished = polish(loose.state);
  loose.converged = polished.converged;
  loose.state = polished.state;
  loose.residual_norm = polished.residual_norm;
  if (!polished.converged)
    loose.reason = first.reason + walked + ", then polishing at load factor 1: " + polished.reason;
  return loose;
}

}  // namespace rodlab::solvers::statics
