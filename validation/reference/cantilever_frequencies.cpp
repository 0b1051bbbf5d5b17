// Natural frequencies of a clamped-free rod (cantilever_frequencies.hpp).
#include "reference/cantilever_frequencies.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "reference/rk8pd.hpp"

namespace rodlab::validation::reference {
namespace {

struct Modal {
  TimoshenkoBeam beam;
  double omega;
};

/// y = [w, w', psi, psi'] of the modal equations (cantilever_frequencies.hpp).
int modal_rhs(double, const double y[], double dyds[], void* params) {
  const auto& m = *static_cast<const Modal*>(params);
  const auto& b = m.beam;
  const double w2 = m.omega * m.omega;
  dyds[0] = y[1];
  dyds[1] = y[3] - b.rhoA * w2 * y[0] / b.GA;
  dyds[2] = y[3];
  dyds[3] = -(b.GA * (y[1] - y[2]) + b.rhoI * w2 * y[2]) / b.EI;
  return GSL_SUCCESS;
}

/// The free-end conditions [psi'(L), w'(L) - psi(L)] of the solution that starts clamped with
/// the slopes (w'(0), psi'(0)) = start.
std::array<double, 2> free_end(const Modal& m, std::array<double, 2> start) {
  double y[4] = {0.0, start[0], 0.0, start[1]};
  integrate_rk8pd({modal_rhs, nullptr, 4, const_cast<Modal*>(&m)}, 0.0, m.beam.length, y, 1e-13,
                  "timoshenko frequencies");
  return {y[3], y[1] - y[2]};
}

double determinant(const TimoshenkoBeam& beam, double omega) {
  const Modal m{beam, omega};
  const auto a = free_end(m, {1.0, 0.0}), b = free_end(m, {0.0, 1.0});
  return a[0] * b[1] - a[1] * b[0];
}

}  // namespace

std::vector<double> timoshenko_cantilever_frequencies(const TimoshenkoBeam& beam, int count) {
  // Scan in steps of a fiftieth of the Euler-Bernoulli fundamental up to past the count-th
  // Euler-Bernoulli frequency ((2n - 1) pi / 2)^2 sqrt(EI / (rho A L^4)), which Timoshenko's
  // lies below.
  const double scale = std::sqrt(beam.EI / (beam.rhoA * std::pow(beam.length, 4)));
  const double first = 1.8751040687 * 1.8751040687 * scale;
  const double last = std::pow((2 * count - 1) * std::numbers::pi / 2, 2) * scale * 1.2;
  std::vector<double> roots;
  double lo = 1e-3 * first, f_lo = determinant(beam, lo);
  for (double hi = lo + first / 50; hi <= last && static_cast<int>(roots.size()) < count;
       hi += first / 50) {
    const double f_hi = determinant(beam, hi);
    if ((f_lo < 0) != (f_hi < 0)) {
      double a = lo, b = hi, fa = f_lo;
      for (int i = 0; i < 100 && b - a > 1e-14 * b; ++i) {
        const double mid = 0.5 * (a + b), fm = determinant(beam, mid);
        if ((fm < 0) == (fa < 0)) {
          a = mid;
          fa = fm;
        } else {
          b = mid;
        }
      }
      roots.push_back(0.5 * (a + b) / (2 * std::numbers::pi));
    }
    lo = hi;
    f_lo = f_hi;
  }
  if (static_cast<int>(roots.size()) < count)
    throw std::runtime_error("timoshenko frequencies: fewer roots than asked below the scan's end");
  return roots;
}

double clamped_free_wave_frequency(double length, double wave_speed, int n) {
  return (2 * n - 1) * wave_speed / (4 * length);
}

}  // namespace rodlab::validation::reference
