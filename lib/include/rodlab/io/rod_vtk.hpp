#pragma once
// A rod's state as VTK polydata (vtk.hpp; docs/visualisation.md): what `--vtk DIR` writes.
//
// rod_polydata: the centreline as one polyline through the nodes, base first, with per node
//   s                 arclength [m]
//   radius            the section's outer radius [m] (ParaView's Tube filter: vary the radius
//                     by this scalar, "absolute"), also in the field data
//   d1, d2, d3        the cross-section's frame, the columns of R(s) (world)
//   curvature         kappa, the angular strain (body frame) [1/m]
//   stretch_shear     nu, the linear strain (body frame): [0, 0, 1] unstretched and unsheared
//   moment, force     the internal wrench K (xi - xi*) = [m; n] (2.28), turned into the world
//                     frame; a Kirchhoff rod's force is a constraint force, not written
//   angular_velocity, velocity   R omega and R v (world frame) of eta = [omega; v], when given
// actuator_polydata: each actuator's path, p(s) + R(s) [x(s), y(s), 0] at the nodes inside
//   its span, one polyline per actuator, with `actuator` (its index in the scene) and `s`.
#include <span>

#include "rodlab/io/vtk.hpp"
#include "rodlab/result/static_result.hpp"
#include "rodlab/scene/scene.hpp"

namespace rodlab::io {

/// The rod's centreline (see above); `velocities`: eta per node (empty: not written).
VtkPolyData rod_polydata(const scene::Scene& scene,
                         std::span<const result::CenterlineSample> centerline,
                         std::span<const lie::Vector6> velocities = {});

/// The scene's actuator paths on the centreline; no points when the scene has no actuator.
VtkPolyData actuator_polydata(const scene::Scene& scene,
                              std::span<const result::CenterlineSample> centerline);

}  // namespace rodlab::io
