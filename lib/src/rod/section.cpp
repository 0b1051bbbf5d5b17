#include "rodlab/rod/section.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rodlab/check.hpp"

namespace rodlab::rod {
namespace {

using std::numbers::pi;

void require_positive(double value, const char* what) {
  RODLAB_THROW_UNLESS(value > 0.0 && std::isfinite(value), "{} must be > 0 (got {:g})", what,
                      value);
}

SectionProperties of(const Circle& c) {
  require_positive(c.diameter, "circle diameter");
  const double r2 = 0.25 * c.diameter * c.diameter;
  const double I = 0.25 * pi * r2 * r2;  // pi D^4 / 64
  return {pi * r2, I, I, 2.0 * I, 2.0 * I};
}

SectionProperties of(const Tube& t) {
  require_positive(t.outer_diameter, "tube outer_diameter");
  RODLAB_THROW_UNLESS(t.inner_diameter >= 0.0 && t.inner_diameter < t.outer_diameter,
                      "tube inner_diameter must be >= 0 and below outer_diameter (got {:g})",
                      t.inner_diameter);
  const double ro2 = 0.25 * t.outer_diameter * t.outer_diameter;
  const double ri2 = 0.25 * t.inner_diameter * t.inner_diameter;
  const double I = 0.25 * pi * (ro2 * ro2 - ri2 * ri2);  // pi (Do^4 - Di^4) / 64
  return {pi * (ro2 - ri2), I, I, 2.0 * I, 2.0 * I};
}

// Saint-Venant torsion constant of a solid a x b rectangle, a >= b (Timoshenko & Goodier, 109):
// Jt = a b^3 / 3 [1 - 192 b / (pi^5 a) sum_{n odd} tanh(n pi a / (2 b)) / n^5].
double rectangle_torsion_constant(double a, double b) {
  if (a < b) std::swap(a, b);
  double sum = 0.0;
  for (int n = 1; n < 200; n += 2) {
    const double term = std::tanh(n * pi * a / (2.0 * b)) / std::pow(n, 5);
    sum += term;
    if (term < 1e-18 * sum) break;
  }
  return a * b * b * b / 3.0 * (1.0 - 192.0 * b / (std::pow(pi, 5) * a) * sum);
}

SectionProperties of(const Rectangle& r) {
  require_positive(r.width, "rectangle width");
  require_positive(r.height, "rectangle height");
  const double w = r.width, h = r.height;
  const double Ix = w * h * h * h / 12.0;  // int y^2 dA, y along the height
  const double Iy = h * w * w * w / 12.0;  // int x^2 dA, x along the width
  return {w * h, Ix, Iy, Ix + Iy, rectangle_torsion_constant(w, h)};
}

}  // namespace

SectionProperties properties(const Section& section) {
  return std::visit([](const auto& s) { return of(s); }, section);
}

std::string_view shape_name(const Section& section) {
  struct Name {
    std::string_view operator()(const Circle&) const { return "circle"; }
    std::string_view operator()(const Tube&) const { return "tube"; }
    std::string_view operator()(const Rectangle&) const { return "rectangle"; }
  };
  return std::visit(Name{}, section);
}

double outer_radius(const Section& section) {
  struct Radius {
    double operator()(const Circle& c) const { return 0.5 * c.diameter; }
    double operator()(const Tube& t) const { return 0.5 * t.outer_diameter; }
    double operator()(const Rectangle& r) const { return 0.5 * std::hypot(r.width, r.height); }
  };
  return std::visit(Radius{}, section);
}

}  // namespace rodlab::rod
