#include "rodlab/solvers/dynamics/energy.hpp"

#include <algorithm>

#include "rodlab/rod/energies.hpp"

namespace rodlab::solvers::dynamics {
namespace {

template <class Density>
double trapezoid(std::size_t n, double ds, Density density) {
  double sum = 0.0;
  for (std::size_t j = 0; j < n; ++j) sum += (j == 0 || j + 1 == n ? 0.5 : 1.0) * density(j);
  return sum * ds;
}

}  // namespace

double kinetic_energy(const rod::RodModel& model, std::span<const Vector6> eta, double ds) {
  return trapezoid(eta.size(), ds,
                   [&](std::size_t j) { return rod::kinetic_energy_density(model, eta[j]); });
}

double strain_energy_segments(const rod::RodModel& model, std::span<const Vector6> xi, double ds) {
  double sum = 0.0;
  for (std::size_t j = 0; j < xi.size(); ++j)
    sum += rod::strain_energy_density(model, xi[j], (static_cast<double>(j) + 0.5) * ds);
  return sum * ds;
}

double strain_energy_nodes(const rod::RodModel& model, std::span<const Vector6> xi, double ds) {
  // node j's rest strain is segment min(j, N - 2)'s (RodModel::node_xi_star), read at its
  // midpoint
  const std::size_t last = xi.size() - 2;
  return trapezoid(xi.size(), ds, [&](std::size_t j) {
    const double s = (static_cast<double>(std::min(j, last)) + 0.5) * ds;
    return rod::strain_energy_density(model, xi[j], s);
  });
}

double gravity_energy(const DynamicProblem& problem, std::span<const SE3> g, double ds) {
  const Vector3 w = problem.weight_per_length();
  if (w.isZero()) return 0.0;
  // -w . (int p ds - int p* ds), both by the trapezoidal rule over the nodes
  Vector3 sum = Vector3::Zero();
  for (std::size_t j = 0; j < g.size(); ++j)
    sum += (j == 0 || j + 1 == g.size() ? 0.5 : 1.0) * g[j].translation();
  return -w.dot(ds * sum - rod::reference_centreline_sum(problem.model(), problem.base(), ds, g.size()));
}

double kinetic_energy(std::span<const lie::Matrix6> inertia, std::span<const Vector6> eta,
                      double ds) {
  return trapezoid(eta.size(), ds,
                   [&](std::size_t j) { return 0.5 * eta[j].dot(inertia[j] * eta[j]); });
}

double embedded_strain_energy_segments(const DynamicProblem& problem,
                                       std::span<const Vector6> xi, double ds) {
  double sum = 0.0;
  for (std::size_t j = 0; j < xi.size(); ++j)
    sum += problem.embedded_strain_density(xi[j], (static_cast<double>(j) + 0.5) * ds);
  return sum * ds;
}

double embedded_strain_energy_nodes(const DynamicProblem& problem, std::span<const Vector6> xi,
                                    double ds) {
  return trapezoid(xi.size(), ds, [&](std::size_t j) {
    return problem.embedded_strain_density(xi[j], static_cast<double>(j) * ds);
  });
}

double embedded_gravity_energy(const DynamicProblem& problem, std::span<const SE3> g, double ds) {
  const double L = problem.length();
  const auto& model = problem.model();
  return trapezoid(g.size(), ds, [&](std::size_t j) {
    const double s = ds * static_cast<double>(j);
    const double a = std::max(0.0, s - 0.5 * ds), b = std::min(L, s + 0.5 * ds);
    // the node's cell [a, b] is its trapezoid weight
    return problem.embedded_gravity_density(g[j], rod::reference_pose(model, problem.base(), s),
                                            a, b, s);
  });
}

Energy staggered_energy(const DynamicProblem& problem, std::span<const SE3> g,
                        std::span<const Vector6> eta, std::span<const Vector6> xi, double ds,
                        std::span<const lie::Matrix6> inertia) {
  Energy e;
  e.kinetic = inertia.empty() ? kinetic_energy(problem.model(), eta, ds)
                              : kinetic_energy(inertia, eta, ds);
  e.strain = strain_energy_segments(problem.model(), xi, ds);
  e.gravity = gravity_energy(problem, g, ds);
  if (!inertia.empty()) {
    e.strain += embedded_strain_energy_segments(problem, xi, ds);
    e.gravity += embedded_gravity_energy(problem, g, ds);
  }
  return e;
}

}  // namespace rodlab::solvers::dynamics
