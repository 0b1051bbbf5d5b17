#include "rodlab/rod/energies.hpp"

#include <stdexcept>

namespace rodlab::rod {

double strain_energy_density(const RodModel& model, const Vector6& xi, double s) {
  const Vector6 d = xi - model.xi_star(s);
  return 0.5 * d.dot(model.K_diag().cwiseProduct(d));  // (2.28)
}

double kinetic_energy_density(const RodModel& model, const Vector6& eta) {
  return 0.5 * eta.dot(model.M_diag().cwiseProduct(eta));  // (3.5)
}

double gravity_energy_density(const RodModel& model, const Vector3& gravity, const Vector3& p,
                              const Vector3& p_ref, double fluid_density) {
  const double rho_eff = model.material().rho - fluid_density;  // buoyancy (2.36)
  return -rho_eff * model.properties().A * gravity.dot(p - p_ref);
}

double viscous_power_density(const RodModel& model, const Vector6& xi_dot) {
  return xi_dot.dot(model.V_diag().cwiseProduct(xi_dot));
}

double integrate_trapezoid(std::span<const double> f, double ds) {
  if (f.size() < 2) throw std::invalid_argument("integrate_trapezoid needs at least 2 samples");
  double sum = 0.5 * (f.front() + f.back());
  for (std::size_t i = 1; i + 1 < f.size(); ++i) sum += f[i];
  return sum * ds;
}

lie::SE3 reference_pose(const RodModel& model, const lie::SE3& base, double s) {
  return base * model.rest_pose(s);
}

}  // namespace rodlab::rod
