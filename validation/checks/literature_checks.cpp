// The "literature" family of `rodlab validate` (issue #18): the classic rod benchmarks, each
// against a reference computed independently of rodlab's schemes (closed forms, elliptic
// integrals, an rk8pd shooting of the planar equations) or a published table, cited in
// docs/validation.md "literature":
//   - the self-weight cantilever elastica, q L^3 / EI from 0.5 to 20 (Cosserat and Kirchhoff);
//   - the post-buckled clamped-free elastica, tip angle 10 to 170 degrees;
//   - Euler's critical loads (clamped-free, pinned-pinned, clamped-clamped) with the shear and
//     extension correction of a Cosserat rod, and Greenhill's twisted clamped rod, measured as
//     the load where the straight rod's stiffness vanishes (checks/bifurcation_load.hpp), and
//     Greenhill's pinned shaft as the moment where a tilted rod's helix closes;
//   - Bathe and Bolourchi's 45-degree bend under an out-of-plane tip force;
//   - the natural frequencies from free vibration (literature_frequencies.cpp);
//   - the localised helical buckle of a twisted rod under tension (literature_helix.cpp).
// --quick runs a subset of the loads of each case.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "rodlab/solvers/statics/solve_static.hpp"

#include "checks/bifurcation_load.hpp"
#include "checks/check.hpp"
#include "checks/literature_frequencies.hpp"
#include "checks/literature_helix.hpp"
#include "reference/bathe_bolourchi.hpp"
#include "reference/buckling.hpp"
#include "reference/planar_rod.hpp"
#include "reference/reference_rods.hpp"

