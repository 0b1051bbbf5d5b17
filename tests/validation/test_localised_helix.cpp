#define BOOST_TEST_MODULE validation_localised_helix
// The localised helical buckle's closed form (validation/reference/localised_helix.hpp) checked
// against the equations it claims to solve, independently of rodlab's schemes: by central
// differences of its samples, the frame's body angular velocity is the curvature in its wrench
// (moment = diag(B, B, C) w), the centreline follows the tangent (p' = R e_z), the force is
// constant and the moment balance of an inextensible rod holds, m' + t x n = 0 (spatial frame).
// Then rodlab's rkmk-rk4 between clamps at its end poses, started from its base wrench with a 1 %
// error, converges to it (the literature family measures how closely, at several N).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "checks/literature_helix.hpp"

#include "reference/localised_helix.hpp"

namespace ref = rodlab::validation::reference;
using rodlab::lie::SE3;
using rodlab::lie::SO3;
using rodlab::lie::Vector3;
using rodlab::lie::Vector6;

namespace {

// A rod of unit length with B = 1, C = 2/3, m = M / sqrt(B T) = 1.5 and kappa L = 8.
constexpr double kB = 1.0, kC = 2.0 / 3.0, kL = 1.0;
double tension() { return 2.0 * kB * 64.0 / (2.0 - 0.5 * 1.5 * 1.5); }
double moment() { return 1.5 * std::sqrt(kB * tension()); }

}  // namespace

BOOST_AUTO_TEST_CASE(closed_form_is_an_equilibrium_of_the_kirchhoff_rod) {
  const ref::LocalisedHelix helix(kB, kC, tension(), moment(), kL);
  BOOST_TEST(std::abs(helix.amplitude() - 0.875) <= 1e-15);
  BOOST_TEST(std::abs(helix.decay() - 8.0) <= 1e-12);
  const double h = 1e-5;
  double worst_curvature = 0, worst_tangent = 0, worst_balance = 0, worst_envelope = 0;
  for (double s : {-0.45, -0.2, -0.05, 0.0, 0.1, 0.3}) {
    const std::vector<double> at{s - h, s, s + h};
    const auto x = helix.samples(at);
    const SE3& g = x[1].pose;
    // w from R^T R' (central difference of the log of the relative rotation)
    const Vector3 w = (x[0].pose.rotation().inverse() * x[2].pose.rotation()).log() / (2 * h);
    const Vector6& W = x[1].wrench;
    const Vector3 curvature_moment(kB * w.x(), kB * w.y(), kC * w.z());
    worst_curvature = std::max(worst_curvature, (curvature_moment - W.head<3>()).norm() / moment());
    const Vector3 t = g.rotation() * Vector3::UnitZ();
    const Vector3 dp = (x[2].pose.translation() - x[0].pose.translation()) / (2 * h);
    worst_tangent = std::max(worst_tangent, (dp - t).norm());
    // spatial moment and force
    const auto spatial = [](const ref::LocalisedHelix::Sample& y) {
      return std::pair{Vector3(y.pose.rotation() * y.wrench.head<3>()),
                       Vector3(y.pose.rotation() * y.wrench.tail<3>())};
    };
    const auto [m0, n0] = spatial(x[0]);
    const auto [m2, n2] = spatial(x[2]);
    const auto [m1, n1] = spatial(x[1]);
    BOOST_TEST((n1 - Vector3(0, 0, tension())).norm() <= 1e-9 * tension());
    const Vector3 balance = (m2 - m0) / (2 * h) + t.cross(n1);
    worst_balance = std::max(worst_balance, balance.norm() / (moment() * helix.decay()));
    worst_envelope = std::max(worst_envelope, std::abs(1.0 - t.z() - helix.envelope(s)));
  }
  BOOST_TEST_MESSAGE("closed form: curvature " << worst_curvature << ", tangent " << worst_tangent
                                               << ", moment balance " << worst_balance
                                               << ", envelope " << worst_envelope);
  BOOST_TEST(worst_curvature <= 1e-7);  // central differences: O(h^2 kappa^2) = 1e-8
  BOOST_TEST(worst_tangent <= 1e-7);
  BOOST_TEST(worst_balance <= 1e-7);
  BOOST_TEST(worst_envelope <= 1e-12);
}

BOOST_AUTO_TEST_CASE(rejects_a_moment_beyond_the_stability_limit) {
  BOOST_CHECK_THROW(ref::LocalisedHelix(1.0, 1.0, 1.0, 2.0, 1.0), std::invalid_argument);
  BOOST_CHECK_THROW(ref::LocalisedHelix(1.0, 1.0, -1.0, 0.5, 1.0), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(rkmk_rk4_between_its_end_poses_converges_to_it) {
  const ref::LocalisedHelix helix(kB, kC, tension(), moment(), kL);
  // the unit rod: a circle section whose E I = 1 and G J = 2/3
  const double D = 0.1, I = 3.141592653589793 * std::pow(D, 4) / 64.0;
  const rodlab::rod::RodModel model(kL, rodlab::rod::Circle{D},
                                    rodlab::rod::Material{1.0 / I, 1.0 / (3.0 * I), 1.0, 0.0},
                                    rodlab::rod::ModelKind::kirchhoff);
  BOOST_TEST(std::abs(model.K_diag()[0] - kB) <= 1e-12);
  BOOST_TEST(std::abs(model.K_diag()[2] - kC) <= 1e-12);
  const int nodes = 401;
  const auto [r, s, exact] = rodlab::validation::solve_localised_helix(model, helix, nodes);
  BOOST_REQUIRE_MESSAGE(r.converged, r.reason);
  double worst = 0.0;
  for (int i = 0; i < nodes; ++i)
    worst = std::max(
        worst, (r.centerline[i].pose.translation() - exact[i].pose.translation()).norm());
  BOOST_TEST_MESSAGE("rkmk-rk4 N = 401: centreline within " << worst << " L, " << r.iterations
                                                            << " iterations");
  BOOST_TEST(worst <= 1e-6);
  // the base wrench: the closed form's, not the 1 % guess
  BOOST_TEST((r.base_wrench - exact.front().wrench).norm() <= 1e-5 * exact.front().wrench.norm());
}
