#pragma once
// One GSL rk8pd integration of an ODE system, for the references that shoot (planar_rod.cpp,
// cantilever_frequencies.cpp).
#include <stdexcept>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

namespace rodlab::validation::reference {

/// Integrates `system` from s0 to s1 (either direction) in place on y, at the absolute and
/// relative tolerance `tol`; throws std::runtime_error naming `who` when rk8pd fails.
inline void integrate_rk8pd(gsl_odeiv2_system system, double s0, double s1, double* y, double tol,
                            const std::string& who) {
  gsl_odeiv2_driver* d =
      gsl_odeiv2_driver_alloc_y_new(&system, gsl_odeiv2_step_rk8pd, 1e-3 * (s1 - s0), tol, tol);
  double s = s0;
  const int status = gsl_odeiv2_driver_apply(d, &s, s1, y);
  gsl_odeiv2_driver_free(d);
  if (status != GSL_SUCCESS) throw std::runtime_error(who + ": rk8pd failed");
}

}  // namespace rodlab::validation::reference
