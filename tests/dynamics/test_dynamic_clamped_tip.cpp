#define BOOST_TEST_MODULE dynamics_clamped_tip
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "../cli/cli_support.hpp"
#include "dynamics_support.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

// A rod clamped at both ends (tip: clamped) in every dynamics scheme (docs/dynamics.md "Clamped
// tips"). Rod: thesis Table 2.1 (dynamics_support.hpp), L = 0.1 m, D = 1 cm (L/D = 10),
// EI = 4.909e-4 N m^2, GA = 25.9 N, rho A = 0.07854 kg/m, clamped at both ends along +z. The
// clamp holds the rest shape's tip pose unless a test says otherwise. Positions are read at the
// middle node (s = L/2; the tip does not move).

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::RestState;
using solvers::dynamics::Stepper;

constexpr double kL = 0.1, kD = 0.01, kE = 1.0e6, kG = 0.33e6, kRho = 1000.0;
constexpr double kA = std::numbers::pi * kD * kD / 4.0;
constexpr double kI = std::numbers::pi * kD * kD * kD * kD / 64.0;
constexpr double kEI = kE * kI;

/// The clamped-clamped rod: extra YAML under `loads:`, clamp at `clamp_position` with identity
/// rotation, viscosity alpha [Pa s].
scene::Scene clamped_scene(const std::string& loads, double alpha = 0.0,
                           const std::string& clamp_position = "[0, 0, 0.1]") {
  const std::string yaml =
      "schema: rodlab.scene/1\nname: clamped-test\nrod:\n  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: " + std::to_string(alpha) + "}\n"
      "tip:\n  clamped: {position: " + clamp_position + ", rotation: identity}\nloads: " + loads +
      "\n";
  return io::load_scene_from_string(yaml, "clamped-test.yaml");
}

/// Small free vibration: held by a uniform transverse force q (world x, q L^3 / EI = 0.1, mid
/// deflection q L^4 / (384 EI) = 2.6e-5 m) until t = 1e-9 s, released at rest from the clamped
/// statics (rkmk-rk4, solve_dynamic's `initial: static`); no gravity.
scene::Scene released_clamped(double alpha = 0.0) {
  const double q = 0.1 * kEI / (kL * kL * kL);
  return clamped_scene("{distributed: {force: {steps: [[0, [" + std::to_string(q) +
                           ", 0, 0]], [1.0e-9, [0, 0, 0]]]}, frame: world}}",
                       alpha);
}

/// Viscous rod released straight under gravity (settles to the clamped statics).
scene::Scene sagging_clamped() { return clamped_scene("{gravity: [-9.81, 0, 0]}", 300.0); }

bool shooting(const std::string& scheme) {
  return scheme == "implicit-midpoint" || scheme == "bdf-alpha";
}

/// The initial state of solve_dynamic for a scene, as `initial: static`: the clamped statics
/// (rkmk-rk4 on a grid 4x finer, sampled at the nodes; for the shooting schemes their own grid's,
/// rkmk-euler-explicit at N).
RestState static_start(const scene::Scene& s, int nodes, const std::string& scheme) {
  const int refine = shooting(scheme) ? 1 : 4;
  solvers::statics::StaticSolveOptions so;
  so.scheme = shooting(scheme) ? "rkmk-euler-explicit" : "rkmk-rk4";
  so.nodes = refine * (nodes - 1) + 1;
  so.tol = 1e-12;
  const auto eq = solvers::statics::solve_static(s, so);
  BOOST_REQUIRE(eq.converged);
  RestState r{std::vector<lie::SE3>(nodes), std::vector<lie::Vector6>(nodes)};
  for (int j = 0; j < nodes; ++j) {
    r.g[j] = eq.centerline[refine * j].pose;
    r.xi[j] = eq.centerline[refine * j].twist;
  }
  return r;
}

/// Steps `stepper` to t_end in steps of dt; the middle node's position after every step.
struct Run {
  std::vector<double> t, mid_x;
  lie::Vector3 mid = lie::Vector3::Zero();
  double max_tip_error = 0.0;  ///< max |p_tip - p_clamp| over the run
  std::vector<solvers::dynamics::Energy> energy;
  bool ok = true;
};

