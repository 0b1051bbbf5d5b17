#include "vtk_output.hpp"

#include <system_error>

#include <fmt/format.h>

#include "rodlab/io/atomic_file.hpp"
#include "rodlab/io/rod_vtk.hpp"

namespace rodlab::cli {

VtkOutput::VtkOutput(const scene::Scene& scene, std::filesystem::path dir)
    : scene_(scene), dir_(std::move(dir)) {}

void VtkOutput::write(const std::string& name, const io::VtkPolyData& data) const {
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw io::WriteError(ec, "cannot create " + dir_.string());
  io::write_file_atomically(dir_ / name, io::vtp_text(data));
}

void VtkOutput::write_state(std::span<const result::CenterlineSample> centerline) const {
  write("rod.vtp", io::rod_polydata(scene_, centerline));
  if (!scene_.actuators.empty()) write("actuators.vtp", io::actuator_polydata(scene_, centerline));
}

void VtkOutput::add_state(double t, std::span<const result::CenterlineSample> centerline,
                          std::span<const lie::Vector6> velocities) {
  const std::size_t k = entries_.size() / (scene_.actuators.empty() ? 1 : 2);
  io::VtkPolyData rod = io::rod_polydata(scene_, centerline, velocities);
  rod.time = t;
  const std::string name = fmt::format("rod_{:06d}.vtp", k);
  write(name, rod);
  entries_.push_back({t, 0, name});
  if (scene_.actuators.empty()) return;
  io::VtkPolyData paths = io::actuator_polydata(scene_, centerline);
  paths.time = t;
  const std::string paths_name = fmt::format("actuators_{:06d}.vtp", k);
  write(paths_name, paths);
  entries_.push_back({t, 1, paths_name});
}

void VtkOutput::finish() const {
  io::write_file_atomically(dir_ / "rod.pvd", io::pvd_text(entries_));
}

void VtkOutput::write_workspace(const result::WorkspaceResult& w) const {
  io::VtkPolyData d;
  const std::size_t m = scene_.actuators.size();
  std::vector<std::vector<double>> inputs(m);
  std::vector<double> omega, phi, epsilon;
  for (const auto& s : w.samples) {
    if (!s.converged) continue;
    d.points.push_back(s.tip);
    for (std::size_t i = 0; i < m && i < s.inputs.size(); ++i) inputs[i].push_back(s.inputs[i]);
    omega.push_back(s.coordinates.omega);
    phi.push_back(s.coordinates.phi);
    epsilon.push_back(s.coordinates.epsilon);
  }
  for (std::size_t i = 0; i < m; ++i) d.add_scalars(fmt::format("input_{}", i), inputs[i]);
  d.add_scalars("omega", std::move(omega));
  d.add_scalars("phi", std::move(phi));
  d.add_scalars("epsilon", std::move(epsilon));
  d.field_data.emplace_back("omega_bound", w.bounds.omega_bound);
  d.field_data.emplace_back("epsilon_low", w.bounds.eps_low);
  d.field_data.emplace_back("epsilon_high", w.bounds.eps_high);
  write("workspace.vtp", d);
}

}  // namespace rodlab::cli