// Data sets and figure specs are written with designated initializers; the fields left out keep
// their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace rodlab::validation {
namespace {

using namespace rodlab::solvers::statics;
using lie::SE3;
using lie::SO3;
using lie::Vector3;
using lie::Vector6;
using reference::table21_model;
constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

std::string model_name(rod::ModelKind kind) {
  return kind == rod::ModelKind::cosserat ? "cosserat" : "kirchhoff";
}

std::string number(double v, int digits = 3) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

/// The planar reference's rod for a rodlab model bending about its section's y axis.
reference::PlanarRod planar(const rod::RodModel& m) {
  if (m.is_kirchhoff()) return {m.length(), m.K_diag()[1], 0.0, 0.0};
  return {m.length(), m.K_diag()[1], m.K_diag()[3], m.K_diag()[5]};
}

result::StaticResult solve(const StaticProblem& P, const std::string& scheme, int nodes) {
  return solve_static(P, {scheme, nodes, 1e-12, 100});
}

Vector3 tip(const result::StaticResult& r) { return r.centerline.back().pose.translation(); }

/// The schemes every planar case runs: the fourth-order shooting and the spectral collocation.
struct SchemeAtN {
  const char* name;
  int nodes;
};
constexpr SchemeAtN kPlanarSchemes[] = {{"rkmk-rk4", 101}, {"chebyshev", 32}};

struct Literature {
  const ValidationContext& context;
  std::vector<Check> checks;
};

/// The headline of a benchmark for the report's summary: the largest error of the checks from
/// `first` on (a relative check's relative error, an upper bound's measured value), against
/// the bound they share.
Check worst_of(const Literature& f, std::size_t first, std::string name, double bound,
               std::string reference) {
  double worst = 0.0;
  bool all = true;
  for (std::size_t i = first; i < f.checks.size(); ++i) {
    const Check& c = f.checks[i];
    const double value = c.tolerance > 0.0 ? c.relative_error() : c.measured;
    worst = std::isfinite(value) ? std::max(worst, value) : NAN;
    all = all && c.passed;
  }
  Check c = with_topic(upper_bound_check(std::move(name), worst, bound, std::move(reference)),
                       "literature");
  c.passed = c.passed && all;
  return c;
}

// --- the self-weight cantilever elastica ----------------------------------------------------

/// The Table 2.1 rod along +z under its weight along -x, scaled to q L^3 / EI = w.
StaticProblem self_weight(rod::ModelKind kind, double w) {
  StaticProblem P(table21_model(kind), SE3::identity());
  const double q = w * P.model().K_diag()[1] / std::pow(P.length(), 3);
  P.set_gravity(loads::Gravity(P.model(), Vector3(-q / P.model().mass_per_length(), 0, 0)));
  return P;
}

void self_weight_elastica(Literature& f) {
  DataSet data{.name = "literature_self_weight",
               .description = "self-weight cantilever elastica: tip deflection / L against "
                              "q L^3 / EI, rodlab against the rk8pd planar reference",
               .columns = {"series", "load", "deflection", "drop", "tip_error"}};
  const std::vector<double> loads = f.context.full ? std::vector<double>{0.5, 1, 2, 5, 10, 20}
                                                   : std::vector<double>{1, 10};
  const std::size_t first = f.checks.size();
  for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
    const std::string model = model_name(kind);
    for (double w : loads) {
      const StaticProblem P = self_weight(kind, w);
      const double L = P.length();
      const auto ref = reference::planar_cantilever(
          planar(P.model()), {-w * P.model().K_diag()[1] / (L * L * L), 0, 0, 0}, 0.0, -0.01);
      data.add_row({"reference (" + model + ")", w, -ref.x / L, 1.0 - ref.z / L, 0.0});
      for (const auto& [scheme, nodes] : kPlanarSchemes) {
        const auto r = solve(P, scheme, nodes);
        const Vector3 p = tip(r);
        const double error = std::hypot(p.x() - ref.x, p.z() - ref.z) / L;
        data.add_row({std::string(scheme) + " (" + model + ")", w, -p.x() / L, 1.0 - p.z() / L,
                      error});
        Check c = upper_bound_check("self-weight elastica (" + model + "), q L^3/EI = " +
                                        number(w) + ": " + scheme + " N = " +
                                        std::to_string(nodes) + " |tip - reference| / L",
                                    r.converged ? error : NAN, 1e-7,
                                    "rk8pd shooting of the planar equations at 1e-14");
        f.checks.push_back(c);
      }
    }
  }
  data.figures.push_back(
      {.name = "literature_self_weight",
       .kind = "semilogx",
       .x = "load",
       .y = {"deflection", "drop"},
       .series = "series",
       .title = "Self-weight cantilever elastica",
       .xlabel = "q L^3 / EI",
       .ylabel = "tip deflection / L, drop / L",
       .caption = "Tip deflection across (-x / L) and drop along the rod (1 - z / L) of the "
                  "Table 2.1 rod under a uniform weight q, rodlab's rkmk-rk4 (N = 101) and "
                  "chebyshev (N = 32) against the rk8pd shooting of the planar equations (the "
                  "inextensible elastica for Kirchhoff rods, with shear and extension for "
                  "Cosserat rods).",
       .style = "lines+markers"});
  f.context.emit(std::move(data));
  f.checks.push_back(worst_of(f, first,
                              "self-weight cantilever elastica: worst |tip - reference| / L (every "
                              "load, Cosserat and Kirchhoff, rkmk-rk4 N = 101, chebyshev N = 32)",
                              1e-7, "rk8pd shooting of the planar equations"));
}

// --- the post-buckled clamped-free elastica -------------------------------------------------

/// The Kirchhoff Table 2.1 rod with its tip held at the closed form's buckled tip (position and
/// angle alpha): under displacement control the branch is selected by the target itself, and
/// the reaction is what the closed form says the dead load is (a load-controlled solve from the
/// straight rod would need an imperfection, and Newton may still settle on the unstable
/// near-straight state past Euler's load).
StaticProblem post_buckled(double alpha, const reference::PostBuckledElastica& e) {
  StaticProblem problem(table21_model(rod::ModelKind::kirchhoff), SE3::identity());
  const double L = problem.length();
  problem.set_tip_clamped(SE3(SO3::exp(Vector3(0, alpha, 0)), Vector3(e.x * L, 0, e.z * L)));
  return problem;
}

