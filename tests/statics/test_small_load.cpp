#define BOOST_TEST_MODULE statics_small_load
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "schemes_under_test.hpp"
#include "statics_support.hpp"

// Case 4: the small-load (linear) limit of the Table 2.1 cantilever (rod along +z, clamped at the
// origin), against Timoshenko beam theory with shear coefficient 1, which is what the model's
// K = diag(EI, EI, GJ, GA, GA, EA) (2.28) encodes. References (Timoshenko & Gere, Mechanics of
// Materials; Timoshenko & Goodier for the shear term):
//
//   tip force P (world frame, along +x):   x_tip = P L^3/(3 EI) + P L/(GA),  angle_y = P L^2/(2 EI)
//   uniform load q along -x (gravity):     x_tip = -(q L^4/(8 EI) + q L^2/(2 GA)),
//                                          angle_y = -q L^3/(6 EI)
//   axial tip force F (world, along +z):   z_tip = L (1 + F/EA)  (exact: the rod stays straight)
//
// Derivation of the shear terms: the shear strain nu_x = V(s)/GA integrates to
// int_0^L V/GA ds with V = P (tip force) or V = q (L - s) (uniform load). The bending terms are
// the Euler-Bernoulli cantilever formulas; rotations are small so angle_y = int M/EI ds. Kirchhoff
// rods have no shear or extension: drop the GA and EA terms.
//
// The loads are PL^2/EI = 1e-4 and qL^3/EI = 1e-4: the nonlinear corrections are relative
// O((PL^2/EI)^2) = 1e-8 (measured: rkmk-rk4 differs from the linear formula by 1.46e-10 relative
// for the tip force, at every N). The shear term is 0.57 % of the tip deflection
// (3 EI/(GA L^2) = 5.7e-3), so the 1e-3 tolerance checks it.
//
// Each scheme runs at a grid fine enough that its discretisation error (measured: order 1
// about 0.75/(N-1) relative for the tip force and 2.7/(N-1) for the uniform load; order 2
// 0.25/(N-1)^2 and 1.0/(N-1)^2; rkmk-rk4 and the implicit midpoint rule are exact for the
// uniform load's quartic deflection) is below 1e-4: nodes_for(C = 3, 1e-4), i.e. N = 30001 for
// order 1, 175 for order 2, 15 for order 4.

namespace {

using namespace rodlab;
using namespace rodlab::testing::statics;
using rod::ModelKind;
using loads::WrenchFrame;

constexpr double kLinearTol = 1e-3;  // relative, as required by the validation plan
constexpr double kLoad = 1e-4;       // P L^2/EI and q L^3/EI

int fine_nodes(const SchemeUnderTest& s) { return nodes_for(s, 3.0, 1e-4, 11, 40001); }

/// Rotation angle about y of a rotation that is (to rounding) about y.
double angle_y(const SE3& g) {
  const Matrix3 R = g.rotation_matrix();
  return std::atan2(R(0, 2), R(2, 2));
}

}  // namespace

/// The tip deflection x and rotation about y against their linear (Timoshenko) references,
/// both within kLinearTol relative; returns the tip pose for further checks.
const SE3& check_linear_tip(const StaticResult& r, ModelKind kind, double x_ref, double angle_ref,
                            const char* label) {
  const SE3& tip = r.centerline.back().pose;
  const double ex = tip.translation().x() / x_ref - 1.0, ea = angle_y(tip) / angle_ref - 1.0;
  BOOST_TEST(std::abs(ex) <= kLinearTol, kind_name(kind) << " " << describe(r) << ": x_tip " << tip.translation().x()
                                                        << ", Timoshenko " << x_ref << ", rel err " << ex);
  BOOST_TEST(std::abs(ea) <= kLinearTol, kind_name(kind) << " " << describe(r) << ": angle rel err " << ea);
  BOOST_TEST_MESSAGE(label << " " << kind_name(kind) << " " << describe(r) << ": x_tip rel err " << ex
                           << ", angle rel err " << ea);
  return tip;
}

