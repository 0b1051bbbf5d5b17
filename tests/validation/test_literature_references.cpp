#define BOOST_TEST_MODULE validation_literature_references
// The references of the "literature" validation family (validation/reference/planar_rod.hpp,
// buckling.hpp) against published tables and independent closed forms, and the bifurcation-load
// measurement (validation/checks/bifurcation_load.hpp) on stiffness laws whose zero is known.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <complex>
#include <numbers>

#include "checks/bifurcation_load.hpp"
#include "reference/buckling.hpp"
#include "reference/cantilever_frequencies.hpp"
#include "reference/planar_rod.hpp"

namespace ref = rodlab::validation::reference;
using rodlab::validation::bifurcation_load;
constexpr double kPi = std::numbers::pi;

// Timoshenko & Gere, Theory of Elastic Stability (1961), the table of the clamped-free
// elastica in section 2.7: tip angle [deg], P / P_cr, tip deflection / L, to their digits.
BOOST_AUTO_TEST_CASE(post_buckled_elastica_matches_timoshenko_and_gere) {
  const double table[][3] = {{20, 1.015, 0.220}, {40, 1.063, 0.422}, {60, 1.152, 0.593},
                             {80, 1.293, 0.719}, {100, 1.518, 0.792}, {120, 1.884, 0.803},
                             {140, 2.541, 0.750}, {160, 4.029, 0.625}, {176, 9.116, 0.421}};
  const double euler = kPi * kPi / 4.0;
  for (const auto& row : table) {
    const auto e = ref::post_buckled_elastica(row[0] * kPi / 180.0);
    BOOST_TEST(std::abs(e.load / euler - row[1]) <= 1.5e-3 * row[1], row[0]);
    BOOST_TEST(std::abs(e.x - row[2]) <= 1e-3, row[0]);
  }
  // Euler's load as the tip angle vanishes: P / P_cr = 1 + alpha^2 / 8 + ...
  const auto small = ref::post_buckled_elastica(1e-3);
  BOOST_TEST(std::abs(small.load / euler - 1.0 - 1e-6 / 8.0) <= 1e-10);
  BOOST_TEST(std::abs(small.z - 1.0) <= 1e-6);
}

BOOST_AUTO_TEST_CASE(cosserat_critical_load_solves_its_equation) {
  const double PE = 2.0, GA = 30.0, EA = 80.0;
  const double P = ref::cosserat_critical_load(PE, GA, EA);
  BOOST_TEST(std::abs(P * (1.0 + P / GA - P / EA) - PE) <= 1e-14);
  BOOST_TEST(P < PE);  // Haringx's shear lowers it more than the shortening raises it
  BOOST_TEST(ref::cosserat_critical_load(PE, 0.0, 0.0) == PE);
}