void post_buckled_elastica(Literature& f) {
  DataSet data{.name = "literature_post_buckled",
               .description = "post-buckled clamped-free elastica (Kirchhoff): P L^2 / EI against "
                              "the tip's deflection / L, closed form and rodlab",
               .columns = {"series", "deflection", "drop", "load"}};
  for (int a = 2; a <= 178; a += 2) {
    const auto e = reference::post_buckled_elastica(a * kDeg);
    data.add_row({"closed form", e.x, 1.0 - e.z, e.load});
  }
  const std::vector<double> angles = f.context.full
                                         ? std::vector<double>{10, 30, 60, 90, 120, 150, 170}
                                         : std::vector<double>{30, 170};
  const double L = reference::Table21::L, EI = table21_model().K_diag()[1];
  // chebyshev at N = 32 and 48 finds the 170-degree target's discrete equations' spurious root
  // (and says so: "not resolved"); N = 64 resolves every angle. kinsol reaches the tips beyond
  // 150 degrees since the Kirchhoff rod's clamped-tip path turns before it moves (session 18).
  constexpr SchemeAtN kSchemes[] = {{"rkmk-rk4", 101}, {"chebyshev", 64}, {"kinsol", 101}};
  const std::size_t first = f.checks.size();
  for (double angle : angles) {
    const auto e = reference::post_buckled_elastica(angle * kDeg);
    const double P = e.load * EI / (L * L);
    for (const auto& [scheme, nodes] : kSchemes) {
      const auto r = solve(post_buckled(angle * kDeg, e), scheme, nodes);
      // The base's internal wrench [moment; force] carries the tip's reaction (no other load).
      const Vector3 force = r.base_wrench.tail<3>();
      const double tip_moment = EI * r.centerline.back().twist[1];
      data.add_row({std::string(scheme) + " N = " + std::to_string(nodes), e.x, 1.0 - e.z,
                    -force.z() * L * L / EI});
      const std::string at = "post-buckled elastica, tip angle " + number(angle) + " deg: " +
                             scheme + " N = " + std::to_string(nodes);
      const std::string source = "elliptic integrals (Timoshenko & Gere 1961, 2.7)";
      Check load = relative_check(at + ": axial reaction P L^2 / EI", -force.z() * L * L / EI,
                                  e.load, 1e-6, source);
      load.passed = load.passed && r.converged;
      f.checks.push_back(load);
      f.checks.push_back(upper_bound_check(
          at + ": lateral reaction and tip moment, max(|F_x| / P, |M(L)| / (P L))",
          r.converged ? std::max(std::abs(force.x()) / P, std::abs(tip_moment) / (P * L)) : NAN,
          1e-6, source + ": a dead axial load, no moment at the tip"));
    }
  }
  data.figures.push_back(
      {.name = "literature_post_buckled",
       .kind = "line",
       .x = "load",
       .y = {"deflection", "drop"},
       .series = "series",
       .title = "Post-buckled clamped-free elastica (Kirchhoff)",
       .xlabel = "P L^2 / EI",
       .ylabel = "tip deflection / L, drop / L",
       .caption = "Tip deflection across (x / L) and drop (1 - z / L) of the buckled column "
                  "against the compressive tip load: the elliptic-integral closed form (tip "
                  "angle 2 to 178 degrees), and the axial reaction rodlab's rkmk-rk4 (N = 101), "
                  "chebyshev (N = 64) and kinsol (N = 101) find with the tip held at the closed "
                  "form's tip. The branch starts at Euler's load pi^2 / 4.",
       .style = "lines+markers"});
  f.context.emit(std::move(data));
  f.checks.push_back(worst_of(f, first,
                              "post-buckled elastica: worst reaction error (axial, relative; "
                              "lateral and tip moment, over P) over every tip angle and scheme",
                              1e-6, "elliptic integrals (Timoshenko & Gere 1961, 2.7)"));
}