Run run(Stepper& stepper, const DynamicProblem& P, int nodes, double dt, double t_end) {
  Run r;
  const int mid = (nodes - 1) / 2;
  const auto steps = static_cast<long>(std::lround(t_end / dt));
  r.energy.push_back(stepper.energy());
  for (long i = 0; i < steps; ++i) {
    const auto status = stepper.step(i * dt, dt);
    if (!status.ok) {
      BOOST_TEST_MESSAGE("step failed: " << status.reason);
      r.ok = false;
      return r;
    }
    const auto c = stepper.centerline();
    r.t.push_back((i + 1) * dt);
    r.mid = c[mid].pose.translation();
    r.mid_x.push_back(r.mid.x());
    r.max_tip_error = std::max(
        r.max_tip_error, (stepper.tip_position() - P.tip_target().translation()).norm());
    r.energy.push_back(stepper.energy());
  }
  return r;
}

/// First bending frequency of a clamped-clamped Timoshenko beam with shear coefficient 1 (the
/// rod model's K = diag(EI, EI, GJ, GA, GA, EA)) and rotary inertia rho I: the root near the
/// Euler-Bernoulli value of det [w; phi](L) of the transfer matrix of
///   GA (w'' - phi') + rho A omega^2 w = 0,   EI phi'' + GA (w' - phi) + rho I omega^2 phi = 0
/// from w = phi = 0 at s = 0 (RK4 on the constant-coefficient system, 2000 steps: 1e-12
/// relative), by bisection.
double timoshenko_clamped_clamped_hz() {
  const double GA = kG * kA, rA = kRho * kA, rI = kRho * kI;
  auto det = [&](double w) {
    Eigen::Matrix4d M;
    M << 0, 0, 1, 0, 0, 0, 0, 1, -rA * w * w / GA, 0, 0, 1, 0, (GA - rI * w * w) / kEI,
        -GA / kEI, 0;
    const int n = 2000;
    const Eigen::Matrix4d h = M * (kL / n), h2 = h * h;
    const Eigen::Matrix4d S = Eigen::Matrix4d::Identity() + h + h2 / 2 + h2 * h / 6 + h2 * h2 / 24;
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    for (int i = 0; i < n; ++i) T = S * T;
    return T.block<2, 2>(0, 2).determinant();
  };
  const double w_eb = std::pow(4.7300407448627040, 2) / (kL * kL) * std::sqrt(kEI / (kRho * kA));
  double lo = 0.85 * w_eb, hi = w_eb;
  BOOST_REQUIRE(det(lo) * det(hi) < 0.0);
  for (int k = 0; k < 60; ++k) {
    const double m = 0.5 * (lo + hi);
    (det(lo) * det(m) <= 0.0 ? hi : lo) = m;
  }
  return 0.5 * (lo + hi) / (2.0 * std::numbers::pi);
}


}  // namespace

