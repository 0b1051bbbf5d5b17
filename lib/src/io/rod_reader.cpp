// rod: model, length, section, material, and the rest shape: reference_twist or rest_strain.
#include <numbers>
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

namespace {

/// A constant rest strain [kappa*; nu*] as six numbers (reference_twist, rest_strain).
std::optional<lie::Vector6> read_twist(Checker& c, const Field& f) {
  auto xi = c.vector<6>(f);
  if (!xi) return std::nullopt;
  if (xi->tail<3>().isZero(0.0)) {
    c.error(f,
            "its linear part nu* (the last 3 entries) must not be zero, or the rod has no "
            "centreline (got " +
                describe(f.node) + ")");
    return std::nullopt;
  }
  return *xi;
}

/// rest_strain: six numbers, or a named shape of constant strain (docs/scene-reference.md):
///   arc: {radius: R} or {angle: a}    curvature 1/R (= a / L) about the section's x axis
///   helix: {radius: r, pitch: p}      curvature r / (r^2 + c^2) about x and torsion
///                                     c / (r^2 + c^2), c = p / (2 pi) (p < 0: left-handed)
std::optional<lie::Vector6> read_rest_strain(Checker& c, const Field& f, double length) {
  if (f.node.IsSequence()) return read_twist(c, f);
  if (!c.is_map(f)) return std::nullopt;
  const KeyCheck kc = c.keys(f, {"arc", "helix"}, "shape");
  if (!kc) return std::nullopt;
  const auto shape = c.exactly_one(f, {"arc", "helix"}, kc.unknown == 0);
  if (!shape) return std::nullopt;
  lie::Vector6 xi = rod::RodModel::straight_twist();
  if (*shape == "arc") {
    const Field arc = Checker::child(f, "arc");
    if (!c.is_map(arc) || !c.keys(arc, {"radius", "angle"})) return std::nullopt;
    const auto given = c.exactly_one(arc, {"radius", "angle"}, true);
    if (!given) return std::nullopt;
    if (*given == "radius") {
      const auto radius = c.number(Checker::child(arc, "radius"), Range::positive());
      if (!radius) return std::nullopt;
      xi[0] = 1.0 / *radius;
    } else {
      const auto angle = c.number(Checker::child(arc, "angle"));
      if (!angle || !(length > 0.0)) return std::nullopt;
      xi[0] = *angle / length;
    }
    return xi;
  }
  const Field helix = Checker::child(f, "helix");
  if (!c.is_map(helix) || !c.keys(helix, {"radius", "pitch"})) return std::nullopt;
  const auto radius = c.number(c.require(helix, "radius"), Range::positive());
  const auto pitch = c.number(c.require(helix, "pitch"));
  if (!radius || !pitch) return std::nullopt;
  const double rise = *pitch / (2.0 * std::numbers::pi);  // c: the rise per radian
  const double d = *radius * *radius + rise * rise;
  xi[0] = *radius / d;  // curvature
  xi[2] = rise / d;     // torsion
  return xi;
}

}  // namespace

scene::Rod read_rod(Checker& c, const Field& f) {
  scene::Rod r;
  if (!c.keys(f, {"model", "length", "section", "material", "reference_twist", "rest_strain"}))
    return r;
  if (auto m = c.choice(c.child(f, "model"), {"cosserat", "kirchhoff"}))
    r.model = *m == 0 ? rod::ModelKind::cosserat : rod::ModelKind::kirchhoff;
  const auto length = c.number(c.require(f, "length"), Range::positive());
  if (length) r.length = *length;
  if (auto section = read_section(c, c.require(f, "section"))) r.section = *section;
  if (auto material = read_material(c, c.require(f, "material"))) r.material = *material;
  // The rest shape: reference_twist (six numbers) or rest_strain (six numbers or a named
  // shape), not both.
  const auto rest = c.exactly_one(f, {"reference_twist", "rest_strain"}, false);
  if (!rest) return r;
  const Field shape = Checker::child(f, *rest);
  if (auto xi = *rest == "reference_twist" ? read_twist(c, shape)
                                           : read_rest_strain(c, shape, length.value_or(0.0)))
    r.reference_twist = *xi;
  return r;
}

}  // namespace rodlab::io::detail