// --- critical loads -----------------------------------------------------------------------

/// One bifurcation case: its name, the closed form, and the measurement.
struct CriticalCase {
  std::string name;  ///< with the scheme that measures it
  double closed_form = 0.0;
  std::function<std::optional<double>(double lambda, double h)> deflection;
};

/// The tip of the rod clamped at `base`, free, under the world tip wrench [moment; force]
/// (rkmk-rk4, N = 101); nullopt when the solve fails.
std::optional<Vector3> free_tip(const rod::RodModel& model, const SE3& base,
                                const Vector6& wrench) {
  StaticProblem P(model, base);
  P.set_tip_wrench({wrench, loads::WrenchFrame::world});
  const auto r = solve(P, "rkmk-rk4", 101);
  if (!r.converged) return std::nullopt;
  return tip(r);
}

/// The response of a clamped-free rod (the model's length) to a compressive tip load lambda
/// and a lateral tip force h: its tip's x.
std::optional<double> column_tip(const rod::RodModel& model, double lambda, double h) {
  const auto p = free_tip(model, SE3::identity(), (Vector6() << 0, 0, 0, h, 0, -lambda).finished());
  return p ? std::optional<double>(p->x()) : std::nullopt;
}

/// The response of a cantilever strip (reference/buckling.hpp) to a tip force P through the
/// centroid along its stiff plane (world y, bending about the section's x axis) and a lateral
/// tip force h (world x): its tip's x.
std::optional<double> strip_tip(const rod::RodModel& model, double P, double h) {
  const auto p = free_tip(model, SE3::identity(), (Vector6() << 0, 0, 0, h, P, 0).finished());
  return p ? std::optional<double>(p->x()) : std::nullopt;
}

/// The response of a rod clamped at both ends, its tip's target `target`, to a uniform lateral
/// load h: the distance of its middle node from the axis (chebyshev at odd N has a node at
/// L / 2; it resolves these cases to 3e-8, where rkmk-rk4 at N = 101 still errs by 7e-7).
std::optional<double> clamped_middle(const rod::RodModel& model, const SE3& target, double h) {
  StaticProblem P(model, SE3::identity());
  P.set_tip_clamped(target);
  P.set_distributed({(Vector6() << 0, 0, 0, h, 0, 0).finished(), loads::WrenchFrame::world});
  const auto r = solve(P, "chebyshev", 33);
  if (!r.converged) return std::nullopt;
  const Vector3 mid = r.centerline[16].pose.translation();
  return std::hypot(mid.x(), mid.y());
}

