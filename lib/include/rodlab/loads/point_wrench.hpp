#pragma once
// A wrench [moment; force] applied at a section (the tip). In the body frame it follows the
// section; in the world frame it is a dead load whose body components are [R^T m; R^T f]
// (applied at the section's centroid, so no moment arm; (2.35) with p = 0).
#include "rodlab/lie/se3.hpp"

namespace rodlab::loads {

enum class WrenchFrame { body, world };

struct PointWrench {
  lie::Vector6 wrench = lie::Vector6::Zero();
  WrenchFrame frame = WrenchFrame::body;

  lie::Vector6 body_wrench(const lie::SO3& R, double scale = 1.0) const {
    if (frame == WrenchFrame::body) return scale * wrench;
    const lie::SO3 Rt = R.inverse();
    return lie::se3::join(Rt * lie::Vector3(scale * wrench.head<3>()),
                          Rt * lie::Vector3(scale * wrench.tail<3>()));
  }
};

/// A uniform distributed wrench per unit length, body or world components; same transformation.
using DistributedWrench = PointWrench;

}  // namespace rodlab::loads
