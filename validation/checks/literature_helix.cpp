// Localised helical buckling (literature_helix.hpp). The Kirchhoff Table 2.1 rod (isotropic:
// B = E I, C = G J) holds the homoclinic buckle of reference/localised_helix.hpp with
// m = M / sqrt(B T) = 1.5 (the envelope's peak a = 0.875, theta = 83 degrees) and kappa L = 8,
// centred on the rod: its base is clamped at the closed form's pose at s = -L/2 and its tip at the
// pose at L/2, so the closed form on [-L/2, L/2] is an exact equilibrium of the finite rod (no
// truncation of the infinite rod's tails, which reach theta = 2.8 degrees at the ends). The rod is
// twisted by tau L = M L / C = 27.5 rad between its clamps, which their poses alone do not record
// (they differ by the same rotation after any whole number of turns): rkmk-rk4's shooting starts
// from the closed form's base wrench with a 1 % error in every component
// (statics::ShootingOptions::base_wrench_guess), where the load continuation from the straight rod
// would follow another branch. Measured against the closed form: the envelope 1 - cos theta at
// every node (over its peak a), the centreline (over L), and the base wrench (moment over M, force
// over T). The errors are fourth order in the nodes but large for the grid: the buckle's place
// along the rod is pinned only by its exponentially small tails (a shift by d moves the ends by
// about d e^(-kappa L / 2)), so the discretisation error shifts it by e^(kappa L / 2) times more
// (measured: 7.0e-5, 2.4e-6 and 9.6e-8 of a on the envelope at N = 201, 401, 801; 2.0e-3 at
// N = 401 with kappa L = 12). N = 801 holds 1e-6.
#include "checks/literature_helix.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rodlab/solvers/statics/shooting.hpp"

#include "reference/localised_helix.hpp"
#include "reference/reference_rods.hpp"

// Data sets and figure specs are written with designated initializers; the fields left out keep
// their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace rodlab::validation {
namespace {

using lie::Vector3;
using lie::Vector6;
using namespace rodlab::solvers::statics;

constexpr double kM = 1.5;       ///< M / sqrt(B T)
constexpr double kDecayL = 8.0;  ///< kappa L
constexpr const char* kSource =
    "closed-form homoclinic envelope (van der Heijden & Thompson 2000; Gazzola et al. 2018)";

struct HelixErrors {
  double envelope = NAN, centreline = NAN, moment = NAN, force = NAN;
  bool converged = false;
  std::string reason;
  std::vector<double> s, u;  ///< the nodes' arclength (centred) and 1 - cos theta
};

HelixErrors solve_helix(const rod::RodModel& model, const reference::LocalisedHelix& helix,
                        double T, double M, int nodes) {
  const double L = model.length();
  const auto [r, s, exact] = solve_localised_helix(model, helix, nodes);
  HelixErrors e;
  e.converged = r.converged;
  e.reason = r.reason;
  if (!r.converged || r.centerline.size() != s.size()) return e;
  e.envelope = e.centreline = 0.0;
  for (int i = 0; i < nodes; ++i) {
    const auto& g = r.centerline[i].pose;
    const double u = 1.0 - (g.rotation() * Vector3::UnitZ()).z();
    e.s.push_back(s[i]);
    e.u.push_back(u);
    e.envelope = std::max(e.envelope, std::abs(u - helix.envelope(s[i])) / helix.amplitude());
    e.centreline =
        std::max(e.centreline, (g.translation() - exact[i].pose.translation()).norm() / L);
  }
  const Vector6 d = r.base_wrench - exact.front().wrench;
  e.moment = d.head<3>().norm() / M;
  e.force = d.tail<3>().norm() / T;
  return e;
}

}  // namespace

LocalisedHelixSolve solve_localised_helix(const rod::RodModel& model,
                                          const reference::LocalisedHelix& helix, int nodes) {
  const double L = model.length();
  LocalisedHelixSolve out;
  out.s.resize(nodes);
  for (int i = 0; i < nodes; ++i) out.s[i] = -0.5 * L + L * i / (nodes - 1);
  out.exact = helix.samples(out.s);
  StaticProblem P(model, out.exact.front().pose);
  P.set_tip_clamped(out.exact.back().pose);
  ShootingOptions options{nodes, 1e-12, 100, {}};
  options.base_wrench_guess = 1.01 * out.exact.front().wrench;
  out.result = solve_shooting(P, RkmkMethod::rk4, options);
  return out;
}

std::vector<Check> localised_helix_checks(const ValidationContext& context) {
  const auto model = reference::table21_model(rod::ModelKind::kirchhoff);
  const double L = model.length(), B = model.K_diag()[0], C = model.K_diag()[2];
  const double a = 2.0 - 0.5 * kM * kM, kappa = kDecayL / L;
  const double T = 2.0 * B * kappa * kappa / a, M = kM * std::sqrt(B * T);
  const reference::LocalisedHelix helix(B, C, T, M, L);
  DataSet data{.name = "literature_localised_helix",
               .description = "localised helical buckling (Kirchhoff, m = 1.5, kappa L = 8): "
                              "1 - cos theta along the rod, closed form and rodlab",
               .columns = {"series", "s_over_L", "one_minus_cos_theta"}};
  for (int i = 0; i <= 400; ++i) {
    const double s = -0.5 * L + L * i / 400.0;
    data.add_row({"closed form", s / L, helix.envelope(s)});
  }
  std::vector<Check> checks;
  const std::vector<int> grids =
      context.full ? std::vector<int>{201, 401, 801} : std::vector<int>{801};
  for (int nodes : grids) {
    const HelixErrors e = solve_helix(model, helix, T, M, nodes);
    const std::string at = "localised helical buckle (Kirchhoff, m = 1.5, kappa L = 8): rkmk-rk4 "
                           "N = " + std::to_string(nodes) + ": ";
    for (std::size_t i = 0; i < e.s.size(); ++i)
      data.add_row({"rkmk-rk4 N = " + std::to_string(nodes), e.s[i] / L, e.u[i]});
    // 1e-6 at N = 801, and the coarser grids' fourth-order share of it
    const double bound = 1e-6 * std::pow(800.0 / (nodes - 1), 4);
    const auto add = [&](const std::string& what, double value) {
      Check c = upper_bound_check(at + what, e.converged ? value : NAN, bound, kSource);
      if (!e.converged) c.detail = e.reason;
      checks.push_back(with_topic(std::move(c), "literature"));
    };
    add("max |(1 - cos theta) - a sech^2(kappa s)| / a over the nodes", e.envelope);
    add("max |p - p_closed form| / L over the nodes", e.centreline);
    add("|base moment - closed form| / M", e.moment);
    add("|base force - T e_z| / T", e.force);
  }
  data.figures.push_back(
      {.name = "literature_localised_helix",
       .kind = "line",
       .x = "s_over_L",
       .y = {"one_minus_cos_theta"},
       .series = "series",
       .title = "Localised helical buckling of a twisted rod under tension",
       .xlabel = "s / L",
       .ylabel = "1 - cos theta",
       .caption = "The envelope 1 - cos theta of the tangent's angle with the axis: the closed "
                  "form a sech^2(kappa s) (m = M / sqrt(B T) = 1.5, a = 0.875, kappa L = 8) and "
                  "rodlab's Kirchhoff rkmk-rk4 between clamps at the closed form's end poses.",
       .style = "lines+markers"});
  context.emit(std::move(data));
  return checks;
}

}  // namespace rodlab::validation
