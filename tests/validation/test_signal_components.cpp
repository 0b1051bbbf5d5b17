#define BOOST_TEST_MODULE validation_signal_components
// The matrix pencil (validation/checks/signal_components.hpp) on signals whose components are
// known: undamped and damped sinusoids of very different amplitudes, an offset, a record
// shorter than the slowest period's 3, and noise far below the weakest component.
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "checks/signal_components.hpp"

using rodlab::validation::signal_components;
constexpr double kTwoPi = 2.0 * std::numbers::pi;

namespace {

struct Sinusoid {
  double hz, amplitude, decay, phase;
};

std::vector<double> sample(const std::vector<Sinusoid>& parts, double offset, int n, double dt,
                           double noise = 0.0) {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::vector<double> y(n, offset);
  for (int k = 0; k < n; ++k) {
    const double t = k * dt;
    for (const auto& p : parts)
      y[k] += p.amplitude * std::exp(-p.decay * t) * std::cos(kTwoPi * p.hz * t + p.phase);
    y[k] += noise * gauss(rng);
  }
  return y;
}

}  // namespace

// Three undamped modes like a cantilever's tip (amplitudes 1, 2.6e-2, 3.4e-3) over 2.2 periods
// of the slowest: each frequency to 1e-9 relative, each amplitude to 1e-7 relative.
BOOST_AUTO_TEST_CASE(finds_undamped_modes_in_a_short_record) {
  const std::vector<Sinusoid> parts{
      {4.4, 1.0, 0.0, 0.3}, {26.7, 2.6e-2, 0.0, 1.1}, {71.1, 3.4e-3, 0.0, -0.4}};
  const double dt = 0.5 / 1200;
  const auto found = signal_components(sample(parts, 0.0, 1200, dt), dt, 11);
  BOOST_REQUIRE(found.size() >= 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    BOOST_TEST(std::abs(found[i].frequency_hz / parts[i].hz - 1.0) <= 1e-9, i);
    BOOST_TEST(std::abs(found[i].amplitude / parts[i].amplitude - 1.0) <= 1e-7, i);
    BOOST_TEST(std::abs(found[i].decay) <= 1e-6, i);
  }
}

// Decay rates and an offset; and noise at 1e-7 of the main amplitude moves the main frequency
// by less than 1e-6 (the literature family's signals are integrated to about 1e-10).
BOOST_AUTO_TEST_CASE(finds_decay_and_ignores_an_offset_and_noise) {
  const std::vector<Sinusoid> parts{{10.0, 1.0, 2.0, 0.0}, {45.0, 0.1, 5.0, 0.5}};
  const double dt = 1e-3;
  const auto found = signal_components(sample(parts, 3.0, 900, dt), dt, 7);
  BOOST_REQUIRE(found.size() == 2u);
  BOOST_TEST(std::abs(found[0].frequency_hz / 10.0 - 1.0) <= 1e-9);
  BOOST_TEST(std::abs(found[0].decay / 2.0 - 1.0) <= 1e-7);
  BOOST_TEST(std::abs(found[1].frequency_hz / 45.0 - 1.0) <= 1e-9);
  BOOST_TEST(std::abs(found[1].decay / 5.0 - 1.0) <= 1e-7);
  const auto noisy = signal_components(sample(parts, 3.0, 900, dt, 1e-7), dt, 7);
  BOOST_REQUIRE(!noisy.empty());
  BOOST_TEST(std::abs(noisy[0].frequency_hz / 10.0 - 1.0) <= 1e-6);
}

BOOST_AUTO_TEST_CASE(refuses_an_order_the_record_cannot_hold) {
  const std::vector<double> y(20, 1.0);
  BOOST_CHECK_THROW(signal_components(y, 0.1, 7), std::invalid_argument);
  BOOST_CHECK_THROW(signal_components(y, 0.1, 0), std::invalid_argument);
}
