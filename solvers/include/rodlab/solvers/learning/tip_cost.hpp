#pragma once
// Guided Policy Search's cost on the rod (docs/learning.md "GPS"; gps.hpp), in the state units
// of the environment (rod_environment.hpp: the tip p / L and its velocity v T / L first): with
// d = p / L - p_des / L,
//
//   l(x, a) = w_t [ sqrt(alpha^2 + |d|^2) / beta  +  w_2 |d|^2 / (2 beta^2)
//                 + w_log log(alpha^2 + |d|^2) / 2
//                 + w_v |v T / L - v_des T / L|^2 / (2 beta^2) ]              (w_v: track)
//           + w_a |a|^2 / 2  +  w_b sum_i max(0, |a_i| - 1)^2 / 2,
//
// w_t = `final` at the last step, `running` before it. The first term is -R of (4.40),
// |d| / beta, smoothed at alpha and not capped at beta L: trajectory optimisation needs the
// direction to the goal everywhere, and (4.40) is flat beyond beta L (it was chosen for DDPG).
// The quadratic and log terms are the reference code's l2 and log parts of its end-effector
// cost. The log term matters for reaching points of the dynamic workspace: a sum of convex
// distances over the trajectory prefers hovering near a point the rod cannot hold to swinging
// through it, the concave log pays for passing close (measured, reach-any, seed 1, 24 000
// samples: 84 % of 50 unseen targets without it, 100 % with w_log = 1; docs/learning.md). The
// last term keeps the actions inside [-1, 1], where the environment clips them.
#include <cmath>

#include <Eigen/Core>

#include "rodlab/solvers/learning/trajectory_environment.hpp"

namespace rodlab::solvers::learning {

struct TipCost {
  double beta = 0.3;        ///< (4.40)
  double alpha = 0.01;      ///< smoothing of |d| [L]
  double quadratic = 1.0;   ///< w_2
  double velocity = 0.0;    ///< w_v (track)
  double action = 1e-3;     ///< w_a
  double bound = 10.0;      ///< w_b
  /// The position and velocity terms are multiplied by `running` before the last step and by
  /// `final` at it (the reference code's ramp with wp_final_multiplier).
  double running = 1.0;
  double final = 1.0;
  /// w_log of the term w_log log(alpha^2 + |d|^2) / 2 (the reference code's "log" distance
  /// term): concave beyond alpha, it pays for passing close rather than hovering near.
  double log = 1.0;

  /// l at (x, a) towards p_des / L = goal (and v_des T / L = goal_velocity); e if given.
  double operator()(const Eigen::Ref<const Eigen::VectorXd>& x,
                    const Eigen::Ref<const Eigen::VectorXd>& a, const Eigen::Vector3d& goal,
                    const Eigen::Vector3d& goal_velocity, bool last, CostExpansion* e) const {
    const double w = last ? final : running;
    const auto n = x.size(), m = a.size();
    const Eigen::Vector3d d = x.head<3>() - goal;
    const Eigen::Vector3d dv = x.segment<3>(3) - goal_velocity;
    const double r = std::sqrt(alpha * alpha + d.squaredNorm());
    const double b2 = beta * beta;
    const double s2 = alpha * alpha + d.squaredNorm();
    double l = w * (r / beta + 0.5 * quadratic * d.squaredNorm() / b2 +
                    0.5 * velocity * dv.squaredNorm() / b2 + 0.5 * log * std::log(s2)) +
               0.5 * action * a.squaredNorm();
    Eigen::VectorXd over = (a.cwiseAbs().array() - 1.0).max(0.0).matrix();
    l += 0.5 * bound * over.squaredNorm();
    if (!e) return l;
    e->value = l;
    e->lx = Eigen::VectorXd::Zero(n);
    e->lxx = Eigen::MatrixXd::Zero(n, n);
    e->lx.head<3>() = w * (d / (beta * r) + quadratic * d / b2 + log * d / s2);
    e->lxx.topLeftCorner<3, 3>() =
        w * ((Eigen::Matrix3d::Identity() / r - d * d.transpose() / (r * r * r)) / beta +
             quadratic / b2 * Eigen::Matrix3d::Identity() +
             log * (Eigen::Matrix3d::Identity() / s2 - 2.0 * d * d.transpose() / (s2 * s2)));
    e->lx.segment<3>(3) = w * velocity * dv / b2;
    e->lxx.block<3, 3>(3, 3) = w * velocity / b2 * Eigen::Matrix3d::Identity();
    e->la = action * a;
    e->laa = action * Eigen::MatrixXd::Identity(m, m);
    for (Eigen::Index i = 0; i < m; ++i)
      if (over[i] > 0.0) {
        e->la[i] += bound * over[i] * (a[i] > 0.0 ? 1.0 : -1.0);
        e->laa(i, i) += bound;
      }
    e->lax = Eigen::MatrixXd::Zero(m, n);
    return l;
  }
};

}  // namespace rodlab::solvers::learning
