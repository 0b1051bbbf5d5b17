#pragma once
// A tendon-like actuator path: a curve at offset r(s) = [x(s), y(s), 0] from the centreline,
// over the span [s0, s1], carrying an axial force F (tension positive). Cables (F = T), fluidic
// chambers (F = -P A_c: the fluid column is in compression; pressure on the curved walls plus
// the cap force, docs/statics.md) and the active force of artificial muscles are all of this kind.
//
// Kinematics (2.39): p_a' = R u, u = nu + omega x r + r' (= nu - hat(r) omega + r'),
// t = u / |u| the unit tangent in the body frame (2.41).
// Internal wrench of the tendon across a section, about the centroid, body frame:
//     F c(xi),  c = [r x t; t]     (the force F t acts at r; compare (2.37), (2.46))
// Embedded frictionless tendons are internal to rod + tendon, so rodlab adds F c(xi) to the
// constitutive law, K (xi - xi*) + sum_k F_k c_k(xi) = Lambda, instead of the distributed load
// (2.45) with its xi' terms; the two are equivalent (docs/statics.md).
#include <utility>
#include <vector>

#include "rodlab/lie/se3.hpp"

namespace rodlab::loads {

using lie::Vector3;
using lie::Vector6;
using Matrix36 = Eigen::Matrix<double, 3, 6>;

class TendonPath {
 public:
  /// points: (s, x, y) knots of a piecewise-linear offset; one knot means a constant offset.
  TendonPath(std::vector<std::pair<double, Eigen::Vector2d>> points, double s0, double s1);

  double s0() const { return s0_; }
  double s1() const { return s1_; }
  bool active(double s) const { return s >= s0_ && s < s1_; }

  /// Offset r(s) and its derivative r'(s) (piecewise constant; at a knot, the right limit).
  Vector3 offset(double s) const;
  Vector3 offset_rate(double s) const;
  /// Knots of the routing inside (s0, s1): where r' jumps (integration breakpoints).
  std::vector<double> knots() const;

  /// u = nu + omega x r + r' (body frame): p_a' = R u.
  Vector3 tangent_vector(double s, const Vector6& xi) const {
    return xi.tail<3>() + xi.head<3>().cross(offset(s)) + offset_rate(s);
  }
  /// c(xi) = [r x t; t].
  Vector6 unit_wrench(double s, const Vector6& xi) const;
  /// dc/dxi = [hat(r); I] (I - t t^T)/|u| [-hat(r), I].
  Eigen::Matrix<double, 6, 6> unit_wrench_jacobian(double s, const Vector6& xi) const;
  /// w += F c(xi) and J += F dc/dxi in one evaluation of r, u and t (the Newton iteration of
  /// the constitutive law with tendons, solvers/common/tendon_law.hpp).
  void add_wrench(double s, const Vector6& xi, double F, Vector6& w,
                  Eigen::Matrix<double, 6, 6>& J) const;
  /// |p_a'| = |u|: the rate of the path's current length (2.47), (2.66).
  double length_rate(double s, const Vector6& xi) const { return tangent_vector(s, xi).norm(); }

 private:
  std::vector<std::pair<double, Eigen::Vector2d>> points_;
  double s0_, s1_;
};

}  // namespace rodlab::loads
