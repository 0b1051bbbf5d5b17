// The buckling closed forms of buckling.hpp.
#include "reference/buckling.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include <gsl/gsl_sf_bessel.h>
#include <gsl/gsl_sf_ellint.h>

namespace rodlab::validation::reference {

PostBuckledElastica post_buckled_elastica(double alpha) {
  if (!(alpha > 0.0 && alpha < std::numbers::pi))
    throw std::domain_error("post_buckled_elastica: tip angle outside (0, pi)");
  const double k = std::sin(0.5 * alpha);
  const double K = gsl_sf_ellint_Kcomp(k, GSL_PREC_DOUBLE);
  const double E = gsl_sf_ellint_Ecomp(k, GSL_PREC_DOUBLE);
  return {K * K, 2.0 * k / K, 2.0 * E / K - 1.0};
}

double cosserat_critical_load(double euler_load, double GA, double EA) {
  const double a = (GA > 0.0 ? 1.0 / GA : 0.0) - (EA > 0.0 ? 1.0 / EA : 0.0);
  // a P^2 + P - P_E = 0, the root that tends to P_E as a -> 0, in its cancellation-free form.
  const double disc = 1.0 + 4.0 * a * euler_load;
  if (!(disc > 0.0)) throw std::domain_error("cosserat_critical_load: no critical load");
  return 2.0 * euler_load / (1.0 + std::sqrt(disc));
}

double greenhill_clamped_moment(double g) {
  // x = mu / 2 in (pi, 3 pi / 2), where tan x rises from 0 to infinity and x / (1 + 4 g x^2)
  // stays positive and finite.
  const auto f = [g](double x) { return std::tan(x) - x / (1.0 + 4.0 * g * x * x); };
  double lo = std::numbers::pi, hi = 1.5 * std::numbers::pi - 1e-12;
  if (!(f(lo) < 0.0 && f(hi) > 0.0)) throw std::domain_error("greenhill_clamped_moment: bracket");
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0.0 ? lo : hi) = mid;
  }
  return lo + hi;  // mu = 2 x
}

double lateral_torsional_constant() {
  // J_{-1/4} = cos(pi/4) J_{1/4} - sin(pi/4) Y_{1/4} (GSL's Bessel functions take nu >= 0); its
  // first zero lies between gamma / 2 = 1.5 and 2.5.
  const auto f = [](double gamma) {
    const double x = 0.5 * gamma;
    return gsl_sf_bessel_Jnu(0.25, x) - gsl_sf_bessel_Ynu(0.25, x);
  };
  double lo = 3.0, hi = 5.0;
  if (!((f(lo) < 0.0) != (f(hi) < 0.0)))
    throw std::domain_error("lateral_torsional_constant: bracket");
  const bool rising = f(hi) > 0.0;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) < 0.0) == rising ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace rodlab::validation::reference