// Greenhill: tan(mu/2) = mu/2 (mu = 8.98682) without shear; with shear, the determinant of the
// clamped conditions (docs/validation.md) written out independently vanishes at mu.
BOOST_AUTO_TEST_CASE(greenhill_moment_is_the_clamped_determinants_root) {
  BOOST_TEST(std::abs(ref::greenhill_clamped_moment(0.0) - 8.986818916) <= 1e-9);
  for (double g : {1e-4, 1e-2, 0.1}) {
    const auto det = [g](double mu) {
      const std::complex<double> i(0.0, 1.0), E = std::exp(i * mu);
      // rows: t(0) = 0, t(L) = 0, w(L) = 0 for t = b + c s + e exp(i mu s), L = 1
      const std::complex<double> a[3][3] = {
          {1.0, 0.0, 1.0}, {1.0, 1.0, E}, {1.0, 0.5 + i * mu * g, (E - 1.0) / (i * mu)}};
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double mu = ref::greenhill_clamped_moment(g);
    BOOST_TEST(std::abs(det(mu)) <= 1e-12, g);
    BOOST_TEST(std::abs(det(mu * 1.001)) >= 1e-4, g);
    BOOST_TEST(mu < ref::greenhill_clamped_moment(0.0));  // shear lowers it
  }
}

// Prandtl's and Michell's constant (Timoshenko & Gere 6.3: 4.013); scipy's brentq on
// jv(-0.25, g/2) gives 4.0125993435789.
BOOST_AUTO_TEST_CASE(lateral_torsional_constant_is_the_bessel_root) {
  BOOST_TEST(std::abs(ref::lateral_torsional_constant() - 4.0125993435789) <= 1e-11);
}

// The planar shooting against the dead-load elastica's closed form (Bisshopp & Drucker 1945;
// the 17-digit values of tests/statics/elastica_reference.hpp, cross-checked with mpmath).
BOOST_AUTO_TEST_CASE(planar_cantilever_reproduces_the_tip_load_elastica) {
  const auto t = ref::planar_cantilever({1.0, 1.0, 0.0, 0.0}, {0, 0, 1.0, 0}, 0.0, 0.01);
  BOOST_TEST(std::abs(t.x - 0.30172077379981353) <= 1e-12);
  BOOST_TEST(std::abs(t.z - 0.94356676371662312) <= 1e-12);
  BOOST_TEST(std::abs(t.theta - 0.46135194971187896) <= 1e-12);
}

// A shearable, extensible cantilever under a small uniform load: Timoshenko's deflection
// q L^4 / (8 EI) + q L^2 / (2 GA) (shear coefficient 1, as rodlab's K), to the load's square.
BOOST_AUTO_TEST_CASE(planar_cantilever_has_timoshenkos_linear_deflection) {
  const double L = 2.0, EI = 3.0, GA = 5.0, EA = 7.0, q = 1e-6;
  const auto t = ref::planar_cantilever({L, EI, GA, EA}, {-q, 0, 0, 0}, 0.0, -1e-7);
  const double linear = q * std::pow(L, 4) / (8 * EI) + q * L * L / (2 * GA);
  BOOST_TEST(std::abs(-t.x / linear - 1.0) <= 1e-6);
  BOOST_TEST(std::abs(t.z - L) <= 1e-9);
}

// The Timoshenko cantilever's frequencies tend to Euler-Bernoulli's (beta L)^2 sqrt(EI/(rho A
// L^4)) / (2 pi), beta L = 1.8751041, 4.6940911, 7.8547574, as shear and rotary inertia vanish;
// and the Table 2.1 rod's (L / D = 10) lie below them (0.6, 3.8 and 8.4 %: the values scipy's
// DOP853 shooting of the same equations gives, 4.398329, 26.661147, 71.133379 Hz).
BOOST_AUTO_TEST_CASE(timoshenko_frequencies_tend_to_euler_bernoulli) {
  const double L = 0.1, EI = 4.908738521e-4, rhoA = 0.0785398163;
  const double eb = std::sqrt(EI / (rhoA * std::pow(L, 4))) / (2 * kPi);
  const double beta[] = {1.8751040687, 4.6940911330, 7.8547574382};
  // G A 4e4 times the Table 2.1 rod's and rho I 1e-5 of it: shear and rotary inertia lower the
  // frequencies by about EI (beta / L)^2 / GA + rho I (beta / L)^2 / rho A < 3e-6 (mode 3).
  const auto slender = ref::timoshenko_cantilever_frequencies({L, EI, 1e6, rhoA, 5e-12}, 3);
  for (int i = 0; i < 3; ++i) {
    const double ratio = slender[i] / (beta[i] * beta[i] * eb);
    BOOST_TEST((ratio < 1.0 && ratio > 1.0 - 3e-6), i << ": " << ratio);
  }
  const auto stubby =
      ref::timoshenko_cantilever_frequencies({L, EI, 25.918139, rhoA, 1000 * 4.908738521e-10}, 3);
  const double scipy[] = {4.398328516825175, 26.661146954484167, 71.13337935306487};
  for (int i = 0; i < 3; ++i) BOOST_TEST(std::abs(stubby[i] / scipy[i] - 1.0) <= 1e-8, i);
  BOOST_TEST(std::abs(ref::clamped_free_wave_frequency(0.1, 1000.0, 2) - 7500.0) <= 1e-9);
}

// The measurement on a stiffness law with a known zero, including a response that buckles
// (a large deflection) above it, as load continuation would.
BOOST_AUTO_TEST_CASE(bifurcation_load_finds_the_zero_of_the_stiffness) {
  for (double curvature : {0.0, 0.5, -0.8}) {
    const double critical = 3.0;
    const auto deflection = [&](double lambda, double h) -> std::optional<double> {
      const double gap = (critical - lambda) / critical;
      if (gap <= 0.0) return 0.1;  // buckled
      return h / (2.0 * gap * (1.0 + curvature * gap));
    };
    const auto r = bifurcation_load(deflection, 0.97 * critical, 1e-5);
    BOOST_TEST(r.ok);
    BOOST_TEST(std::abs(r.load / critical - 1.0) <= 1e-9, curvature);
    for (const auto& p : r.points) BOOST_TEST(p.load < critical);
  }
  // A failed solve is reported, not hidden.
  const auto failing = [](double, double) -> std::optional<double> { return std::nullopt; };
  BOOST_TEST(!bifurcation_load(failing, 1.0, 1e-5).ok);
}
