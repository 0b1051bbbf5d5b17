#include "rodlab/loads/tendon.hpp"

#include <algorithm>
#include <stdexcept>

namespace rodlab::loads {

TendonPath::TendonPath(std::vector<std::pair<double, Eigen::Vector2d>> points, double s0, double s1)
    : points_(std::move(points)), s0_(s0), s1_(s1) {
  if (points_.empty()) throw std::invalid_argument("a tendon path needs at least one offset point");
  if (!(s0 < s1)) throw std::invalid_argument("a tendon span needs s0 < s1");
  for (std::size_t k = 1; k < points_.size(); ++k)
    if (!(points_[k].first > points_[k - 1].first))
      throw std::invalid_argument("routing knots must have increasing s");
}

namespace {
// Index k of the routing segment [s_k, s_k+1] containing s (clamped to the first/last one).
std::size_t segment(const std::vector<std::pair<double, Eigen::Vector2d>>& p, double s) {
  std::size_t k = 0;
  while (k + 2 < p.size() && s >= p[k + 1].first) ++k;
  return k;
}
}  // namespace

Vector3 TendonPath::offset(double s) const {
  if (points_.size() == 1) return {points_[0].second.x(), points_[0].second.y(), 0.0};
  if (s <= points_.front().first) return {points_.front().second.x(), points_.front().second.y(), 0.0};
  if (s >= points_.back().first) return {points_.back().second.x(), points_.back().second.y(), 0.0};
  const std::size_t k = segment(points_, s);
  const auto& [sa, ra] = points_[k];
  const auto& [sb, rb] = points_[k + 1];
  const Eigen::Vector2d r = ra + (s - sa) / (sb - sa) * (rb - ra);
  return {r.x(), r.y(), 0.0};
}

Vector3 TendonPath::offset_rate(double s) const {
  if (points_.size() == 1 || s < points_.front().first || s >= points_.back().first)
    return Vector3::Zero();
  const std::size_t k = segment(points_, s);
  const Eigen::Vector2d d = (points_[k + 1].second - points_[k].second) /
                            (points_[k + 1].first - points_[k].first);
  return {d.x(), d.y(), 0.0};
}

std::vector<double> TendonPath::knots() const {
  std::vector<double> out;
  for (const auto& [s, r] : points_)
    if (s > s0_ && s < s1_) out.push_back(s);
  return out;
}

Vector6 TendonPath::unit_wrench(double s, const Vector6& xi) const {
  const Vector3 r = offset(s);
  const Vector3 t = tangent_vector(s, xi).normalized();
  return lie::se3::join(r.cross(t), t);
}

Eigen::Matrix<double, 6, 6> TendonPath::unit_wrench_jacobian(double s, const Vector6& xi) const {
  Vector6 w = Vector6::Zero();
  Eigen::Matrix<double, 6, 6> J = Eigen::Matrix<double, 6, 6>::Zero();
  add_wrench(s, xi, 1.0, w, J);
  return J;
}

void TendonPath::add_wrench(double s, const Vector6& xi, double F, Vector6& w,
                            Eigen::Matrix<double, 6, 6>& J) const {
  const Vector3 r = offset(s);
  const Vector3 u = xi.tail<3>() + xi.head<3>().cross(r) + offset_rate(s);
  const double n = u.norm();
  const Vector3 t = u / n;
  w.head<3>() += F * r.cross(t);
  w.tail<3>() += F * t;
  // dt/dxi = P [-hat(r), I] with P = (I - t t^T) / |u|, and c's top rows are hat(r) t
  const lie::Matrix3 P = (F / n) * (lie::Matrix3::Identity() - t * t.transpose());
  const lie::Matrix3 rh = lie::so3::hat(r);
  const lie::Matrix3 P_rh = P * rh;
  J.topLeftCorner<3, 3>() -= rh * P_rh;
  J.topRightCorner<3, 3>() += rh * P;
  J.bottomLeftCorner<3, 3>() -= P_rh;
  J.bottomRightCorner<3, 3>() += P;
}

}  // namespace rodlab::loads
