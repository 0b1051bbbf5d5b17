#pragma once
// Evaluating a control trajectory (control.trajectory in a scene, docs/scene-reference.md).
//
// A circle of centre c, radius r, period T, `laps` laps, unit normal n is traced
// counter-clockwise about n at constant speed:
//
//   p(t) = c + r (cos phi e1 + sin phi e2),   phi = 2 pi t / T,   0 <= t <= laps T,
//
// with e2 = n x e1 and e1 the world x axis projected onto the circle's plane and normalised;
// when n is within 45 degrees of the x axis (|n_x| > 1/sqrt 2) the world y axis is projected
// instead, so e1 is never degenerate. For n = [0, 0, 1], e1 = x and e2 = y: phase 0 is at
// c + [r, 0, 0] and the tip turns from +x towards +y. Before t = 0 the trajectory waits at its
// start, after laps T at its end.
#include <utility>

#include "rodlab/scene/scene.hpp"

namespace rodlab::scene {

/// The in-plane axes (e1, e2) of a circle with unit normal n, as defined above.
std::pair<Vector3, Vector3> circle_axes(const Vector3& normal);

/// The point of the circle at time t [s].
Vector3 position(const CircleTrajectory& circle, double t);
Vector3 position(const Trajectory& trajectory, double t);

/// How long the trajectory lasts [s]: laps * period.
double duration(const CircleTrajectory& circle);
double duration(const Trajectory& trajectory);

}  // namespace rodlab::scene
