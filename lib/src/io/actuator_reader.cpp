// actuators: cable, fluidic and muscle, with their offsets/routings, spans, limits and inputs.
#include "scene_readers.hpp"

namespace rodlab::io::detail {
namespace {

using Limits = std::pair<double, double>;

std::string length_bound(std::optional<double> rod_length) {
  return rod_length ? "rod.length = " + format_number(*rod_length) : std::string("rod.length");
}

/// offset: [x, y] or [x, y, 0].
std::optional<scene::Offset> read_constant_offset(Checker& c, const Field& f) {
  if (!f.node.IsSequence() || (f.node.size() != 2 && f.node.size() != 3)) {
    c.error(f, "must be [x, y] or [x, y, 0] (got " + describe(f.node) + ")");
    return std::nullopt;
  }
  const auto x = c.number(Checker::element(f, 0));
  const auto y = c.number(Checker::element(f, 1));
  if (f.node.size() == 3) {
    const Field z_field = Checker::element(f, 2);
    const auto z = c.number(z_field);
    if (z && *z != 0.0) {
      c.error(z_field,
              "must be 0: an actuator lies in the cross-section plane; use routing to "
              "move it along s (got " +
                  describe(z_field.node) + ")");
      return std::nullopt;
    }
  }
  if (!x || !y) return std::nullopt;
  return scene::Offset{{{0.0, scene::Vector2(*x, *y)}}};
}

/// routing: [[s, x, y], ...] with s strictly increasing within [0, L].
std::optional<scene::Offset> read_routing(Checker& c, const Field& f, std::optional<double> L) {
  const auto items = c.list(f, 1);
  if (!items) return std::nullopt;
  scene::Offset offset;
  bool ok = true;
  std::optional<std::pair<double, std::string>> previous;  // (s, as written)
  for (const Field& item : *items) {
    const auto point = c.vector<3>(item);
    if (!point) {
      ok = false;
      continue;
    }
    const Field s_field = Checker::element(item, 0);
    const double s = (*point)[0];
    if (s < 0.0 || (L && s > *L)) {
      c.error(s_field.mark, item.path,
              "s must be in [0, " + length_bound(L) + "] (got " + s_field.node.Scalar() + ")");
      ok = false;
    } else if (previous && s <= previous->first) {
      c.error(s_field.mark, item.path,
              "s must increase along the routing (got " + s_field.node.Scalar() + " after " +
                  previous->second + ")");
      ok = false;
    }
    previous = {s, s_field.node.Scalar()};
    offset.points.emplace_back(s, point->tail<2>());
  }
  if (!ok) return std::nullopt;
  return offset;
}

/// Exactly one of offset / routing.
std::optional<scene::Offset> read_offset(Checker& c, const Field& actuator,
                                         std::optional<double> L) {
  const auto which = c.exactly_one(actuator, {"offset", "routing"}, true);
  if (!which) return std::nullopt;
  const Field f = Checker::child(actuator, *which);
  return *which == "offset" ? read_constant_offset(c, f) : read_routing(c, f, L);
}

/// span: [s0, s1] with 0 <= s0 < s1 <= L.
std::optional<scene::Span> read_span(Checker& c, const Field& f, std::optional<double> L) {
  const auto v = c.vector<2>(f);
  if (!v) return std::nullopt;
  if (!((*v)[0] >= 0.0 && (*v)[0] < (*v)[1] && (!L || (*v)[1] <= *L))) {
    c.error(f, "must be [s0, s1] with 0 <= s0 < s1 <= " + length_bound(L) + " (got " +
                   describe(f.node) + ")");
    return std::nullopt;
  }
  return scene::Span{(*v)[0], (*v)[1]};
}

/// limits: [min, max] with min <= max.
std::optional<Limits> read_limits(Checker& c, const Field& f) {
  const auto v = c.vector<2>(f);
  if (!v) return std::nullopt;
  if ((*v)[0] > (*v)[1]) {
    c.error(f, "must be [min, max] with min <= max (got " + describe(f.node) + ")");
    return std::nullopt;
  }
  return Limits{(*v)[0], (*v)[1]};
}

/// The input `key` (a number in `range` or a schedule of them), every value within the limits.
std::optional<scene::ScalarSchedule> read_input(Checker& c, const Field& actuator,
                                                std::string_view key, const Range& range,
                                                const std::optional<Limits>& limits) {
  const Field f = Checker::child(actuator, key);
  auto input = read_scalar_input(c, f, range);
  if (!input || !limits) return input;
  for (const auto& [t, v] : input->points()) {
    if (v < limits->first || v > limits->second) {
      c.error(f, "must stay within limits [" + format_number(limits->first) + ", " +
                     format_number(limits->second) + "] (got " + format_number(v) + ")");
      return std::nullopt;
    }
  }
  return input;
}

/// The fields every actuator has: where it sits, its span and its limits.
template <class Actuator>
Actuator read_placement(Checker& c, const Field& f, std::optional<double> L) {
  Actuator a;
  if (auto offset = read_offset(c, f, L)) a.offset = *offset;
  a.span = read_span(c, Checker::child(f, "span"), L);
  a.limits = read_limits(c, Checker::child(f, "limits"));
  return a;
}

scene::Cable read_cable(Checker& c, const Field& f, std::optional<double> L) {
  if (!c.keys(f, {"offset", "routing", "tension", "displacement", "span", "limits"})) return {};
  auto cable = read_placement<scene::Cable>(c, f, L);
  const auto input = c.exactly_one(f, {"tension", "displacement"}, true);
  if (input == "tension")
    cable.tension = read_input(c, f, "tension", Range::non_negative(), cable.limits);
  else if (input == "displacement")
    cable.displacement = read_input(c, f, "displacement", Range::any(), cable.limits);
  return cable;
}

scene::Fluidic read_fluidic(Checker& c, const Field& f, std::optional<double> L) {
  if (!c.keys(f, {"offset", "routing", "chamber_radius", "pressure", "volume", "span", "limits"}))
    return {};
  auto fluidic = read_placement<scene::Fluidic>(c, f, L);
  if (auto r = c.number(c.require(f, "chamber_radius"), Range::positive()))
    fluidic.chamber_radius = *r;
  const auto input = c.exactly_one(f, {"pressure", "volume"}, true);
  if (input == "pressure")
    fluidic.pressure = read_input(c, f, "pressure", Range::non_negative(), fluidic.limits);
  else if (input == "volume")
    fluidic.volume = read_input(c, f, "volume", Range::non_negative(), fluidic.limits);
  return fluidic;
}

scene::MuscleLaw read_muscle_law(Checker& c, const Field& f) {
  scene::MuscleLaw law;
  if (!c.keys(f, {"type", "gain", "stiffness"})) return law;
  if (c.choice(c.child(f, "type"), {"linear"})) law.type = "linear";  // the only law so far
  if (auto gain = c.number(c.require(f, "gain"))) law.gain = *gain;
  if (auto k = c.number(c.child(f, "stiffness"), Range::non_negative())) law.stiffness = *k;
  return law;
}

scene::Muscle read_muscle(Checker& c, const Field& f, std::optional<double> L) {
  if (!c.keys(f, {"offset", "routing", "section", "material", "input", "law", "span", "limits"}))
    return {};
  auto muscle = read_placement<scene::Muscle>(c, f, L);
  if (auto section = read_section(c, c.require(f, "section"))) muscle.section = *section;
  if (auto material = read_material(c, c.require(f, "material"))) muscle.material = *material;
  c.require(f, "input");
  if (auto q = read_input(c, f, "input", Range::any(), muscle.limits)) muscle.input = *q;
  muscle.law = read_muscle_law(c, c.require(f, "law"));
  return muscle;
}

}  // namespace

std::vector<scene::Actuator> read_actuators(Checker& c, const Field& f,
                                            std::optional<double> rod_length) {
  std::vector<scene::Actuator> actuators;
  const auto items = c.list(f);
  if (!items) return actuators;
  for (const Field& item : *items) {
    const KeyCheck kc = c.keys(item, {"cable", "fluidic", "muscle"}, "actuator type");
    if (!kc) continue;
    const auto type = c.exactly_one(item, {"cable", "fluidic", "muscle"}, kc.unknown == 0);
    if (!type) continue;
    const Field a = Checker::child(item, *type);
    if (*type == "cable")
      actuators.emplace_back(read_cable(c, a, rod_length));
    else if (*type == "fluidic")
      actuators.emplace_back(read_fluidic(c, a, rod_length));
    else
      actuators.emplace_back(read_muscle(c, a, rod_length));
  }
  return actuators;
}

}  // namespace rodlab::io::detail
