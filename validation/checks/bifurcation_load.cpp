// The bifurcation load of a straight equilibrium by its vanishing stiffness (bifurcation_load.hpp).
#include "checks/bifurcation_load.hpp"

#include <cmath>

namespace rodlab::validation {
namespace {

/// The root nearest the last point of the quadratic through the last three points (Newton's
/// form about the last point, solved by Newton's method from the secant root).
double quadratic_root(const std::vector<BifurcationPoint>& p) {
  const auto& a = p[p.size() - 3];
  const auto& b = p[p.size() - 2];
  const auto& c = p[p.size() - 1];
  const double d1 = (c.stiffness - b.stiffness) / (c.load - b.load);
  const double d0 = (b.stiffness - a.stiffness) / (b.load - a.load);
  const double d2 = (d1 - d0) / (c.load - a.load);
  const auto f = [&](double x) { return c.stiffness + (x - c.load) * (d1 + d2 * (x - b.load)); };
  const auto df = [&](double x) { return d1 + d2 * (2.0 * x - c.load - b.load); };
  double x = c.load - c.stiffness / d1;
  for (int i = 0; i < 50; ++i) x -= f(x) / df(x);
  return x;
}

}  // namespace

BifurcationLoad bifurcation_load(
    const std::function<std::optional<double>(double lambda, double h)>& deflection, double guess,
    double deflection_target) {
  BifurcationLoad out;
  // One measurement at load lambda whose deflection is expected near the target for the
  // stiffness `expected`; false when the solve failed or the rod buckled (past the root).
  const auto measure = [&](double lambda, double expected) {
    const double h = deflection_target * expected;
    const auto d = deflection(lambda, h);
    if (!d || !(std::abs(*d) < 100.0 * deflection_target) || *d == 0.0) return false;
    out.points.push_back({lambda, h / *d});
    return true;
  };
  // The first point: a trial imperfection gives the stiffness, the second solve the target.
  const auto trial = deflection(0.7 * guess, 1e-6 * guess);
  if (!trial || *trial == 0.0) return out;
  if (!measure(0.7 * guess, 1e-6 * guess / *trial)) return out;
  for (double f : {0.8, 0.9})
    if (!measure(f * guess, out.points.back().stiffness)) return out;
  // Halve the gap to the estimated root until it is below 1e-3 of it: a new load stays below the
  // critical one as long as the estimate overshoots by less than the gap.
  for (int i = 0;; ++i) {
    const double root = quadratic_root(out.points);
    const auto& last = out.points.back();
    const double gap = root - last.load;
    if (gap < 1e-3 * root) break;
    if (i == 20) return out;
    const double lambda = last.load + 0.5 * gap;
    // The stiffness falls linearly to zero at the root: expect half of it at the new load.
    if (!measure(lambda, 0.5 * last.stiffness)) return out;
  }
  out.load = quadratic_root(out.points);
  out.ok = true;
  return out;
}

}  // namespace rodlab::validation
