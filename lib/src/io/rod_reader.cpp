// rod: model, length, section, material, reference_twist.
#include <stdexcept>

#include "scene_readers.hpp"

namespace rodlab::io::detail {

std::optional<rod::Section> read_section(Checker& c, const Field& f) {
  if (!c.is_map(f)) return std::nullopt;
  const auto shape = c.choice(Checker::child(f, "shape"), {"circle", "tube", "rectangle"});
  if (!shape) {
    // Without a (known) shape, check the keys against every shape's dimensions.
    c.keys(f, {"shape", "diameter", "outer_diameter", "inner_diameter", "width", "height"});
    c.require(f, "shape");
    return std::nullopt;
  }
  switch (*shape) {
    case 0: {
      c.keys(f, {"shape", "diameter"});
      const auto d = c.number(c.require(f, "diameter"), Range::positive());
      if (!d) return std::nullopt;
      return rod::Circle{*d};
    }
    case 1: {
      c.keys(f, {"shape", "outer_diameter", "inner_diameter"});
      const auto outer = c.number(c.require(f, "outer_diameter"), Range::positive());
      const Field inner_field = c.require(f, "inner_diameter");
      const auto inner = c.number(inner_field, Range::non_negative());
      if (!outer || !inner) return std::nullopt;
      if (*inner >= *outer) {
        c.error(inner_field, "must be < outer_diameter = " + format_number(*outer) + " (got " +
                                 describe(inner_field.node) + ")");
        return std::nullopt;
      }
      return rod::Tube{*outer, *inner};
    }
    default: {
      c.keys(f, {"shape", "width", "height"});
      const auto width = c.number(c.require(f, "width"), Range::positive());
      const auto height = c.number(c.require(f, "height"), Range::positive());
      if (!width || !height) return std::nullopt;
      return rod::Rectangle{*width, *height};
    }
  }
}

std::optional<rod::Material> read_material(Checker& c, const Field& f) {
  if (!c.keys(f, {"E", "G", "poisson", "rho", "viscosity"})) return std::nullopt;
  const auto E = c.number(c.require(f, "E"), Range::positive());
  const auto rho = c.number(c.require(f, "rho"), Range::positive());
  double viscosity = 0.0;
  if (auto v = c.number(c.child(f, "viscosity"), Range::non_negative())) viscosity = *v;
  const auto which = c.exactly_one(f, {"G", "poisson"}, true);
  if (!which) return std::nullopt;
  if (*which == "G") {
    const auto G = c.number(c.child(f, "G"), Range::positive());
    if (!E || !rho || !G) return std::nullopt;
    return rod::Material{*E, *G, *rho, viscosity};
  }
  const Range poisson_range{-1.0, 0.5, true, false};  // (-1, 0.5]: G > 0, bulk modulus >= 0
  const auto poisson = c.number(c.child(f, "poisson"), poisson_range);
  if (!E || !rho || !poisson) return std::nullopt;
  return rod::Material::from_poisson(*E, *poisson, *rho, viscosity);
}

scene::Rod read_rod(Checker& c, const Field& f) {
  scene::Rod r;
  if (!c.keys(f, {"model", "length", "section", "material", "reference_twist"})) return r;
  if (auto m = c.choice(c.child(f, "model"), {"cosserat", "kirchhoff"}))
    r.model = *m == 0 ? rod::ModelKind::cosserat : rod::ModelKind::kirchhoff;
  if (auto length = c.number(c.require(f, "length"), Range::positive())) r.length = *length;
  if (auto section = read_section(c, c.require(f, "section"))) r.section = *section;
  if (auto material = read_material(c, c.require(f, "material"))) r.material = *material;
  const Field twist = c.child(f, "reference_twist");
  if (auto xi = c.vector<6>(twist)) {
    if (xi->tail<3>().isZero(0.0))
      c.error(twist,
              "its linear part nu* (the last 3 entries) must not be zero, or the rod has no "
              "centreline (got " +
                  describe(twist.node) + ")");
    else
      r.reference_twist = *xi;
  }
  return r;
}

}  // namespace rodlab::io::detail
