#define BOOST_TEST_MODULE characteristics
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rodlab/rod/characteristics.hpp"

using namespace rodlab::rod;
using std::numbers::pi;
namespace tt = boost::test_tools;

namespace {
const Material kTable21{1e6, 0.33e6, 1000.0, 0.0};
}

// Reference: Table 2.1 rod. Wave speeds sqrt(E/rho) = 31.623 m/s, sqrt(G/rho) = 18.166 m/s;
// (3.44) dt = 0.1 ds sqrt(rho/E); Euler-Bernoulli cantilever f1 = 1.8751^2/(2 pi L^2) sqrt(EI/(rho A))
// (clamped-clamped 4.7300^2); axial bar c/(4L) (clamped-free), c/(2L) (clamped-clamped).
BOOST_AUTO_TEST_CASE(table21_rod) {
  const RodModel m(0.1, Circle{0.01}, kTable21);
  const auto c = characteristics(m, 21, TipSupport::free);
  const double D = 0.01, L = 0.1, A = pi * D * D / 4, I = pi * std::pow(D, 4) / 64;
  BOOST_TEST(c.axial_wave_speed == std::sqrt(1000.0), tt::tolerance(1e-15));
  BOOST_TEST(c.shear_wave_speed == std::sqrt(330.0), tt::tolerance(1e-15));
  BOOST_TEST(c.ds == 0.005, tt::tolerance(1e-15));
  BOOST_TEST(c.dt_cfl == 0.005 / std::sqrt(1000.0), tt::tolerance(1e-15));
  BOOST_TEST(c.dt_thesis == 0.1 * 0.005 * std::sqrt(1e-3), tt::tolerance(1e-15));
  const double f1 = std::pow(1.8751040687, 2) / (2 * pi * L * L) * std::sqrt(1e6 * I / (1000 * A));
  BOOST_TEST(c.first_bending_frequency_hz == f1, tt::tolerance(1e-9));
  BOOST_TEST(c.first_axial_frequency_hz == std::sqrt(1000.0) / (4 * L), tt::tolerance(1e-15));
  BOOST_TEST(c.shear_to_bending == 0.33e6 * A * L * L / (1e6 * I), tt::tolerance(1e-14));
  BOOST_TEST(c.axial_to_bending == 16 * L * L / (D * D), tt::tolerance(1e-14));  // A L^2 / I
  BOOST_TEST(c.kirchhoff_error_estimate == 3 * 1e6 * I / (0.33e6 * A * L * L), tt::tolerance(1e-14));
  BOOST_TEST(c.kirchhoff_error_estimate > 0.005);  // 3/(16 * 0.33 * 100) = 0.57 %: safe
  BOOST_TEST(c.kirchhoff_safe);

  const auto cc = characteristics(m, 21, TipSupport::clamped);
  const double f1cc = std::pow(4.7300407449, 2) / (2 * pi * L * L) * std::sqrt(1e6 * I / (1000 * A));
  BOOST_TEST(cc.first_bending_frequency_hz == f1cc, tt::tolerance(1e-9));
  BOOST_TEST(cc.first_axial_frequency_hz == std::sqrt(1000.0) / (2 * L), tt::tolerance(1e-15));
}

// Reference: the thesis's safety factors, 0.1 (Cosserat, (3.44)) and 0.9 (Kirchhoff, 3.3.2).
BOOST_AUTO_TEST_CASE(kirchhoff_time_step_factor) {
  const RodModel k(0.1, Circle{0.01}, kTable21, ModelKind::kirchhoff);
  const auto c = characteristics(k, 11, TipSupport::free);
  BOOST_TEST(c.thesis_safety_factor == 0.9);
  BOOST_TEST(c.dt_thesis == 0.9 * 0.01 * std::sqrt(1e-3), tt::tolerance(1e-15));
}

// A stubby rod (L = 2 D) is not a Kirchhoff rod: 3 E I / (G A L^2) = 3/(16 * 0.33 * 4) = 14 %.
BOOST_AUTO_TEST_CASE(stubby_rod_is_not_kirchhoff_safe) {
  const RodModel m(0.02, Circle{0.01}, kTable21);
  const auto c = characteristics(m, 5, TipSupport::free);
  BOOST_TEST(c.kirchhoff_error_estimate == 3.0 / (16 * 0.33 * 4), tt::tolerance(1e-12));
  BOOST_TEST(!c.kirchhoff_safe);
  BOOST_CHECK_THROW(characteristics(m, 1, TipSupport::free), std::invalid_argument);
}
