#include "rodlab/solvers/dynamics/corrected_grid.hpp"

#include <stdexcept>
#include <string>

#include "rodlab/lie/so3.hpp"
#include "rodlab/rod/energies.hpp"

namespace rodlab::solvers::dynamics {

std::optional<std::string> corrected_grid_refusal(const DynamicProblem& problem) {
  if (problem.is_kirchhoff())
    return "solver.grid: corrected needs rod.model cosserat (its bending correction is a shear "
           "compliance, and a Kirchhoff rod has no shear); use solver.grid: staggered";
  if (problem.has_actuators())
    return "solver.grid: corrected does not take actuators yet (their node inertia and loads are "
           "not corrected); use solver.grid: staggered";
  return std::nullopt;
}

void require_corrected_grid(const DynamicProblem& problem) {
  if (const auto reason = corrected_grid_refusal(problem)) throw std::invalid_argument(*reason);
}

DynamicProblem corrected_grid_problem(const DynamicProblem& problem, int nodes) {
  return problem.with_model(
      problem.model().with_residual_bending_flexibility(problem.length() / (nodes - 1)));
}

std::optional<TipHalfCell> TipHalfCell::of(const DynamicProblem& problem, int nodes) {
  if (problem.tip_clamped()) return std::nullopt;
  TipHalfCell cell = make(problem.model(), nodes);
  cell.rest_rotation =
      rod::reference_pose(problem.model(), problem.base(), problem.length()).rotation();
  return cell;
}

TipHalfCell TipHalfCell::make(const rod::RodModel& model, int nodes) {
  const double ds = model.length() / (nodes - 1);
  const lie::Vector3 nu = model.segment_xi_star(nodes - 2, nodes).tail<3>();
  TipHalfCell cell;
  cell.offset = -(ds / 6.0) * nu.normalized();
  const double rho_A = model.mass_per_length();
  const lie::Matrix3 d = lie::so3::hat(cell.offset);
  cell.M = model.M_diag().asDiagonal();
  cell.M.topLeftCorner<3, 3>() -= rho_A * d * d;
  cell.M.topRightCorner<3, 3>() = rho_A * d;
  cell.M.bottomLeftCorner<3, 3>() = -rho_A * d;
  cell.M_inv = cell.M.inverse();
  return cell;
}

}  // namespace rodlab::solvers::dynamics
