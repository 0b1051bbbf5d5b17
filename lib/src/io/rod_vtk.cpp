#include "rodlab/io/rod_vtk.hpp"

#include <stdexcept>
#include <variant>

#include "rodlab/rod/section.hpp"

namespace rodlab::io {

VtkPolyData rod_polydata(const scene::Scene& scene,
                         std::span<const result::CenterlineSample> centerline,
                         std::span<const lie::Vector6> velocities) {
  const std::size_t n = centerline.size();
  if (!velocities.empty() && velocities.size() != n)
    throw std::invalid_argument("vtk: the velocities are not one per centreline node");
  const rod::RodModel model = scene.rod.to_model();
  const double radius = rod::outer_radius(scene.rod.section);
  VtkPolyData d;
  d.field_data.emplace_back("radius", radius);
  d.lines.emplace_back();
  std::vector<double> s(n), r(n, radius);
  std::vector<lie::Vector3> d1(n), d2(n), d3(n), kappa(n), nu(n), m(n), f(n), w(n), v(n);
  for (std::size_t j = 0; j < n; ++j) {
    const auto& c = centerline[j];
    const lie::Matrix3 R = c.pose.rotation_matrix();
    d.points.push_back(c.pose.translation());
    d.lines.back().push_back(static_cast<int>(j));
    s[j] = c.s;
    d1[j] = R.col(0), d2[j] = R.col(1), d3[j] = R.col(2);
    kappa[j] = c.twist.head<3>();
    nu[j] = c.twist.tail<3>();
    // (2.28); xi*(s): at a rest-strain span begin, the span it begins
    const lie::Vector6 wrench = model.K_diag().cwiseProduct(c.twist - model.xi_star(c.s));
    m[j] = R * wrench.head<3>();
    f[j] = R * wrench.tail<3>();
    if (!velocities.empty()) {
      w[j] = R * velocities[j].head<3>();
      v[j] = R * velocities[j].tail<3>();
    }
  }
  d.add_scalars("s", std::move(s));
  d.add_scalars("radius", std::move(r));
  d.add_vectors("d1", d1);
  d.add_vectors("d2", d2);
  d.add_vectors("d3", d3);
  d.add_vectors("curvature", kappa);
  d.add_vectors("stretch_shear", nu);
  d.add_vectors("moment", m);
  if (!model.is_kirchhoff()) d.add_vectors("force", f);
  if (!velocities.empty()) {
    d.add_vectors("angular_velocity", w);
    d.add_vectors("velocity", v);
  }
  return d;
}

VtkPolyData actuator_polydata(const scene::Scene& scene,
                              std::span<const result::CenterlineSample> centerline) {
  VtkPolyData d;
  std::vector<double> index, s;
  const double tolerance = 1e-9 * scene.rod.length;
  for (std::size_t a = 0; a < scene.actuators.size(); ++a) {
    const auto [offset, span] = std::visit(
        [](const auto& x) { return std::pair{x.offset, x.span}; }, scene.actuators[a]);
    std::vector<int> line;
    for (const auto& c : centerline) {
      if (span && (c.s < span->s0 - tolerance || c.s > span->s1 + tolerance)) continue;
      const scene::Vector2 xy = offset.at(c.s);
      line.push_back(static_cast<int>(d.points.size()));
      d.points.push_back(c.pose.translation() +
                         c.pose.rotation_matrix() * lie::Vector3(xy[0], xy[1], 0.0));
      index.push_back(static_cast<double>(a));
      s.push_back(c.s);
    }
    if (line.size() >= 2) d.lines.push_back(std::move(line));
  }
  d.add_scalars("actuator", std::move(index));
  d.add_scalars("s", std::move(s));
  return d;
}

}  // namespace rodlab::io
