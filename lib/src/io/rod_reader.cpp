// rod: model, length, section, material, and the rest shape: reference_twist or rest_strain.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

/// A named shape of constant strain (docs/scene-reference.md) in the map f, over a length:
///   arc: {radius: R} or {angle: a}    curvature 1/R (= a / length) about the section's x axis
///   helix: {radius: r, pitch: p}      curvature r / (r^2 + c^2) about x and torsion
///                                     c / (r^2 + c^2), c = p / (2 pi) (p < 0: left-handed)
/// `shape` is the key present ("arc" or "helix").
std::optional<lie::Vector6> read_shape(Checker& c, const Field& f, std::string_view shape,
                                       double length) {
  lie::Vector6 xi = rod::RodModel::straight_twist();
  if (shape == "arc") {
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

/// One span of rest_strain.spans: its length and exactly one of strain (six numbers), arc or
/// helix (an arc's angle is the span's own bend). Returns the span and its length.
std::optional<std::pair<rod::RestSpan, double>> read_span(Checker& c, const Field& f,
                                                          double begin) {
  if (!c.is_map(f) || !c.keys(f, {"length", "strain", "arc", "helix"})) return std::nullopt;
  const auto length = c.number(c.require(f, "length"), Range::positive());
  const auto form = c.exactly_one(f, {"strain", "arc", "helix"}, true);
  if (!length || !form) return std::nullopt;
  const std::string name(*form);
  const auto xi = name == "strain" ? read_twist(c, Checker::child(f, name))
                                   : read_shape(c, f, name, *length);
  if (!xi) return std::nullopt;
  return std::pair{rod::RestSpan{begin, *xi}, *length};
}

/// rest_strain.spans: a list of spans whose lengths add up to the rod's.
std::optional<std::vector<rod::RestSpan>> read_spans(Checker& c, const Field& f, double length) {
  const auto items = c.list(f, 1);
  if (!items) return std::nullopt;
  std::vector<rod::RestSpan> spans;
  double begin = 0.0;
  bool ok = true;
  for (const Field& item : *items) {
    if (auto span = read_span(c, item, begin)) {
      spans.push_back(span->first);
      begin += span->second;
    } else {
      ok = false;
    }
  }
  if (!ok || !(length > 0.0)) return std::nullopt;
  if (std::abs(begin - length) > 1e-9 * length) {
    c.error(f, "the spans' lengths add up to " + format_number(begin) +
                   " m, not the rod's length " + format_number(length) + " m");
    return std::nullopt;
  }
  return spans;
}

/// rest_strain: six numbers, a named shape of constant strain, or spans.
bool read_rest_strain(Checker& c, const Field& f, double length, scene::Rod& rod) {
  if (f.node.IsSequence()) {
    const auto xi = read_twist(c, f);
    if (xi) rod.reference_twist = *xi;
    return xi.has_value();
  }
  if (!c.is_map(f)) return false;
  const KeyCheck kc = c.keys(f, {"arc", "helix", "spans"}, "shape");
  if (!kc) return false;
  const auto shape = c.exactly_one(f, {"arc", "helix", "spans"}, kc.unknown == 0);
  if (!shape) return false;
  if (*shape == "spans") {
    const Field field = Checker::child(f, "spans");
    auto spans = read_spans(c, field, length);
    if (!spans) return false;
    rod.rest_spans = std::move(*spans);
    rod.rest_spans_line = field.mark.line + 1;
    rod.rest_spans_column = field.mark.column + 1;
    return true;
  }
  const auto xi = read_shape(c, f, *shape, length);
  if (xi) rod.reference_twist = *xi;
  return xi.has_value();
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
  if (*rest == "rest_strain") {
    read_rest_strain(c, shape, length.value_or(0.0), r);
  } else if (auto xi = read_twist(c, shape)) {
    r.reference_twist = *xi;
  }
  return r;
}

}  // namespace rodlab::io::detail
