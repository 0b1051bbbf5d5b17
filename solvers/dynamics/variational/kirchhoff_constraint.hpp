#pragma once
// The Kirchhoff restriction (3.45) in the variational integrator, done with constraint forces
// (docs/dynamics.md "Kirchhoff rods"). Segment k carries an unknown force f_k in its stress,
// lambda^k += dexp^-T_{ds xi^k} [0; f_k] = B_k f_k, which enters the momenta of nodes k (+B_k f_k)
// and k + 1 (-Ad^T_{G^k} B_k f_k = -C_k f_k) through (3.41). The f_k are chosen so that the
// velocities of (3.42) take every segment of the next step's compatibility (3.38) onto the
// constraint:
//   c_k = nu-part of log((E^k)^-1 G^k E^(k+1)) / ds - nu* = 0,   E^j = exp(dt eta^j)
// (SHAKE: the constraint on the next positions through this step's impulses; the constraint
// forces do no work to the solve's tolerance). Newton with the chord matrix of the linearised
// map, block tridiagonal in the segments with 3 x 3 blocks:
//   dc_k = (dt/ds) [dexp^-1_{-ds xi^k}]_nu (d eta^(k+1) - Ad_{(G^k)^-1} d eta^k),
//   d eta^j = (dt / w_j) M^-1 (B_j f_j - C_(j-1) f_(j-1)).
// Private to solvers/dynamics (variational.cpp).
#include <span>
#include <string>
#include <vector>

#include "discrete_legendre.hpp"
#include "rodlab/lie/se3.hpp"
#include "rodlab/solvers/common/block_tridiagonal.hpp"

namespace rodlab::solvers::dynamics {

class KirchhoffConstraint {
 public:
  /// `nodes` nodes a distance ds apart (trapezoid weights, 1/2 at the tip), nu_star[k] segment
  /// k's constraint (its span's nu*).
  KirchhoffConstraint(int nodes, double ds, std::vector<lie::Vector3> nu_star,
                      DiscreteLegendre legendre, int max_iterations);

  /// After a free step: adds the constraint impulses to the momenta mu (nodes 1..N-1) and
  /// re-solves their velocities eta so that |nu - nu*| <= 1e-12 max(1, max |nu*|) on the next
  /// step's segments. G and xi are this step's segments. Returns false with failure() set
  /// when the solve fails.
  bool enforce(double dt, std::span<const lie::SE3> G, std::span<const lie::Vector6> xi,
               std::span<lie::Vector6> mu, std::span<lie::Vector6> eta);
  const std::string& failure() const { return failure_; }

 private:
  using Matrix63 = Eigen::Matrix<double, 6, 3>;
  double weight(int j) const { return j == n_ - 1 ? 0.5 * ds_ : ds_; }

  int n_;
  double ds_;
  std::vector<lie::Vector3> nu_star_;  ///< per segment
  double nu_scale_;                     ///< max(1, max_k |nu*_k|): the tolerance's scale
  DiscreteLegendre legendre_;
  int max_iterations_;
  std::vector<lie::Vector6> mu_free_;  ///< momenta without the constraint impulses
  std::vector<lie::Vector3> f_, c_;    ///< constraint forces per segment; residuals / steps
  std::vector<Matrix63> B_, C_;        ///< a force's impulse on the inner and outer node
  BlockTridiagonal<3> A_;              ///< the chord matrix dc/df
  std::string failure_;
};

}  // namespace rodlab::solvers::dynamics