// (a) First bending frequency, every scheme, against Euler-Bernoulli beta_1 L = 4.7300407,
// f_EB = beta_1^2 / (2 pi L^2) sqrt(EI / rho A) = 28.151 Hz, with the shear and rotary-inertia
// correction of L/D = 10: the Timoshenko beam (shear coefficient 1, as the rod model) gives
// f_T = 0.9531 f_EB = 26.83 Hz (computed here; a clamped-clamped mode is far more sensitive than
// the cantilever's, where the same beam gives 0.9942). Tolerance per scheme around f_T: the
// staggered grid at N = 21 (second order in s) and the time steps below, 0.5 % (measured
// +0.26 .. +0.34 %); bdf-alpha (first order in s, N = 21, dt = 1 ms) 4 % (measured +3.2 %). implicit-midpoint (the thesis form) is unstable
// without damping (docs/dynamics.md): at dt = 1 and 2 ms its shooting stopped converging after
// 16 and 66 ms, so it has no undamped frequency; its clamp is checked in the settling and CLI
// cases.
BOOST_AUTO_TEST_CASE(first_bending_frequency_every_scheme) {
  const auto s = released_clamped();
  const auto P = DynamicProblem::from_scene(s);
  BOOST_REQUIRE(P.tip_clamped());
  const double f_eb = std::pow(4.7300407448627040, 2) / (2 * std::numbers::pi * kL * kL) *
                      std::sqrt(kEI / (kRho * kA));
  const double f_t = timoshenko_clamped_clamped_hz();
  BOOST_TEST_MESSAGE("Euler-Bernoulli " << f_eb << " Hz, Timoshenko " << f_t << " Hz (ratio "
                                        << f_t / f_eb << ")");
  BOOST_TEST(std::abs(f_t / f_eb - 0.9531) < 1e-3);  // the correction the docs state
  const int n = 21;
  struct Case {
    const char* scheme;
    double dt, tol, t_end;
  };
  const double dt_var = solvers::dynamics::auto_time_step(P, "variational", n);
  for (const Case c : {Case{"variational", dt_var, 5e-3, 0.16},
                       Case{"implicit-midpoint-collocation", 5e-4, 5e-3, 0.16},
                       Case{"ida", 2.5e-4, 5e-3, 0.16}, Case{"bdf-alpha", 1e-3, 4e-2, 0.16}}) {
    const auto start_time = std::chrono::steady_clock::now();
    auto stepper = make_scheme(c.scheme, P, n, static_start(s, n, c.scheme), 1e-10, 1e-10);
    const Run r = run(*stepper, P, n, c.dt, c.t_end);
    BOOST_TEST_CONTEXT(c.scheme) {
      BOOST_REQUIRE(r.ok);
      const double f = 1.0 / mean_period(r.t, r.mid_x);
      BOOST_TEST_MESSAGE(c.scheme << ": f = " << f << " Hz, f / f_EB = " << f / f_eb
                                  << ", f / f_T = " << f / f_t << ", max |tip - clamp| "
                                  << r.max_tip_error << " m, wall "
                                  << seconds_since(start_time) << " s");
      BOOST_TEST(std::abs(f / f_t - 1.0) < c.tol);
      // the shooting schemes hold the clamp to their tolerance (1e-10, scaled by L): 1e-11 m
      BOOST_TEST(r.max_tip_error < (std::string(c.scheme) == "bdf-alpha" ? 2e-11 : 1e-12));
    }
  }
}

