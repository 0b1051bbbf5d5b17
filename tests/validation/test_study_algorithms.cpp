#define BOOST_TEST_MODULE study_algorithms
#include <boost/test/unit_test.hpp>

// The study algorithms of validation/studies on synthetic data with known answers: the order
// fit (fit.hpp: least squares on the asymptotic range, rounding floor, unusable points), the
// Pareto front of error against time (work_precision.hpp) and `study recommend` (the fastest
// run within the tolerance and the budget). References: exact power laws and hand-made
// sweeps whose fronts and recommendations are read off by eye.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "studies/fit.hpp"
#include "studies/stable_step.hpp"
#include "studies/work_precision.hpp"

namespace study = rodlab::validation::study;

namespace {

std::vector<study::FitPoint> power_law(double C, double p, const std::vector<double>& h) {
  std::vector<study::FitPoint> out;
  for (const double x : h) out.push_back({x, C * std::pow(x, p), true});
  return out;
}

/// A study row of a sweep: scheme, error [m], median wall time [s].
study::SweepRow row(const std::string& scheme, double error, double time, bool converged = true) {
  study::SweepRow r;
  r.role = "study";
  r.spec.scheme = scheme;
  r.run.converged = converged;
  r.run.wall_time_s = time;
  r.error = error;
  return r;
}

study::Json json_row(const std::string& scheme, int nodes, double error, double time) {
  return {{"role", "study"}, {"scheme", scheme}, {"nodes", nodes}, {"dt", nullptr},
          {"converged", true}, {"error", error}, {"wall_time_s", time}, {"repeats", 3}};
}

}  // namespace

// Exact power laws C h^p: the fitted slope is p to rounding (1e-12).
BOOST_AUTO_TEST_CASE(order_fit_is_exact_on_power_laws) {
  for (const double p : {1.0, 2.0, 4.0}) {
    const auto fit = study::fit_order(power_law(3.0, p, {0.1, 0.05, 0.025, 0.0125}), 0.0);
    BOOST_TEST(std::abs(fit.order - p) <= 1e-12);
    BOOST_TEST(fit.points == 4);
  }
}

// A pre-asymptotic coarse point (local order 0.5 where the rest is 2) is dropped.
BOOST_AUTO_TEST_CASE(order_fit_drops_the_preasymptotic_point) {
  auto points = power_law(1.0, 2.0, {0.05, 0.025, 0.0125, 0.00625});
  points.insert(points.begin(), {0.1, points.front().error * std::sqrt(2.0), true});
  const auto fit = study::fit_order(points, 0.0);
  BOOST_TEST(std::abs(fit.order - 2.0) <= 1e-12);
  BOOST_TEST(!fit.used[0]);
  BOOST_TEST(fit.points == 4);
}

// Errors at or below the rounding floor and unusable points take no part; too few points
// give no fit (NaN, with a note).
BOOST_AUTO_TEST_CASE(order_fit_ignores_rounding_and_failed_points) {
  auto points = power_law(1.0, 4.0, {0.1, 0.05, 0.025});
  points.push_back({0.0125, 1e-17, true});  // below the floor
  points.push_back({0.00625, 1e-3, false});  // did not converge
  const double floor = study::rounding_floor(0.1);
  BOOST_TEST(floor == 1e3 * std::numeric_limits<double>::epsilon() * 0.1);
  const auto fit = study::fit_order(points, floor);
  BOOST_TEST(std::abs(fit.order - 4.0) <= 1e-12);
  BOOST_TEST(fit.points == 3);
  BOOST_TEST(!fit.used[3]);
  BOOST_TEST(!fit.used[4]);
  const auto none = study::fit_order({{0.1, 1e-3, true}}, 0.0);
  BOOST_TEST(std::isnan(none.order));
  BOOST_TEST(!none.note.empty());
}

// Pareto front of (error, time): a run is on it unless another is at least as good in both
// and better in one; failed runs and reference rows are never on it.
BOOST_AUTO_TEST_CASE(pareto_front_of_a_hand_made_sweep) {
  study::Sweep sweep;
  sweep.rows = {row("a", 1e-3, 1.0),   // front: the fastest
                row("b", 1e-4, 2.0),   // front
                row("c", 1e-4, 3.0),   // dominated by b (same error, slower)
                row("d", 1e-6, 10.0),  // front: the most accurate
                row("e", 1e-2, 5.0),   // dominated by a
                row("f", 1e-9, 0.1, false)};  // failed: not eligible
  study::SweepRow ref = row("ref", 0.0, 0.01);
  ref.role = "reference";
  sweep.rows.push_back(ref);
  const auto front = study::pareto_front(sweep);
  const std::vector<bool> expected{true, true, false, true, false, false, false};
  BOOST_TEST(front == expected, boost::test_tools::per_element());
}

// recommend: the fastest run with error <= tol within the budget; without a budget the
// fastest meeting tol; when nothing meets tol, the most accurate for the message.
BOOST_AUTO_TEST_CASE(recommend_on_hand_made_rows) {
  const study::Json rows = study::Json::array({json_row("a", 11, 1e-3, 0.001),
                                               json_row("b", 21, 1e-5, 0.004),
                                               json_row("c", 41, 1e-7, 0.020),
                                               json_row("d", 81, 1e-7, 0.015)});
  const auto r1 = study::recommend(rows, 1e-4, std::nullopt);
  BOOST_TEST_REQUIRE(r1.best.has_value());
  BOOST_TEST(r1.best->scheme == "b");
  BOOST_TEST(r1.candidates == 4);
  const auto r2 = study::recommend(rows, 1e-6, std::nullopt);
  BOOST_TEST(r2.best->scheme == "d");  // c and d equally accurate, d faster
  const auto r3 = study::recommend(rows, 1e-6, 10.0);  // 10 ms: c and d too slow
  BOOST_TEST(!r3.best.has_value());
  BOOST_TEST(r3.fastest_meeting_tol->scheme == "d");
  const auto r4 = study::recommend(rows, 1e-9, std::nullopt);
  BOOST_TEST(!r4.best.has_value());
  BOOST_TEST(!r4.fastest_meeting_tol.has_value());
  BOOST_TEST((r4.most_accurate->scheme == "c" || r4.most_accurate->scheme == "d"));
}

// The stable-step bisection (stable_step.hpp) on a known threshold: dt <= 0.37 is stable. The
// bracket [0.1, 1] closes geometrically to hi / lo <= 1.001 around it, in
// ceil(log2(ln 10 / ln 1.001)) = 12 runs.
BOOST_AUTO_TEST_CASE(stable_step_bisection_brackets_a_known_threshold) {
  int calls = 0;
  const auto b = study::bisect_stable_step(
      [&](double dt) {
        ++calls;
        return dt <= 0.37;
      },
      0.1, 1.0, 1.001);
  BOOST_TEST(b.stable <= 0.37);
  BOOST_TEST(b.unstable > 0.37);
  BOOST_TEST(b.unstable / b.stable <= 1.001);
  BOOST_TEST(b.runs == 12);
  BOOST_TEST(calls == 12);
}
