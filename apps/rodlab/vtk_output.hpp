#pragma once
// --vtk DIR: ParaView files of a run (docs/visualisation.md). A static state is DIR/rod.vtp (and
// DIR/actuators.vtp when the scene has actuators); a time series is DIR/rod_<k>.vtp (and
// DIR/actuators_<k>.vtp) per recorded time, k = 0, 1, ..., with DIR/rod.pvd listing them with
// their times (part 0: the rod, part 1: the actuators), which ParaView opens as an animation. A
// workspace is DIR/workspace.vtp, a point cloud of the reached tips. Every file is written
// atomically; the .pvd last, so that it lists only files that exist.
#include <filesystem>
#include <span>
#include <vector>

#include "rodlab/io/vtk.hpp"
#include "rodlab/result/static_result.hpp"
#include "rodlab/result/workspace_result.hpp"
#include "rodlab/scene/scene.hpp"

namespace rodlab::cli {

class VtkOutput {
 public:
  /// `dir` (and its parents) is created with the first file; io::WriteError when it cannot.
  VtkOutput(const scene::Scene& scene, std::filesystem::path dir);

  /// A static state: rod.vtp (and actuators.vtp).
  void write_state(std::span<const result::CenterlineSample> centerline) const;
  /// One state of a time series: rod_<k>.vtp (and actuators_<k>.vtp) at time t.
  void add_state(double t, std::span<const result::CenterlineSample> centerline,
                 std::span<const lie::Vector6> velocities);
  /// rod.pvd, listing the states added.
  void finish() const;
  /// workspace.vtp: the converged samples' tips with their inputs (input_<i>, one per
  /// actuator) and model coordinates (omega, phi, epsilon).
  void write_workspace(const result::WorkspaceResult& workspace) const;

 private:
  void write(const std::string& name, const io::VtkPolyData& data) const;

  const scene::Scene& scene_;
  std::filesystem::path dir_;
  std::vector<io::VtkCollectionEntry> entries_;
};

}  // namespace rodlab::cli