BOOST_AUTO_TEST_CASE(tip_force_timoshenko) {
  const double L = Table21::L, EI = Table21::EI, GA = Table21::GA;
  const double P = kLoad * EI / (L * L);
  for (const ModelKind kind : {ModelKind::cosserat, ModelKind::kirchhoff}) {
    const double shear = kind == ModelKind::kirchhoff ? 0.0 : P * L / GA;
    const double x_ref = P * L * L * L / (3.0 * EI) + shear;
    const double angle_ref = P * L * L / (2.0 * EI);
    const auto problem = tip_wrench_problem(kind, wrench(Vector3::Zero(), Vector3(P, 0, 0)), WrenchFrame::world);
    for (const auto& s : statics_schemes_under_test()) {
      const int N = fine_nodes(s);
      const auto r = solve(problem, s.name, N);
      if (!check_result(r, N)) continue;
      const SE3& tip = check_linear_tip(r, kind, x_ref, angle_ref, "tip force");
      BOOST_TEST(std::abs(tip.translation().y()) <= 1e-12 * L);
    }
  }
  // The shear term is resolved: without it the Cosserat deflection would be 0.57 % off.
  BOOST_TEST(3.0 * EI / (GA * L * L) > 5.0 * kLinearTol);
}

BOOST_AUTO_TEST_CASE(uniform_load_timoshenko) {
  const double L = Table21::L, EI = Table21::EI, GA = Table21::GA;
  const double q = kLoad * EI / (L * L * L);           // weight per length
  const double g = q / (Table21::rho * Table21::A);     // 6.25e-4 m/s^2
  for (const ModelKind kind : {ModelKind::cosserat, ModelKind::kirchhoff}) {
    const double shear = kind == ModelKind::kirchhoff ? 0.0 : q * L * L / (2.0 * GA);
    const double x_ref = -(q * L * L * L * L / (8.0 * EI) + shear);
    const double angle_ref = -q * L * L * L / (6.0 * EI);
    const auto problem = gravity_cantilever(kind, Vector3(-g, 0, 0));
    for (const auto& s : statics_schemes_under_test()) {
      const int N = fine_nodes(s);
      const auto r = solve(problem, s.name, N);
      if (!check_result(r, N)) continue;
      check_linear_tip(r, kind, x_ref, angle_ref, "uniform load");
    }
  }
}

// Axial tip force, world frame along +z: the rod stays straight (every force is along the
// tangent), nu_z = 1 + F/EA exactly, z_tip = L (1 + F/EA); Kirchhoff: z_tip = L. Exact for every
// scheme (constant strain), so checked to 1e-12 at modest N. F/EA = 0.01 (tension; a compressive
// 0.785 N would exceed the Euler buckling load pi^2 EI/(4 L^2) = 0.121 N).
BOOST_AUTO_TEST_CASE(axial_tip_force) {
  const double L = Table21::L, F = 0.01 * Table21::EA;
  for (const ModelKind kind : {ModelKind::cosserat, ModelKind::kirchhoff}) {
    const double z_ref = kind == ModelKind::kirchhoff ? L : L * (1.0 + F / Table21::EA);
    const auto problem = tip_wrench_problem(kind, wrench(Vector3::Zero(), Vector3(0, 0, F)), WrenchFrame::world);
    for (const auto& s : statics_schemes_under_test()) {
      for (const int N : {5, 50}) {
        const auto r = solve(problem, s.name, N);
        if (!check_result(r, N)) continue;
        const SE3& tip = r.centerline.back().pose;
        BOOST_TEST(std::abs(tip.translation().z() - z_ref) <= 1e-12 * L,
                   kind_name(kind) << " " << describe(r) << ": z_tip - ref = " << tip.translation().z() - z_ref);
        BOOST_TEST(tip.translation().head<2>().norm() <= 1e-12 * L);
        BOOST_TEST(rotation_distance(tip.rotation_matrix(), Matrix3::Identity()) <= 1e-12);
        BOOST_TEST(std::abs(r.base_wrench[5] - F) <= 1e-12 * F);
      }
    }
  }
}
