#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rodlab/check.hpp"

namespace rodlab::solvers::dynamics {

double single_shooting_exponent(const DynamicProblem& problem, double dt) {
  const auto& model = problem.model();
  const auto& K = model.K_diag();
  const auto& M = model.M_diag();
  const auto& V = model.V_diag();
  const double c = 2.0 / dt;
  const Vector6 Kt = K + c * V;
  double k = 0.0;
  for (int axis = 0; axis < 2; ++axis)  // bending about either axis: rho A c^2 / Kt_bend
    k = std::max(k, std::pow(M[3] * c * c / Kt[axis], 0.25));
  k = std::max(k, c * std::sqrt(M[2] / Kt[2]));  // torsion
  for (int axis = 3; axis < 6; ++axis)           // shear and axial
    k = std::max(k, c * std::sqrt(M[axis] / Kt[axis]));
  return problem.length() * k;
}

double single_shooting_exponent_bound(ShootingGrid grid, double tol) {
  const double bound = std::log(tol / std::numeric_limits<double>::epsilon());
  return bound + (grid == ShootingGrid::euler ? kEulerGridAllowance : kStaggeredGridAllowance);
}

double single_shooting_min_step(const DynamicProblem& problem, ShootingGrid grid, double tol) {
  const double bound = single_shooting_exponent_bound(grid, tol);
  double lo = 1e-15, hi = 1e6;  // kappa(lo) > bound >= kappa(hi) for any physical rod
  for (int i = 0; i < 200 && hi / lo > 1.0 + 1e-6; ++i) {
    const double mid = std::sqrt(lo * hi);
    (single_shooting_exponent(problem, mid) > bound ? lo : hi) = mid;
  }
  return hi;
}

std::string single_shooting_step_problem(const DynamicProblem& problem, std::string_view scheme,
                                         ShootingGrid grid, double dt, double tol) {
  const double kappa = single_shooting_exponent(problem, dt);
  const double bound = single_shooting_exponent_bound(grid, tol);
  if (!(kappa > bound)) return {};
  return rodlab::format(
      "dt = {:g} s is below {}'s lower step bound on this rod (grid {}): single shooting "
      "amplifies an error at the base by e^{:.1f} along the rod, more than tol = {:g} allows "
      "(e^{:.1f}; docs/dynamics.md \"The lower step bound of single shooting\"); it needs dt >= "
      "{:.3g} s; use implicit-midpoint-collocation (the midpoint rule without a lower step bound) "
      "or ida{}",
      dt, scheme, shooting_grid_name(grid), kappa, tol, bound,
      single_shooting_min_step(problem, grid, tol),
      grid == ShootingGrid::euler ? ", or --grid staggered (the default grid, which steps below "
                                    "the bound by multiple shooting)"
                                  : "");
}

int shooting_intervals(double kappa, ShootingGrid grid, double tol, int segments) {
  const double bound = single_shooting_exponent_bound(grid, tol);
  if (!(kappa > bound)) return 1;
  const double per_interval = std::max(bound - kIntervalMargin, kMinIntervalExponent);
  const double wanted = std::ceil(kappa / per_interval);
  return std::max(2, static_cast<int>(std::min(wanted, static_cast<double>(segments))));
}

std::string shooting_step_problem(const DynamicProblem& problem, std::string_view scheme,
                                  ShootingGrid grid, double dt, double tol) {
  if (grid != ShootingGrid::euler) return {};  // multiple shooting beyond the bound
  return single_shooting_step_problem(problem, scheme, grid, dt, tol);
}

}  // namespace rodlab::solvers::dynamics