std::vector<CriticalCase> critical_cases(bool full) {
  std::vector<CriticalCase> cases;
  for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
    if (!full && kind == rod::ModelKind::kirchhoff) continue;
    const rod::RodModel m = table21_model(kind);
    const double L = m.length(), EI = m.K_diag()[1];
    const double GA = m.is_kirchhoff() ? 0.0 : m.K_diag()[3];
    const double EA = m.is_kirchhoff() ? 0.0 : m.K_diag()[5];
    const std::string model = " (" + model_name(kind) + ")";
    cases.push_back({"Euler clamped-free" + model + ", rkmk-rk4 N = 101",
                     reference::cosserat_critical_load(kPi * kPi * EI / (4 * L * L), GA, EA),
                     [m](double lambda, double h) { return column_tip(m, lambda, h); }});
    if (!full) continue;
    // Pinned-pinned through its symmetric half: clamped at the middle, free at the end.
    const rod::RodModel half(0.5 * L, m.section(), m.material(), kind);
    cases.push_back({"Euler pinned-pinned, as its clamped-free half" + model + ", rkmk-rk4 N = 101",
                     reference::cosserat_critical_load(kPi * kPi * EI / (L * L), GA, EA),
                     [half](double lambda, double h) { return column_tip(half, lambda, h); }});
    if (kind == rod::ModelKind::cosserat)  // a Kirchhoff rod cannot be compressed between clamps
      cases.push_back({"Euler clamped-clamped" + model + ", chebyshev N = 33",
                       reference::cosserat_critical_load(4 * kPi * kPi * EI / (L * L), GA, EA),
                       [m, L, EA](double lambda, double h) {
                         const SE3 target = SE3::translation(Vector3(0, 0, L * (1 - lambda / EA)));
                         return clamped_middle(m, target, h);
                       }});
    // Greenhill's shaft is free to shorten between its clamps; a Kirchhoff rod held at its full
    // length cannot deflect at all (any bend shortens it), so only the Cosserat rod, whose axial
    // force stays zero to first order, is held so.
    if (kind == rod::ModelKind::kirchhoff) continue;
    // Greenhill's rod: G = 10 E, so that the critical twist (8.9 E I / G J = 0.45 rad) stays
    // below pi: a clamped tip's target is a rotation, which cannot hold more than half a turn.
    const rod::Material stiff{m.material().E, 10.0 * m.material().E, m.material().rho, 0.0};
    const rod::RodModel t(L, m.section(), stiff, kind);
    const double g = t.is_kirchhoff() ? 0.0 : EI / (t.K_diag()[3] * L * L);
    cases.push_back({"Greenhill clamped twisted rod (G = 10 E), moment" + model +
                         ", chebyshev N = 33",
                     reference::greenhill_clamped_moment(g) * EI / L,
                     [t, L, GJ = t.K_diag()[2]](double M, double h) {
                       const SO3 twist = SO3::exp(Vector3(0, 0, M * L / GJ));
                       return clamped_middle(t, SE3(twist, Vector3(0, 0, L)), h);
                     }});
  }
  if (full)
    for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
      // A strip 1 m long, 0.1 mm by 1 m: stiff about its section's x axis, so the in-plane
      // bending that the classic constant neglects shifts it by O(EI_y / EI_x) = 1e-8
      // (measured: 2.6e-8; 1.5e-6 at h / b = 1000).
      const rod::RodModel strip(1.0, rod::Rectangle{1e-4, 1.0},
                                rod::Material{1e6, 1e6 / 2.6, 1000.0, 0.0}, kind);
      const double EIy = strip.K_diag()[1], GJ = strip.K_diag()[2];
      cases.push_back({"lateral-torsional buckling, strip h / b = 1e4, tip force (" +
                           model_name(kind) + "), rkmk-rk4 N = 101",
                       reference::lateral_torsional_constant() * std::sqrt(EIy * GJ),
                       [strip](double P, double h) { return strip_tip(strip, P, h); }});
    }
  return cases;
}

void critical_loads(Literature& f) {
  DataSet data{.name = "literature_critical_loads",
               .description = "the straight rod's stiffness (imperfection / deflection, scaled "
                              "by its first value) against the load over the closed-form "
                              "critical load: its zero is the measured critical load",
               .columns = {"case", "load_ratio", "stiffness"}};
  for (const auto& c : critical_cases(f.context.full)) {
    const auto measured =
        bifurcation_load(c.deflection, c.closed_form, 1e-5 * reference::Table21::L);
    for (const auto& p : measured.points)
      data.add_row({c.name, p.load / c.closed_form,
                    p.stiffness / measured.points.front().stiffness});
    Check check = relative_check(c.name + ": critical load", measured.load,
                                 c.closed_form, 1e-6,
                                 "closed form with the Cosserat correction (docs/validation.md)");
    check.passed = check.passed && measured.ok;
    if (!measured.ok) check.detail = "a solve did not converge or the rod buckled early";
    f.checks.push_back(with_topic(std::move(check), "literature"));
  }
  data.figures.push_back(
      {.name = "literature_critical_loads",
       .kind = "line",
       .x = "load_ratio",
       .y = {"stiffness"},
       .series = "case",
       .title = "Critical loads: the straight rod's stiffness vanishes",
       .xlabel = "load / closed-form critical load",
       .ylabel = "stiffness / stiffness at 0.7",
       .caption = "Imperfection over deflection of the straight rod (rkmk-rk4 at N = 101 with a "
                  "free tip, chebyshev at N = 33 between clamps) as the load approaches the "
                  "critical load from below; the zero of a quadratic through the last three "
                  "points is the measured critical load. Euler's loads carry the Haringx shear "
                  "and the extension correction of a Cosserat rod, Greenhill's moment the shear "
                  "correction; the strip's constant neglects its in-plane bending (1e-8).",
       .style = "lines+markers"});
  f.context.emit(std::move(data));
}

