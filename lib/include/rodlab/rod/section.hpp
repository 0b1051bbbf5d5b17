#pragma once
// Cross-sections of the rod and their geometric properties. Axes: x and y are the principal
// axes of the section, z is along the centreline (docs/conventions.md).
#include <string_view>
#include <variant>

namespace rodlab::rod {

struct Circle {
  double diameter = 0.0;
};
struct Tube {
  double outer_diameter = 0.0;
  double inner_diameter = 0.0;
};
/// width along the section's x axis, height along its y axis.
struct Rectangle {
  double width = 0.0;
  double height = 0.0;
};

using Section = std::variant<Circle, Tube, Rectangle>;

struct SectionProperties {
  double A = 0.0;    ///< area
  double Ix = 0.0;   ///< second moment about x: int y^2 dA (bending about x)
  double Iy = 0.0;   ///< second moment about y: int x^2 dA (bending about y)
  double J = 0.0;    ///< polar second moment int (x^2 + y^2) dA = Ix + Iy (rotary inertia, (3.4))
  double Jt = 0.0;   ///< torsion constant (Saint-Venant); equals J for circles and tubes
};

/// Geometric properties; throws std::invalid_argument for non-positive or inconsistent sizes.
SectionProperties properties(const Section& section);

/// "circle", "tube" or "rectangle".
std::string_view shape_name(const Section& section);

/// Largest distance of a section point from the centroid.
double outer_radius(const Section& section);

}  // namespace rodlab::rod
