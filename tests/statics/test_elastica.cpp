#define BOOST_TEST_MODULE statics_elastica
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "elastica_reference.hpp"
#include "schemes_under_test.hpp"
#include "statics_support.hpp"

// Cases 5 and 9: large deflections of the Table 2.1 cantilever as a Kirchhoff rod (inextensible
// and unshearable, the classic elastica's assumptions), with a tip force perpendicular to the
// undeformed rod, PL^2/EI in {1, 2, 5, 10}:
//   - dead load (world frame, along +x): against the elliptic-integral closed form of Bisshopp &
//     Drucker (1945) and an independent rk8pd integration (elastica_reference.hpp);
//   - follower load (body frame, along the tip section's x axis): against the rk8pd integration.
// Every scheme must converge from the solver's own start (straight-rod guess, then its load
// continuation; no hand-made initial guess), its tip error must fall at its design order over
// N in {26, 51, 101, 201} (least-squares fit, within 0.15), and rkmk-rk4 at N = 200 must be
// within 1e-8 L of the closed form.
//
// Measured (this file's messages, RKMK schemes): rkmk-rk4 N = 200 dead-load tip errors 1.6e-12
// (alpha = 1), 3.7e-12, 2.2e-11, 1.05e-10 L (alpha = 10); observed orders 0.96-1.05 (Euler),
// 1.97-2.07 (midpoint), 3.96-4.07 (rk4) over both load types and all alpha. Newton iterations
// (summed over any continuation steps): 4-56; every run converged without continuation help
// beyond the solver's own. Follower references (rk8pd): alpha = 1: x = 0.320642, z = 0.935646,
// theta_L = 0.495885; 2: 0.573839, 0.767362, 0.968239; 5: 0.780690, 0.172278, 2.09816;
// 10: 0.546983, -0.0921232, 2.99271 (the tip turns past the horizontal).

namespace {

using namespace rodlab;
using namespace rodlab::testing::statics;
using rod::ModelKind;
using loads::WrenchFrame;

const std::vector<double> kAlphas{1.0, 2.0, 5.0, 10.0};
const std::vector<int> kOrderNodes{26, 51, 101, 201};
// Per-N bound err <= C (h/L)^p (error_bound): measured constants err / (h/L)^p up to 4.0
// (Euler, follower alpha = 10), 2.5 (midpoint), 2.1 (rk4); C = 10.
constexpr double kElasticaC = 10.0;

Matrix3 rot_y(double a) {
  Matrix3 R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}

/// max(|dp|/L, rotation distance to Ry(theta_ref)) of a result's tip against a planar reference
/// (the rotation distance does not wrap at pi: the follower tip turns to ~3 rad at alpha = 10).
double planar_error(const StaticResult& r, const PlanarTip& ref) {
  const SE3& tip = r.centerline.back().pose;
  const Vector3 p = tip.translation() / Table21::L;
  const double dp = (p - Vector3(ref.x, 0.0, ref.z)).norm();
  return std::max(dp, rotation_distance(tip.rotation_matrix(), rot_y(ref.theta)));
}

StaticProblem elastica_problem(double alpha, WrenchFrame frame) {
  const double P = alpha * Table21::EI / (Table21::L * Table21::L);
  return tip_wrench_problem(ModelKind::kirchhoff, wrench(Vector3::Zero(), Vector3(P, 0, 0)), frame);
}

/// Runs every scheme on the grids, checks convergence, the observed order and returns nothing;
/// logs the table.
void check_schemes_against(const PlanarTip& ref, double alpha, WrenchFrame frame, const char* label) {
  const auto problem = elastica_problem(alpha, frame);
  for (const auto& s : statics_schemes_under_test()) {
    std::vector<double> h, err;
    std::ostringstream row;
    row << label << " alpha = " << alpha << " " << s.name << ":";
    for (const int N : grid_for(s, kOrderNodes)) {
      const auto r = solve(problem, s.name, N);
      if (!check_result(r, N)) continue;
      h.push_back(1.0 / (N - 1));
      err.push_back(planar_error(r, ref));
      const double bound = error_bound(s, N, kElasticaC, 1e-11);
      BOOST_TEST(err.back() <= bound, label << " alpha = " << alpha << " " << describe(r) << ": tip error " << err.back()
                                            << " > C h^p = " << bound << " (tip at "
                                            << r.centerline.back().pose.translation().transpose() / Table21::L << " L)");
      row << " N=" << N << " err=" << err.back() << " it=" << r.iterations;
    }
    if (h.size() != grid_for(s, kOrderNodes).size()) continue;
    // Floor: the reference (rk8pd at 1e-14, bisection to 1e-16) and the Newton tolerance.
    const double p = check_observed_order(s, h, err, 1e-11, std::string(label) + " alpha " + std::to_string(alpha));
    row << "  observed order " << p;
    BOOST_TEST_MESSAGE(row.str());
  }
}

}  // namespace