// --- Greenhill's pinned shaft ---------------------------------------------------------------

/// The tip of a rod whose clamped base is tilted by theta0 about world y and whose free tip
/// carries the dead moment M along world z (reference/buckling.hpp, Greenhill's pinned shaft).
std::optional<Vector3> tilted_rod_tip(const rod::RodModel& model, double theta0, double M) {
  return free_tip(model, SE3(SO3::exp(Vector3(0, theta0, 0)), Vector3::Zero()),
                  (Vector6() << 0, 0, M, 0, 0, 0).finished());
}

/// Greenhill's pinned shaft: the moment M at which the tilted rod's tip returns to the axis
/// through its base (its x crosses zero between M L / EI = 1.5 pi and 2.5 pi), by the secant
/// method to 1e-12 relative; nullopt when a solve fails.
std::optional<double> closing_moment(const rod::RodModel& model, double theta0, double guess) {
  double a = 0.95 * guess, b = 1.05 * guess;
  auto fa = tilted_rod_tip(model, theta0, a), fb = tilted_rod_tip(model, theta0, b);
  for (int it = 0; it < 30 && fa && fb; ++it) {
    if (std::abs(b - a) <= 1e-12 * guess) return b;
    const double c = b - fb->x() * (b - a) / (fb->x() - fa->x());
    a = b, fa = fb;
    b = c, fb = tilted_rod_tip(model, theta0, c);
  }
  return std::nullopt;
}

void greenhill_pinned(Literature& f) {
  constexpr double kTilt = 0.2;  // rad: the closing moment does not depend on it (exact helix)
  DataSet data{.name = "literature_greenhill_pinned",
               .description = "Greenhill's pinned shaft: the tip offset of a rod with its base "
                              "tilted by 0.2 rad under a dead axial tip moment, against M L / "
                              "(2 pi EI); closed form and rodlab",
               .columns = {"series", "moment_ratio", "x_over_L", "y_over_L"}};
  for (auto kind : {rod::ModelKind::cosserat, rod::ModelKind::kirchhoff}) {
    if (!f.context.full && kind == rod::ModelKind::kirchhoff) continue;
    const rod::RodModel m = table21_model(kind);
    const double L = m.length(), EI = m.K_diag()[1], closed = 2.0 * kPi * EI / L;
    if (kind == rod::ModelKind::cosserat) {
      for (int i = 1; i <= 30; ++i) {
        const double ratio = i / 20.0, k = ratio * closed / EI;  // the helix of rate k = M / EI
        data.add_row({"closed form", ratio, std::sin(kTilt) * std::sin(k * L) / (k * L),
                      std::sin(kTilt) * (1.0 - std::cos(k * L)) / (k * L)});
        if (i % 3 != 0) continue;
        const auto p = tilted_rod_tip(m, kTilt, ratio * closed);
        if (p) data.add_row({"rkmk-rk4 N = 101", ratio, p->x() / L, p->y() / L});
      }
    }
    const auto M = closing_moment(m, kTilt, closed);
    const std::string name = "Greenhill pinned shaft (" + model_name(kind) +
                             "), dead axial moment, rkmk-rk4 N = 101";
    Check check = relative_check(name + ": critical moment (the tilted rod's helix closes)",
                                 M ? *M : NAN, closed, 1e-6,
                                 "M L / EI = 2 pi (Greenhill 1883; derived in docs/validation.md)");
    check.passed = check.passed && M.has_value();
    f.checks.push_back(with_topic(std::move(check), "literature"));
    const auto p = M ? tilted_rod_tip(m, kTilt, *M) : std::nullopt;
    f.checks.push_back(upper_bound_check(
        name + ": |tip offset from the axis| / L at that moment",
        p ? std::hypot(p->x(), p->y()) / L : NAN, 1e-8,
        "the pinned mode's ends lie on one axis"));
  }
  data.figures.push_back(
      {.name = "literature_greenhill_pinned",
       .kind = "line",
       .x = "moment_ratio",
       .y = {"x_over_L", "y_over_L"},
       .series = "series",
       .title = "Greenhill's pinned shaft: the helix closes at M L / EI = 2 pi",
       .xlabel = "M L / (2 pi EI)",
       .ylabel = "tip offset x / L, y / L",
       .caption = "The tip of the Table 2.1 rod (Cosserat) whose base is tilted by 0.2 rad, under "
                  "a dead tip moment along the axis: the closed form sin(0.2) (sin kL, 1 - cos "
                  "kL) / (kL), k = M / EI (the tangent precesses about the axis at k), and "
                  "rodlab's rkmk-rk4 at N = 101. Both components vanish at M L / EI = 2 pi, the "
                  "critical moment of the shaft pinned at both ends.",
       .style = "lines+markers"});
  f.context.emit(std::move(data));
}