// (b) Released straight under gravity with Kelvin-Voigt damping (300 Pa s; the first mode decays
// at ~13 /s), the rod settles to its clamped statics, compared at s = L/4 (not the middle: by
// symmetry the first-order error of the shooting grid vanishes there). Reference: rkmk-rk4 at
// N = 161 (fourth order; 1e-12 m here). The staggered grid's equilibrium is one for collocation,
// ida and variational (the same semi-discrete system): collocation at N = 5, 9, 17 must show order
// 2 in ds (1.8..2.2), ida and variational reach collocation's settled node at N = 9 to 1e-8 m
// (settling and tolerance residue; the errors are ~1e-5 m). The shooting schemes settle to the
// statics of their own grid (rkmk-euler-explicit at the same N) to 1e-9 m (bdf-alpha), and its error
// against the reference falls at least at first order from N = 9 to 17.
BOOST_AUTO_TEST_CASE(settles_to_the_clamped_statics) {
  const auto s = sagging_clamped();
  const auto P = DynamicProblem::from_scene(s);
  auto statics_at_quarter = [&](const std::string& scheme, int nodes) {
    solvers::statics::StaticSolveOptions so;
    so.scheme = scheme;
    so.nodes = nodes;
    so.tol = 1e-12;
    const auto eq = solvers::statics::solve_static(s, so);
    BOOST_REQUIRE(eq.converged);
    const std::size_t q = (nodes - 1) / 4;
    BOOST_REQUIRE(std::abs(eq.centerline[q].s - 0.25 * kL) < 1e-14);
    return eq.centerline[q].pose.translation();
  };
  const lie::Vector3 ref = statics_at_quarter("rkmk-rk4", 161);
  BOOST_TEST_MESSAGE("statics (rkmk-rk4 N = 161): node at L/4 x = " << ref.x() << " m");
  BOOST_REQUIRE(ref.x() < -1e-4);  // sags (middle: q L^4 / (384 EI) = 4.1e-4 m)
  auto settled = [&](const std::string& scheme, int n, double dt, double t_end) {
    const auto start = std::chrono::steady_clock::now();
    auto stepper = make_scheme(scheme, P, n, straight(P, n), 1e-10, 1e-8);
    const Run r = run(*stepper, P, n, dt, t_end);
    BOOST_REQUIRE(r.ok);
    const lie::Vector3 quarter = stepper->centerline()[(n - 1) / 4].pose.translation();
    BOOST_TEST_MESSAGE(scheme << " N = " << n << ": error at L/4 " << (quarter - ref).norm()
                              << " m, wall " << seconds_since(start) << " s");
    return quarter;
  };
  std::vector<double> err;
  lie::Vector3 coll9 = lie::Vector3::Zero();
  for (int n : {5, 9, 17}) {
    const lie::Vector3 x = settled("implicit-midpoint-collocation", n, 2e-3, 1.5);
    if (n == 9) coll9 = x;
    err.push_back((x - ref).norm());
  }
  for (std::size_t i = 1; i < err.size(); ++i) {
    const double order = std::log2(err[i - 1] / err[i]);
    BOOST_TEST_MESSAGE("collocation order " << order);
    BOOST_TEST(order > 1.8);
    BOOST_TEST(order < 2.2);
  }
  const lie::Vector3 ida9 = settled("ida", 9, 5e-3, 1.5);
  BOOST_TEST((ida9 - coll9).norm() < 1e-8);
  const double dt_var = solvers::dynamics::auto_time_step(P, "variational", 9);
  const lie::Vector3 var9 = settled("variational", 9, dt_var, 1.5);
  BOOST_TEST((var9 - coll9).norm() < 1e-8);
  // The shooting schemes: bdf-alpha (its high modes damped) settles onto its own grid's statics.
  // implicit-midpoint is left out: its stiff viscous modes flip sign instead of decaying
  // (amplification -> -1) and it had not settled after 1.5 s (7e-5 m off at N = 9).
  std::vector<double> shooting_err;
  for (int n : {9, 17}) {
    const lie::Vector3 x = settled("bdf-alpha", n, 5e-3, 1.5);
    const double own = (x - statics_at_quarter("rkmk-euler-explicit", n)).norm();
    BOOST_TEST_MESSAGE("  against rkmk-euler-explicit N = " << n << ": " << own << " m");
    BOOST_TEST(own < 1e-9);
    shooting_err.push_back((x - ref).norm());
  }
  // Explicit Euler RKMK is first order, but on this symmetric clamped-clamped case its error
  // falls at 1.9 (measured); asserted: it converges at least at first order.
  const double order = std::log2(shooting_err[0] / shooting_err[1]);
  BOOST_TEST_MESSAGE("bdf-alpha order " << order);
  BOOST_TEST(order > 0.8);
}

