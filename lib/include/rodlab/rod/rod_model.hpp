#pragma once
// The immutable rod model (Pinocchio's Model/Data split: algorithms take a const RodModel&).
//   K = diag(E Ix, E Iy, G Jt, G A, G A, E A)          (2.28)
//   M = rho diag(Ix, Iy, J, A, A, A)                   (3.5)
//   V = alpha diag(3 Ix, 3 Iy, J, A, A, 3 A)           (3.10), Trouton ratio 3 for extension
// with the reference twist xi* (the rest strain; straight rod: [0 0 0 0 0 1]), constant along s
// or piecewise constant over spans (issue #18: rod.rest_strain.spans).
// model kirchhoff holds nu = nu* (3.45): only the angular strains are free.
#include <algorithm>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "rodlab/lie/se3.hpp"
#include "rodlab/rod/material.hpp"
#include "rodlab/rod/section.hpp"

namespace rodlab::rod {

using lie::Matrix6;
using lie::Vector6;

enum class ModelKind { cosserat, kirchhoff };

/// A stretch of constant rest strain: from `begin` (arclength) to the next span's begin, or L.
struct RestSpan {
  double begin = 0.0;
  Vector6 xi_star;
};

class RodModel {
 public:
  /// Throws std::invalid_argument for a non-positive length or modulus, a bad section, or
  /// a reference twist whose linear part is zero (no centreline).
  RodModel(double length, const Section& section, const Material& material,
           ModelKind kind = ModelKind::cosserat,
           const Vector6& reference_twist = straight_twist());

  /// A rest strain piecewise constant over spans: spans.front().begin == 0, begins ascending
  /// and below the length. Throws std::invalid_argument otherwise, or for a span whose nu* is 0.
  RodModel(double length, const Section& section, const Material& material, ModelKind kind,
           std::vector<RestSpan> spans);

  static Vector6 straight_twist() { return (Vector6() << 0, 0, 0, 0, 0, 1).finished(); }

  double length() const { return length_; }
  const Section& section() const { return section_; }
  const Material& material() const { return material_; }
  ModelKind kind() const { return kind_; }
  bool is_kirchhoff() const { return kind_ == ModelKind::kirchhoff; }
  const SectionProperties& properties() const { return props_; }
  /// The rest strain of a uniform rod (of the first span when it has several).
  const Vector6& xi_star() const { return xi_star_; }
  /// The rest strain of the span that holds s (a span's begin belongs to it).
  const Vector6& xi_star(double s) const {
    if (spans_.size() == 1) return xi_star_;
    std::size_t k = 0;
    while (k + 1 < spans_.size() && spans_[k + 1].begin <= s) ++k;
    return spans_[k].xi_star;
  }
  /// The rest strain of segment j = [s_j, s_(j+1)] of the uniform grid of `nodes` nodes, read
  /// at its midpoint (with every span beginning on a node, the span that holds the segment).
  const Vector6& segment_xi_star(int j, int nodes) const {
    return xi_star((j + 0.5) * length_ / (nodes - 1));
  }
  /// Node j's on a grid with strains at the nodes (the shooting schemes' Euler grid, where node
  /// j's strain carries the pose along segment j): segment min(j, nodes - 2)'s.
  const Vector6& node_xi_star(int j, int nodes) const {
    return segment_xi_star(std::min(j, nodes - 2), nodes);
  }
  /// Whether the rest strain changes along s (more than one span).
  bool has_rest_spans() const { return spans_.size() > 1; }
  const std::vector<RestSpan>& rest_spans() const { return spans_; }
  /// The span begins inside (0, L), where xi* jumps.
  std::vector<double> rest_breaks() const;
  /// The rest shape at s relative to the base: the product of exp(l_k xi*_k) over the spans
  /// up to s.
  lie::SE3 rest_pose(double s) const;
  /// Its rotation alone, the product of exp(l_k omega*_k) (exp(s omega*) for a uniform rod).
  lie::SO3 rest_rotation(double s) const;
  /// Throws std::invalid_argument unless every span begins on a node of the uniform grid of
  /// `nodes` nodes (each segment then lies in one span, whose xi* it takes); `who` names the
  /// scheme in the message.
  void require_spans_on_grid(int nodes, std::string_view who) const;

  /// Diagonals of K, M, V, and of K^-1.
  const Vector6& K_diag() const { return K_; }
  const Vector6& M_diag() const { return M_; }
  const Vector6& V_diag() const { return V_; }
  const Vector6& K_inv_diag() const { return K_inv_; }
  Matrix6 K() const { return K_.asDiagonal(); }
  Matrix6 M() const { return M_.asDiagonal(); }
  Matrix6 V() const { return V_.asDiagonal(); }

  /// Mass per unit length rho A.
  double mass_per_length() const { return material_.rho * props_.A; }

  /// This model with the residual bending flexibility of a staggered grid of spacing ds
  /// (MacNeal's correction; docs/dynamics.md "The corrected grid"): each shear compliance gets
  /// ds^2 / (12 E I) of the bending it couples with (shear x with bending about y, shear y with
  /// bending about x), 1 / K'_s = 1 / K_s + ds^2 / (12 K_b), and the shear viscosity likewise
  /// from the bending viscosity. On the staggered grid the bending symbol of a rod with
  /// constrained shear is k^4 (1 + (k ds)^2 / 12); with this compliance the grid's symbol is the
  /// shear-flexible (Timoshenko) rod's to O(ds^4).
  RodModel with_residual_bending_flexibility(double ds) const;

 private:
  double length_;
  Section section_;
  Material material_;
  ModelKind kind_;
  SectionProperties props_;
  Vector6 xi_star_, K_, M_, V_, K_inv_;
  std::vector<RestSpan> spans_;  ///< one span for a uniform rod
};

}  // namespace rodlab::rod
