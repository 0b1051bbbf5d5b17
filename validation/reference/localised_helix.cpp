#include "reference/localised_helix.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "reference/rk8pd.hpp"

namespace rodlab::validation::reference {
namespace {

using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;

/// The Euler angles' and position's derivatives at s (header).
struct Rates {
  double theta, theta_rate, psi_rate, phi_rate;
};

}  // namespace

LocalisedHelix::LocalisedHelix(double B, double C, double T, double M, double L)
    : B_(B), C_(C), T_(T), M_(M), L_(L), a_(2.0 - M * M / (2.0 * B * T)),
      kappa_(std::sqrt(T * a_ / (2.0 * B))) {
  if (!(B > 0.0 && C > 0.0 && T > 0.0 && L > 0.0 && M * M < 4.0 * B * T))
    throw std::invalid_argument("LocalisedHelix: needs B, C, T, L > 0 and M^2 < 4 B T");
}

double LocalisedHelix::envelope(double s) const {
  const double sech = 1.0 / std::cosh(kappa_ * s);
  return a_ * sech * sech;
}

std::vector<LocalisedHelix::Sample> LocalisedHelix::samples(std::span<const double> s) const {
  auto rates = [this](double x) {
    const double u = envelope(x);
    const double sin_theta = std::sqrt(u * (2.0 - u)), cos_theta = 1.0 - u;
    const double du = -2.0 * kappa_ * std::tanh(kappa_ * x) * u;  // (a sech^2)'
    const double psi_rate = M_ / (B_ * (1.0 + cos_theta));
    return Rates{std::atan2(sin_theta, cos_theta), du / sin_theta, psi_rate,
                 M_ / C_ - psi_rate * cos_theta};
  };
  // y = (psi, phi, p)
  auto derivatives = [](double x, const double y[], double dy[], void* self) -> int {
    const auto& h = *static_cast<const LocalisedHelix*>(self);
    const double u = h.envelope(x), sin_theta = std::sqrt(u * (2.0 - u));
    const double psi_rate = h.M_ / (h.B_ * (2.0 - u));
    dy[0] = psi_rate;
    dy[1] = h.M_ / h.C_ - psi_rate * (1.0 - u);
    dy[2] = sin_theta * std::cos(y[0]);
    dy[3] = sin_theta * std::sin(y[0]);
    dy[4] = 1.0 - u;
    return GSL_SUCCESS;
  };
  gsl_odeiv2_system system{derivatives, nullptr, 5, const_cast<LocalisedHelix*>(this)};
  std::array<double, 5> y{};
  double at = -0.5 * L_;
  std::vector<Sample> out;
  out.reserve(s.size());
  for (double x : s) {
    if (x > at) integrate_rk8pd(system, at, x, y.data(), 1e-13, "LocalisedHelix");
    at = x;
    const Rates r = rates(x);
    const double psi = y[0], phi = y[1];
    const SO3 R = SO3::exp(Vector3(0, 0, psi)) * SO3::exp(Vector3(0, r.theta, 0)) *
                  SO3::exp(Vector3(0, 0, phi));
    // the body angular velocity of R = Rz(psi) Ry(theta) Rz(phi): the curvature
    const Vector3 w(-r.psi_rate * std::sin(r.theta) * std::cos(phi) + r.theta_rate * std::sin(phi),
                    r.psi_rate * std::sin(r.theta) * std::sin(phi) + r.theta_rate * std::cos(phi),
                    r.psi_rate * std::cos(r.theta) + r.phi_rate);
    Vector6 wrench;
    wrench << B_ * w.x(), B_ * w.y(), C_ * w.z(), R.inverse() * Vector3(0, 0, T_);
    out.push_back({SE3(R, Vector3(y[2], y[3], y[4])), wrench});
  }
  return out;
}

}  // namespace rodlab::validation::reference
