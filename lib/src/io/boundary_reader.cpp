// base and tip: poses, the free tip's wrench (also used by loads.distributed).
#include <Eigen/SVD>
#include <cmath>

#include "rodlab/check.hpp"
#include "scene_readers.hpp"

namespace rodlab::io::detail {
namespace {

constexpr double kRotationTolerance = 1e-6;

bool is_word(const Field& f, std::string_view word) {
  return f.node.IsScalar() && f.node.Scalar() == word;
}

/// A 3x3 matrix that is a rotation to kRotationTolerance, projected onto SO(3) exactly.
std::optional<lie::SO3> read_rotation_matrix(Checker& c, const Field& f) {
  const auto R = c.matrix3(f);
  if (!R) return std::nullopt;
  const double orthogonality = (R->transpose() * *R - Eigen::Matrix3d::Identity()).norm();
  const double det = R->determinant();
  if (!(orthogonality <= kRotationTolerance && std::abs(det - 1.0) <= kRotationTolerance)) {
    c.error(f, rodlab::format("must be a rotation matrix, orthonormal with det +1 to 1e-6 (got "
                              "||R^T R - I|| = {:.3g}, det = {:.3g})",
                              orthogonality, det));
    return std::nullopt;
  }
  // Nearest rotation: the polar factor U V^T of R = U S V^T.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(*R, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return lie::SO3::from_matrix(svd.matrixU() * svd.matrixV().transpose());
}

/// identity | 3x3 matrix | {axis: [3], angle: rad} (axis normalised; the angle is about it).
std::optional<lie::SO3> read_rotation(Checker& c, const Field& f) {
  if (!f.present()) return std::nullopt;
  if (is_word(f, "identity")) return lie::SO3::identity();
  if (f.node.IsSequence()) return read_rotation_matrix(c, f);
  if (!f.node.IsMap()) {
    c.error(f, "must be identity, a 3x3 matrix or {axis, angle} (got " + describe(f.node) + ")");
    return std::nullopt;
  }
  c.keys(f, {"axis", "angle"});
  const Field axis_field = c.require(f, "axis");
  const auto axis = c.vector<3>(axis_field);
  const auto angle = c.number(c.require(f, "angle"));
  if (axis && axis->isZero(0.0)) {
    c.error(axis_field, "must not be zero (got " + describe(axis_field.node) + ")");
    return std::nullopt;
  }
  if (!axis || !angle) return std::nullopt;
  return lie::SO3::exp(axis->normalized() * *angle);
}

}  // namespace

std::optional<lie::SE3> read_pose(Checker& c, const Field& f) {
  if (!f.present()) return std::nullopt;
  if (is_word(f, "identity")) return lie::SE3::identity();
  if (f.node.IsScalar() || f.node.IsSequence()) {
    c.error(f, "must be identity or a map {position: [x, y, z], rotation: ...} (got " +
                   describe(f.node) + ")");
    return std::nullopt;
  }
  if (!c.keys(f, {"position", "rotation"})) return std::nullopt;
  const Field position_field = c.child(f, "position");
  const Field rotation_field = c.child(f, "rotation");
  const auto position = c.vector<3>(position_field);
  const auto rotation = read_rotation(c, rotation_field);
  if ((position_field.present() && !position) || (rotation_field.present() && !rotation))
    return std::nullopt;
  return lie::SE3(rotation.value_or(lie::SO3::identity()),
                  position.value_or(Eigen::Vector3d::Zero()));
}

scene::Base read_base(Checker& c, const Field& f) {
  scene::Base base;
  if (!c.keys(f, {"pose"})) return base;
  if (auto pose = read_pose(c, c.child(f, "pose"))) base.pose = *pose;
  return base;
}

WrenchFields read_wrench(Checker& c, const Field& f, scene::Frame default_frame) {
  WrenchFields w;
  w.frame = default_frame;
  if (!c.keys(f, {"moment", "force", "frame"})) return w;
  if (auto m = read_vector_input(c, c.child(f, "moment"))) w.moment = *m;
  if (auto force = read_vector_input(c, c.child(f, "force"))) w.force = *force;
  if (auto frame = c.choice(c.child(f, "frame"), {"body", "world"}))
    w.frame = *frame == 0 ? scene::Frame::body : scene::Frame::world;
  return w;
}

std::optional<scene::Tip> read_tip(Checker& c, const Field& f) {
  const KeyCheck kc = c.keys(f, {"free", "clamped"});
  if (!kc) return std::nullopt;
  const auto which = c.exactly_one(f, {"free", "clamped"}, kc.unknown == 0);
  if (!which) return std::nullopt;
  if (*which == "clamped") {
    const auto pose = read_pose(c, c.child(f, "clamped"));
    if (!pose) return std::nullopt;
    return scene::ClampedTip{*pose};
  }
  const Field free = c.child(f, "free");
  scene::FreeTip tip;
  if (!c.keys(free, {"wrench"})) return std::nullopt;
  const WrenchFields w = read_wrench(c, c.child(free, "wrench"), scene::Frame::body);
  tip.wrench = scene::Wrench{w.moment, w.force, w.frame};
  return tip;
}

}  // namespace rodlab::io::detail