// --- Bathe and Bolourchi's 45-degree bend ----------------------------------------------------

namespace bb = reference::bathe_bolourchi;

/// The bend (reference/bathe_bolourchi.hpp) as a pre-curved Cosserat rod: its body z along
/// world +x, its body x along world +y (the side it curves to, rest curvature 1 / R about body
/// y), its body y along world +z; the tip force along world +z. G is scaled so that G Jt is the
/// published torsional stiffness; the shear stiffness G A rises with it by 19 %, which changes
/// nothing visible in a rod this slender (E I / (G A L^2) = 3e-5).
StaticProblem bend(double force) {
  const rod::Rectangle square{bb::kSide, bb::kSide};
  const double G = bb::kGJ / rod::properties(square).Jt;
  const rod::RodModel model(bb::kLength, square, rod::Material{bb::kE, G, 1.0, 0.0},
                            rod::ModelKind::cosserat,
                            (Vector6() << 0, 1.0 / bb::kRadius, 0, 0, 0, 1).finished());
  lie::Matrix3 R;
  R.col(0) = Vector3::UnitY();
  R.col(1) = Vector3::UnitZ();
  R.col(2) = Vector3::UnitX();
  StaticProblem P(model, SE3(SO3::from_matrix(R), Vector3::Zero()));
  P.set_tip_wrench({(Vector6() << 0, 0, 0, 0, 0, force).finished(), loads::WrenchFrame::world});
  return P;
}

