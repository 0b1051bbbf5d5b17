// The planar cantilever reference (planar_rod.hpp): rk8pd shooting on the tip angle.
#include "reference/planar_rod.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "reference/rk8pd.hpp"

namespace rodlab::validation::reference {
namespace {

struct System {
  PlanarRod rod;
  PlanarLoads loads;
};

/// y = [theta, m, x, z, n_x, n_z] (planar_rod.hpp).
int rhs(double, const double y[], double dyds[], void* params) {
  const auto& sys = *static_cast<const System*>(params);
  const double c = std::cos(y[0]), s = std::sin(y[0]);
  const double nx = y[4], nz = y[5];
  double nu1 = 0.0, nu3 = 1.0;
  if (!sys.rod.kirchhoff()) {
    nu1 = (nx * c - nz * s) / sys.rod.GA;
    nu3 = 1.0 + (nx * s + nz * c) / sys.rod.EA;
  }
  const double px = nu1 * c + nu3 * s, pz = -nu1 * s + nu3 * c;
  dyds[0] = y[1] / sys.rod.EI;
  dyds[1] = nz * px - nx * pz;
  dyds[2] = px;
  dyds[3] = pz;
  dyds[4] = -sys.loads.fx;
  dyds[5] = -sys.loads.fz;
  return GSL_SUCCESS;
}

/// Integrates from the tip at angle theta_L to the base; returns y(0).
std::array<double, 6> shoot(const System& sys, double theta_L) {
  const auto& f = sys.loads;
  const double c = std::cos(theta_L), sn = std::sin(theta_L);
  const double Fx = f.follower ? f.Fx * c + f.Fz * sn : f.Fx;  // d1 = (c, -s), d3 = (s, c)
  const double Fz = f.follower ? -f.Fx * sn + f.Fz * c : f.Fz;
  std::array<double, 6> y{theta_L, 0.0, 0.0, 0.0, Fx, Fz};
  integrate_rk8pd({rhs, nullptr, 6, const_cast<System*>(&sys)}, sys.rod.length, 0.0, y.data(),
                  1e-14, "planar_cantilever");
  return y;
}

}  // namespace

PlanarTip planar_cantilever(const PlanarRod& rod, const PlanarLoads& loads, double start,
                            double step) {
  const System sys{rod, loads};
  double lo = start, f_lo = shoot(sys, lo)[0], hi = lo;
  for (int i = 1;; ++i) {
    if (i > 2000) throw std::runtime_error("planar_cantilever: no root bracketed");
    hi = start + step * i;
    const double f_hi = shoot(sys, hi)[0];
    if ((f_lo < 0) != (f_hi < 0)) break;
    lo = hi;
    f_lo = f_hi;
  }
  for (int i = 0; i < 200 && std::abs(hi - lo) > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double f_mid = shoot(sys, mid)[0];
    if (mid == lo || mid == hi) break;
    if ((f_mid < 0) == (f_lo < 0)) {
      lo = mid;
      f_lo = f_mid;
    } else {
      hi = mid;
    }
  }
  PlanarTip tip;
  tip.theta = 0.5 * (lo + hi);
  const auto base = shoot(sys, tip.theta);
  tip.x = -base[2];  // the tip relative to the base
  tip.z = -base[3];
  return tip;
}

}  // namespace rodlab::validation::reference
