#include "rodlab/rod/rod_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rodlab/check.hpp"

namespace rodlab::rod {

RodModel::RodModel(double length, const Section& section, const Material& material, ModelKind kind,
                   const Vector6& reference_twist)
    : length_(length),
      section_(section),
      material_(material),
      kind_(kind),
      props_(rod::properties(section)),
      xi_star_(reference_twist) {
  RODLAB_THROW_UNLESS(length > 0.0 && std::isfinite(length), "rod length must be > 0 (got {:g})",
                      length);
  RODLAB_THROW_UNLESS(material.E > 0.0 && std::isfinite(material.E), "E must be > 0 (got {:g})",
                      material.E);
  RODLAB_THROW_UNLESS(material.G > 0.0 && std::isfinite(material.G), "G must be > 0 (got {:g})",
                      material.G);
  RODLAB_THROW_UNLESS(material.rho > 0.0 && std::isfinite(material.rho),
                      "rho must be > 0 (got {:g})", material.rho);
  RODLAB_THROW_UNLESS(material.viscosity >= 0.0 && std::isfinite(material.viscosity),
                      "viscosity must be >= 0 (got {:g})", material.viscosity);
  RODLAB_THROW_UNLESS(reference_twist.allFinite() && reference_twist.tail<3>().norm() > 0.0,
                      "reference twist needs a non-zero linear part nu* (got {:g})",
                      reference_twist.tail<3>().norm());

  const auto& p = props_;
  const double E = material.E, G = material.G, rho = material.rho, alpha = material.viscosity;
  K_ << E * p.Ix, E * p.Iy, G * p.Jt, G * p.A, G * p.A, E * p.A;                       // (2.28)
  M_ << rho * p.Ix, rho * p.Iy, rho * p.J, rho * p.A, rho * p.A, rho * p.A;             // (3.5)
  // (3.10): Kelvin-Voigt with E -> 3 alpha (Trouton) and G -> alpha; the torsion entry uses the
  // torsion constant like K does (identical to the thesis's J for circles and tubes).
  V_ << 3 * alpha * p.Ix, 3 * alpha * p.Iy, alpha * p.Jt, alpha * p.A, alpha * p.A, 3 * alpha * p.A;
  K_inv_ = K_.cwiseInverse();
  spans_ = {RestSpan{0.0, xi_star_}};
}

RodModel::RodModel(double length, const Section& section, const Material& material, ModelKind kind,
                   std::vector<RestSpan> spans)
    : RodModel(length, section, material, kind,
               spans.empty() ? straight_twist() : spans.front().xi_star) {
  RODLAB_THROW_UNLESS(!spans.empty() && spans.front().begin == 0.0,
                      "rest-strain spans must start at s = 0");
  for (std::size_t k = 0; k < spans.size(); ++k) {
    const RestSpan& span = spans[k];
    RODLAB_THROW_UNLESS(span.xi_star.allFinite() && span.xi_star.tail<3>().norm() > 0.0,
                        "rest-strain span {} needs a non-zero linear part nu*", k + 1);
    RODLAB_THROW_UNLESS(span.begin < length && (k == 0 || span.begin > spans[k - 1].begin),
                        "rest-strain span {} begins at s = {:g}, not after the previous span "
                        "and before the rod's end",
                        k + 1, span.begin);
  }
  spans_ = std::move(spans);
}

std::vector<double> RodModel::rest_breaks() const {
  std::vector<double> breaks;
  for (std::size_t k = 1; k < spans_.size(); ++k) breaks.push_back(spans_[k].begin);
  return breaks;
}

lie::SO3 RodModel::rest_rotation(double s) const {
  if (spans_.size() == 1) return lie::SO3::exp(s * lie::Vector3(xi_star_.head<3>()));
  lie::SO3 R;
  for (std::size_t k = 0; k < spans_.size() && spans_[k].begin < s; ++k) {
    const double end = k + 1 < spans_.size() ? std::min(s, spans_[k + 1].begin) : s;
    R = R * lie::SO3::exp((end - spans_[k].begin) * lie::Vector3(spans_[k].xi_star.head<3>()));
  }
  return R;
}

void RodModel::require_spans_on_grid(int nodes, std::string_view who) const {
  if (spans_.size() == 1) return;
  const double ds = length_ / (nodes - 1);
  for (double b : rest_breaks()) {
    const double k = b / ds;
    RODLAB_THROW_UNLESS(std::abs(k - std::round(k)) <= 1e-9 * std::max(1.0, k),
                        "rod.rest_strain.spans: the span that begins at s = {:g} m does not begin "
                        "on a node of {}'s {} nodes (spacing {:g} m); choose N so that every span "
                        "begins on a node",
                        b, who, nodes, ds);
  }
}

lie::SE3 RodModel::rest_pose(double s) const {
  if (spans_.size() == 1) return lie::SE3::exp(s * xi_star_);
  lie::SE3 g = lie::SE3::identity();
  for (std::size_t k = 0; k < spans_.size() && spans_[k].begin < s; ++k) {
    const double end = k + 1 < spans_.size() ? std::min(s, spans_[k + 1].begin) : s;
    g = g * lie::SE3::exp((end - spans_[k].begin) * spans_[k].xi_star);
  }
  return g;
}

RodModel RodModel::with_residual_bending_flexibility(double ds) const {
  RODLAB_THROW_UNLESS(ds > 0.0 && std::isfinite(ds), "grid spacing must be > 0 (got {:g})", ds);
  RodModel m = *this;
  const double c = ds * ds / 12.0;
  // in series: the shear's compliance plus the residual bending flexibility c / K_b
  auto series = [c](double shear, double bending) {
    return shear > 0.0 && bending > 0.0 ? 1.0 / (1.0 / shear + c / bending) : shear;
  };
  m.K_[3] = series(K_[3], K_[1]);  // shear x, bending about y
  m.K_[4] = series(K_[4], K_[0]);  // shear y, bending about x
  m.V_[3] = series(V_[3], V_[1]);
  m.V_[4] = series(V_[4], V_[0]);
  m.K_inv_ = m.K_.cwiseInverse();
  return m;
}

}  // namespace rodlab::rod
