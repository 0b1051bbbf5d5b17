#pragma once
// Bathe and Bolourchi's 45-degree bend (K.-J. Bathe, S. Bolourchi, Large displacement analysis
// of three-dimensional beam structures, IJNME 14 (1979) 961-986): a cantilever on an eighth of
// a circle of radius 100 in the x-y plane, clamped at the origin with its tangent along +x,
// bending towards +y (the unloaded tip at (100 sin 45, 100 (1 - cos 45), 0)); a unit square
// section, E = 1e7, Poisson's ratio 0 (G = E / 2); a dead tip force P along +z. The published
// solutions take the torsional stiffness G J with J = 1/6, the polar moment of the unit square
// (BeamDyn's test of the case lists GJ = 8.333e5), not its Saint-Venant constant 0.1406.
//
// The published tip positions are finite-element solutions:
//   Simo & Vu-Quoc (J.C. Simo, L. Vu-Quoc, A three-dimensional finite-strain rod model. Part II:
//   computational aspects, CMAME 58 (1986) 79-116), 8 elements, at P = 300, 450, 600;
//   Bathe & Bolourchi (1979) at P = 600: (47.2, 15.9, 53.4).
// Discretisations of this kind sit a few tenths of a percent of the tip displacement from the
// converged solution.
#include <array>
#include <cmath>
#include <numbers>

#include "rodlab/lie/se3.hpp"

namespace rodlab::validation::reference::bathe_bolourchi {

constexpr double kRadius = 100.0;
constexpr double kE = 1.0e7, kG = 0.5e7, kSide = 1.0;
constexpr double kGJ = kG / 6.0;  ///< the published torsional stiffness (J = 1/6)
constexpr double kLength = kRadius * std::numbers::pi / 4.0;

struct Published {
  double force, x, y, z;
};

/// Simo & Vu-Quoc (1986), Table 2 (8 elements).
constexpr std::array<Published, 3> kSimoVuQuoc{{{300.0, 58.84, 22.33, 40.08},
                                               {450.0, 52.32, 18.62, 48.39},
                                               {600.0, 47.23, 15.79, 53.37}}};
/// Bathe & Bolourchi (1979) at P = 600.
constexpr Published kBatheBolourchi{600.0, 47.2, 15.9, 53.4};

/// The tolerance against a published tip: 0.5 % of its displacement from the unloaded tip
/// (the published solutions are coarse finite-element discretisations).
constexpr double kPublishedTolerance = 5e-3;

inline lie::Vector3 unloaded_tip() {
  const double a = std::numbers::pi / 4.0;
  return {kRadius * std::sin(a), kRadius * (1.0 - std::cos(a)), 0.0};
}

}  // namespace rodlab::validation::reference::bathe_bolourchi