void forty_five_degree_bend(Literature& f) {
  DataSet data{.name = "literature_45_degree_bend",
               .description = "45-degree bend (Bathe & Bolourchi 1979): centreline at each tip "
                              "force, x, y, z",
               .columns = {"case", "x", "y", "z"}};
  // The unloaded bend, and the published tips (a line through the three loads).
  for (int i = 0; i <= 20; ++i) {
    const double a = i * std::numbers::pi / 80.0;
    data.add_row({"unloaded", bb::kRadius * std::sin(a), bb::kRadius * (1 - std::cos(a)), 0.0});
  }
  for (const auto& row : bb::kSimoVuQuoc)
    data.add_row({"Simo & Vu-Quoc tips", row.x, row.y, row.z});
  for (const auto& row : bb::kSimoVuQuoc) {
    if (!f.context.full && row.force != 600.0) continue;
    const StaticProblem P = bend(row.force);
    Vector3 tips[2];
    int k = 0;
    for (const auto& [scheme, nodes] : {SchemeAtN{"rkmk-rk4", 101}, SchemeAtN{"chebyshev", 40}}) {
      const auto r = solve(P, scheme, nodes);
      tips[k++] = r.converged ? tip(r) : Vector3::Constant(NAN);
      if (std::string(scheme) != "rkmk-rk4") continue;
      for (std::size_t i = 0; i < r.centerline.size(); i += 5) {
        const Vector3 p = r.centerline[i].pose.translation();
        data.add_row({"P = " + number(row.force), p.x(), p.y(), p.z()});
      }
    }
    const std::string at = "45-degree bend, P = " + number(row.force) + ": ";
    f.checks.push_back(upper_bound_check(
        at + "|rkmk-rk4 N = 101 - chebyshev N = 40| / R", (tips[0] - tips[1]).norm() / bb::kRadius,
        1e-6, "two schemes of different kind agree (the continuum solution)"));
    const auto against = [&](const bb::Published& p, const std::string& who) {
      const Vector3 published(p.x, p.y, p.z);
      const double displacement = (published - bb::unloaded_tip()).norm();
      f.checks.push_back(with_topic(
          upper_bound_check(at + "|tip - " + who + "| / |their tip displacement|",
                            (tips[1] - published).norm() / displacement, bb::kPublishedTolerance,
                            who + ", finite elements (reference/bathe_bolourchi.hpp)"),
          "literature"));
    };
    against(row, "Simo & Vu-Quoc (1986)");
    if (row.force == bb::kBatheBolourchi.force)
      against(bb::kBatheBolourchi, "Bathe & Bolourchi (1979)");
  }
  data.figures.push_back(
      {.name = "literature_45_degree_bend",
       .kind = "shape",
       .x = "x",
       .y = {"y", "z"},
       .series = "case",
       .title = "Bathe and Bolourchi's 45-degree bend",
       .xlabel = "x",
       .ylabel = "y, z",
       .caption = "Centrelines of the 45-degree bend (radius 100, unit square section, E = 1e7, "
                  "G J = 8.333e5 as published) unloaded and under an out-of-plane tip force "
                  "P = 300, 450 and 600 (rkmk-rk4 N = 101), and the line through Simo & "
                  "Vu-Quoc's tips at the three loads.",
       .style = "lines"});
  f.context.emit(std::move(data));
}

/// The natural frequencies from free vibration (literature_frequencies.cpp).
void frequencies(Literature& f) {
  const std::size_t first = f.checks.size();
  for (auto& c : free_vibration_frequencies(f.context)) f.checks.push_back(std::move(c));
  f.checks.push_back(worst_of(f, first,
                              "natural frequencies from free vibration: worst relative error "
                              "(bending 1-3, torsion, axial; every scheme and N >= 40)",
                              1e-3, "Timoshenko beam (Huang 1961) and the wave equations"));
}

/// The localised helical buckle (literature_helix.cpp); the headline is the finest grid's four
/// checks, the last ones.
void localised_helix(Literature& f) {
  auto checks = localised_helix_checks(f.context);
  const std::size_t first = f.checks.size() + checks.size() - 4;
  for (auto& c : checks) f.checks.push_back(std::move(c));
  f.checks.push_back(worst_of(f, first,
                              "localised helical buckle: worst error (envelope / a, centreline / "
                              "L, base moment / M, base force / T) at rkmk-rk4 N = 801",
                              1e-6, "closed-form homoclinic (van der Heijden & Thompson 2000)"));
}

constexpr void (*kCases[])(Literature&) = {&self_weight_elastica, &post_buckled_elastica,
                                           &critical_loads, &greenhill_pinned,
                                           &forty_five_degree_bend, &frequencies,
                                           &localised_helix};

}  // namespace

std::vector<Check> literature_checks(const ValidationContext& context) {
  Literature family{context};
  for (const auto run : kCases) run(family);
  return std::move(family.checks);
}

}  // namespace rodlab::validation
