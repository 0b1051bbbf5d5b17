#include "rodlab/rod/characteristics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rodlab::rod {
namespace {

// First roots of the Euler-Bernoulli frequency equations (beta L):
// clamped-free cos(x) cosh(x) = -1, clamped-clamped cos(x) cosh(x) = 1.
constexpr double kBetaLClampedFree = 1.8751040687119611;
constexpr double kBetaLClampedClamped = 4.7300407448627040;
// Safety factors the thesis used in (3.44) (Cosserat) and 3.3.2 (Kirchhoff), unmeasured there.
constexpr double kThesisSafetyCosserat = 0.1;
constexpr double kThesisSafetyKirchhoff = 0.9;
constexpr double kKirchhoffSafeBelow = 0.01;

}  // namespace

Characteristics characteristics(const RodModel& model, int nodes, TipSupport tip) {
  if (nodes < 2) throw std::invalid_argument("nodes must be >= 2");
  const auto& p = model.properties();
  const auto& m = model.material();
  const double L = model.length();
  const double two_pi = 2.0 * std::numbers::pi;

  Characteristics c;
  c.section = p;
  c.K_diag = model.K_diag();
  c.M_diag = model.M_diag();
  c.V_diag = model.V_diag();
  c.axial_wave_speed = std::sqrt(m.E / m.rho);
  c.shear_wave_speed = std::sqrt(m.G / m.rho);
  c.nodes = nodes;
  c.ds = L / (nodes - 1);
  c.dt_cfl = c.ds / std::max(c.axial_wave_speed, c.shear_wave_speed);  // (3.43)
  c.thesis_safety_factor = model.is_kirchhoff() ? kThesisSafetyKirchhoff : kThesisSafetyCosserat;
  c.dt_thesis = c.thesis_safety_factor * c.ds * std::sqrt(m.rho / m.E);  // (3.44)

  const double I_weak = std::min(p.Ix, p.Iy), I_strong = std::max(p.Ix, p.Iy);
  const bool clamped = tip == TipSupport::clamped;
  const double beta_L = clamped ? kBetaLClampedClamped : kBetaLClampedFree;
  c.first_bending_frequency_hz =
      beta_L * beta_L * std::sqrt(m.E * I_weak / (m.rho * p.A)) / (L * L) / two_pi;
  // Axial bar: clamped-free lambda = pi/2, clamped-clamped lambda = pi; omega = lambda c / L.
  c.first_axial_frequency_hz = (clamped ? 1.0 : 0.5) * c.axial_wave_speed / (2.0 * L);

  c.shear_to_bending = m.G * p.A * L * L / (m.E * I_weak);
  c.axial_to_bending = p.A * L * L / I_weak;
  // Timoshenko cantilever under a tip load: shear adds P L / (G A) to the Euler-Bernoulli
  // deflection P L^3 / (3 E I); their ratio estimates what the Kirchhoff restriction drops.
  c.kirchhoff_error_estimate = 3.0 * m.E * I_strong / (m.G * p.A * L * L);
  c.kirchhoff_safe = c.kirchhoff_error_estimate < kKirchhoffSafeBelow;
  return c;
}

}  // namespace rodlab::rod