// The two references agree with each other and with the mpmath values quoted in
// elastica_reference.hpp, and with Bisshopp & Drucker's 4-digit table.
BOOST_AUTO_TEST_CASE(references_agree) {
  const double mp[4][4] = {{1, 0.30172077379981353, 0.94356676371662312, 0.46135194971187896},
                           {2, 0.49345748039671182, 0.83935827917483276, 0.78174983155654304},
                           {5, 0.71379152361191273, 0.61237163927557013, 1.2153681176116811},
                           {10, 0.81060902488029645, 0.44500440224624873, 1.4302855388038575}};
  for (const auto& row : mp) {
    const PlanarTip e = elastica_dead_load_elliptic(row[0]);
    const PlanarTip o = elastica_dead_load_ode(row[0]);
    BOOST_TEST_MESSAGE("alpha " << row[0] << ": elliptic x " << e.x << " z " << e.z << " phi0 " << e.theta
                                << "; ode - elliptic: " << o.x - e.x << ", " << o.z - e.z << ", " << o.theta - e.theta);
    BOOST_TEST(std::abs(e.x - row[1]) <= 1e-13);
    BOOST_TEST(std::abs(e.z - row[2]) <= 1e-13);
    BOOST_TEST(std::abs(e.theta - row[3]) <= 1e-13);
    BOOST_TEST(std::abs(o.x - e.x) <= 1e-12);
    BOOST_TEST(std::abs(o.z - e.z) <= 1e-12);
    BOOST_TEST(std::abs(o.theta - e.theta) <= 1e-12);
  }
  // Bisshopp & Drucker (1945), vertical tip deflection / L to 4 digits.
  BOOST_TEST(std::abs(elastica_dead_load_elliptic(1.0).x - 0.3017) <= 0.5e-4);
  BOOST_TEST(std::abs(elastica_dead_load_elliptic(10.0).x - 0.8106) <= 0.5e-4);
  // Small-load limit: x/L -> alpha/3, phi0 -> alpha/2.
  const PlanarTip small = elastica_dead_load_elliptic(1e-4);
  BOOST_TEST(std::abs(small.x / (1e-4 / 3.0) - 1.0) <= 1e-6);
  BOOST_TEST(std::abs(small.theta / (1e-4 / 2.0) - 1.0) <= 1e-6);
}

BOOST_AUTO_TEST_CASE(dead_load_rk4_n200) {
  for (const double alpha : kAlphas) {
    const PlanarTip ref = elastica_dead_load_elliptic(alpha);
    const auto r = solve(elastica_problem(alpha, WrenchFrame::world), "rkmk-rk4", 200);
    if (!check_result(r, 200)) continue;
    const double e = planar_error(r, ref);
    BOOST_TEST(e <= 1e-8, "alpha " << alpha << " " << describe(r) << ": tip error " << e);
    // Inextensible: arclength preserved, nu = e_z at every node.
    for (const auto& c : r.centerline) BOOST_TEST((c.twist.tail<3>() - Vector3(0, 0, 1)).norm() == 0.0);
    BOOST_TEST_MESSAGE("dead load alpha = " << alpha << " " << describe(r) << ": tip error " << e << " L");
  }
}

BOOST_AUTO_TEST_CASE(dead_load_every_scheme_order) {
  for (const double alpha : kAlphas)
    check_schemes_against(elastica_dead_load_elliptic(alpha), alpha, WrenchFrame::world, "dead load");
}

// Follower (body-frame) tip force: the force turns with the tip section, F = R(L) (P e_x).
BOOST_AUTO_TEST_CASE(follower_load_every_scheme_order) {
  for (const double alpha : kAlphas) {
    const PlanarTip ref = elastica_follower_ode(alpha);
    BOOST_TEST_MESSAGE("follower reference alpha = " << alpha << ": x " << ref.x << " z " << ref.z
                                                     << " theta_L " << ref.theta);
    check_schemes_against(ref, alpha, WrenchFrame::body, "follower load");
    const auto r = solve(elastica_problem(alpha, WrenchFrame::body), "rkmk-rk4", 200);
    if (!check_result(r, 200)) continue;
    BOOST_TEST(planar_error(r, ref) <= 1e-8, describe(r) << ": follower tip error " << planar_error(r, ref));
  }
}