// (c) On the same grid (N = 11) implicit-midpoint-collocation converges to ida (rtol = atol =
// 1e-12) at second order in dt: the viscous rod released straight under gravity (Kelvin-Voigt
// 300 Pa s damps the grid's high modes), the largest difference of the middle node over the
// first 0.04 s (compared every 1 ms) at dt = 1, 0.5, 0.25 ms; observed orders within 1.8..2.2.
// (The undamped release from the bend, at dt = 0.2, 0.1, 0.05 ms, gave 2.3e-7, 8.3e-8, 5.5e-8 m:
// a floor of ~5e-8 m, 0.2 % of the amplitude, that is not explained yet; docs/dynamics.md.)
BOOST_AUTO_TEST_CASE(collocation_converges_to_ida_at_second_order) {
  const auto s = sagging_clamped();
  const auto P = DynamicProblem::from_scene(s);
  const int n = 11;
  const RestState start = straight(P, n);
  auto ida = make_scheme("ida", P, n, start, 1e-10, 1e-12);
  const Run ref = run(*ida, P, n, 1e-3, 0.04);
  BOOST_REQUIRE(ref.ok);
  std::vector<double> err;
  for (const int per_ms : {1, 2, 4}) {
    auto coll = make_scheme("implicit-midpoint-collocation", P, n, start, 1e-12);
    const Run r = run(*coll, P, n, 1e-3 / per_ms, 0.04);
    BOOST_REQUIRE(r.ok);
    double d = 0.0;
    for (std::size_t k = 0; k < ref.mid_x.size(); ++k)
      d = std::max(d, std::abs(r.mid_x[(k + 1) * per_ms - 1] - ref.mid_x[k]));
    err.push_back(d);
    BOOST_TEST_MESSAGE("dt = " << 1e-3 / per_ms << " s: largest middle-node difference " << d
                               << " m");
  }
  for (std::size_t i = 1; i < err.size(); ++i) {
    const double order = std::log2(err[i - 1] / err[i]);
    BOOST_TEST_MESSAGE("order " << order);
    BOOST_TEST(order > 1.8);
    BOOST_TEST(order < 2.2);
  }
}

// (d) The clamp does no work. Damped (300 Pa s, gravity, released straight, 0.5 s): the ledger
// kinetic + strain + gravity + dissipated - work_in stays within 1e-6 of
// max |gravity energy| (ida; dt = 1 ms for collocation, dt: auto for variational; collocation 2e-5, variational 5e-4, measured 5.8e-6 and 1.1e-4),
// with work_in = 0 exactly (no input). Undamped (released from the small
// bend, 1 s = 27 periods): the energy error has no trend, max |E - E0| in the second half at
// most 1.5x the first half's, and below 1e-6 E0 (collocation, dt = 1 ms) or 2e-2 E0
// (variational at half its dt: auto; its energy error falls as dt^2, measured 11 %, 0.73 %,
// 0.16 % of E0 at dt = 2.5e-4, 1.25e-4, 6.25e-5 s).
BOOST_AUTO_TEST_CASE(ledger_closes_and_energy_has_no_trend) {
  {
    const auto s = sagging_clamped();
    const auto P = DynamicProblem::from_scene(s);
    const int n = 11;
    struct Case {
      const char* scheme;
      double dt, tol;
    };
    for (const Case c : {Case{"ida", 1e-3, 1e-6}, Case{"implicit-midpoint-collocation", 1e-3, 2e-5},
                         Case{"variational", solvers::dynamics::auto_time_step(P, "variational", n),
                              5e-4}}) {
      auto stepper = make_scheme(c.scheme, P, n, straight(P, n), 1e-10, 1e-10);
      const Run r = run(*stepper, P, n, c.dt, 0.5);
      BOOST_REQUIRE(r.ok);
      const double scale = max_abs_gravity(r.energy), drift = ledger_drift(r.energy);
      BOOST_TEST_MESSAGE(c.scheme << " damped: max |P| " << scale << " J, dissipated "
                                  << r.energy.back().dissipated << " J, ledger drift " << drift
                                  << " J (" << drift / scale << " relative)");
      BOOST_TEST(r.energy.back().dissipated > 0.1 * scale);
      BOOST_TEST(drift <= c.tol * scale);
      BOOST_TEST(r.energy.back().work_in == 0.0);
    }
  }
  const auto s = released_clamped();
  const auto P = DynamicProblem::from_scene(s);
  const int n = 11;
  const RestState start = static_start(s, n, "ida");
  for (const auto& [scheme, dt] :
       {std::pair<std::string, double>{"implicit-midpoint-collocation", 1e-3},
        {"variational", 0.5 * solvers::dynamics::auto_time_step(P, "variational", n)}}) {
    auto stepper = make_scheme(scheme, P, n, start);
    const Run r = run(*stepper, P, n, dt, 1.0);
    BOOST_REQUIRE(r.ok);
    const double E0 = r.energy.front().total();
    double first = 0.0, second = 0.0;
    const std::size_t half = r.energy.size() / 2;
    for (std::size_t i = 0; i < r.energy.size(); ++i) {
      double& m = i < half ? first : second;
      m = std::max(m, std::abs(r.energy[i].total() - E0));
    }
    BOOST_TEST_MESSAGE(scheme << " undamped: E0 = " << E0 << " J, max |E - E0| " << first
                              << " / " << second << " J (first / second half)");
    BOOST_TEST(E0 > 0.0);
    BOOST_TEST(std::max(first, second) <= (scheme == "variational" ? 2e-2 : 1e-6) * E0);
    BOOST_TEST(second <= 1.5 * first);
  }
}

