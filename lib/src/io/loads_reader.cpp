// loads: gravity, drag, buoyancy, distributed wrench.
#include "scene_readers.hpp"

namespace rodlab::io::detail {

scene::Loads read_loads(Checker& c, const Field& f) {
  scene::Loads loads;
  if (!c.keys(f, {"gravity", "drag", "buoyancy", "distributed"})) return loads;
  loads.gravity = c.vector<3>(c.child(f, "gravity"));

  const Field drag = c.child(f, "drag");
  if (c.keys(drag, {"fluid_density", "laminar", "turbulent"})) {
    scene::Drag d;  // (3.11), (3.12)
    if (auto rho = c.number(c.require(drag, "fluid_density"), Range::non_negative()))
      d.fluid_density = *rho;
    const Field laminar = c.child(drag, "laminar");
    const Field turbulent = c.child(drag, "turbulent");
    if (auto v = c.vector<6>(laminar, Range::non_negative())) d.laminar = *v;
    if (auto v = c.vector<6>(turbulent, Range::non_negative())) d.turbulent = *v;
    c.at_least_one(drag, {"laminar", "turbulent"});
    loads.drag = d;
  }

  const Field buoyancy = c.child(f, "buoyancy");
  if (c.keys(buoyancy, {"fluid_density"})) {
    scene::Buoyancy b;  // gravity acts on rho - fluid_density (2.36)
    if (auto rho = c.number(c.require(buoyancy, "fluid_density"), Range::non_negative()))
      b.fluid_density = *rho;
    if (!c.child(f, "gravity").present())
      c.error(buoyancy.key_mark, buoyancy.path, "has no effect without loads.gravity");
    loads.buoyancy = b;
  }

  const Field distributed = c.child(f, "distributed");
  if (distributed.present()) {
    const WrenchFields w = read_wrench(c, distributed, scene::Frame::world);
    loads.distributed = scene::DistributedWrench{w.moment, w.force, w.frame};
  }
  return loads;
}

}  // namespace rodlab::io::detail
