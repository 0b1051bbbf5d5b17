#pragma once
// The control tests' robot: the thesis' Table 2.1 rod (L = 0.1 m, D = 1 cm, E = 1 MPa,
// G = 0.33 MPa, rho = 1000 kg/m^3) with four cables at 4 mm, tensions in [0, 0.5] N (thesis
// 2.7.3, scenes/cable-driven.yaml) and Kelvin-Voigt viscosity alpha = 300 Pa s
// (scenes/viscous-cantilever.yaml), no gravity.
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/control/plant.hpp"

namespace rodlab::testing::control {

inline scene::Scene cable_robot(const std::string& model = "cosserat",
                                const std::string& limits = "limits: [0, 0.5]") {
  const std::string cable = "  - cable: {offset: [%x, %y, 0], tension: 0, " + limits + "}\n";
  auto with = [&](const char* x, const char* y) {
    std::string c = cable;
    c.replace(c.find("%x"), 2, x);
    c.replace(c.find("%y"), 2, y);
    return c;
  };
  const std::string yaml =
      "schema: rodlab.scene/1\nname: cable-robot\nrod:\n  model: " + model +
      "\n  length: 0.1\n  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 300}\n"
      "tip:\n  free: {}\nactuators:\n" +
      with("0.004", "0") + with("0", "0.004") + with("-0.004", "0") + with("0", "-0.004");
  return io::load_scene_from_string(yaml, "cable-robot.yaml");
}

/// Plant options: `scheme` at N nodes (the schemes' default grid and options), dt_c.
inline solvers::control::PlantOptions plant_options(const std::string& scheme, int nodes,
                                                    double dt_control) {
  solvers::control::PlantOptions o;
  o.solver.scheme = scheme;
  o.solver.nodes = nodes;
  o.dt_control = dt_control;
  return o;
}

}  // namespace rodlab::testing::control