// (e) Bad input and the command line. A clamp away from the rest shape's tip cannot start from
// `initial: straight`: exit 2 naming tip.clamped and dynamics.initial and pointing to `initial:
// static`; with `initial: static` the same scene runs. scenes/clamped-clamped-dynamics.yaml runs
// with `rodlab dynamic` (exit 0, a converged result written) in every scheme. Kirchhoff rods
// with a clamped tip are rejected by the staggered-grid schemes (exit 2).
BOOST_AUTO_TEST_CASE(command_line_and_bad_input) {
  namespace cli = rodlab::testing::cli;
  cli::Sandbox box("clamped");
  const std::string displaced = R"(schema: rodlab.scene/1
name: displaced-clamp
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 300}
tip:
  clamped: {position: [0.01, 0, 0.1], rotation: identity}
dynamics: {t_end: 0.02, dt: 0.002, initial: straight}
)";
  box.write("displaced.yaml", displaced);
  cli::expect_bad_input(box, "dynamic displaced.yaml --nodes 11",
                        {"tip.clamped", "dynamics.initial", "initial: static"});
  {
    const cli::Run r = box.run("dynamic displaced.yaml --nodes 11 --set dynamics.initial=static "
                               "--scheme implicit-midpoint-collocation --out d.json");
    BOOST_TEST_CONTEXT(r.err) {
      BOOST_TEST(r.status == 0);
      BOOST_TEST(cli::contains(cli::read(box.work / "d.json"), "\"converged\": true"));
    }
  }
  cli::expect_bad_input(box,
                        "dynamic displaced.yaml --nodes 11 --set dynamics.initial=static "
                        "--set rod.model=kirchhoff --scheme variational",
                        {"kirchhoff", "tip.clamped"});
  {
    // (an inextensible rod cannot reach the displaced clamp; held at its rest tip it is locked)
    box.write("kirchhoff.yaml", R"(schema: rodlab.scene/1
name: kirchhoff-clamped
rod:
  model: kirchhoff
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 300}
tip:
  clamped: {position: [0, 0, 0.1], rotation: identity}
loads:
  gravity: [-9.81, 0, 0]
dynamics: {t_end: 0.05, dt: 0.005, initial: straight}
)");
    cli::expect_bad_input(box, "dynamic kirchhoff.yaml --nodes 11 --scheme implicit-midpoint-collocation",
                          {"kirchhoff", "tip.clamped"});
  }
  const std::string scene = std::string(RODLAB_SOURCE_DIR) + "/scenes/clamped-clamped-dynamics.yaml";
  for (const std::string scheme : {"variational", "implicit-midpoint-collocation", "ida",
                                   "implicit-midpoint", "bdf-alpha"}) {
    const cli::Run r =
        box.run("dynamic " + cli::quote(scene) + " --t-end 0.05 --scheme " + scheme + " --out " +
                scheme + ".json");
    BOOST_TEST_CONTEXT(scheme << "\n" << r.err) {
      BOOST_TEST(r.status == 0);
      const std::string json = cli::read(box.work / (scheme + ".json"));
      BOOST_TEST(cli::contains(json, "\"converged\": true"));
      BOOST_TEST(cli::contains(json, "rodlab.dynamic-result/1"));
    }
  }
}
