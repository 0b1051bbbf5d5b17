#define BOOST_TEST_MODULE energies
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "rodlab/rod/energies.hpp"

using namespace rodlab;
using namespace rodlab::rod;
namespace tt = boost::test_tools;

namespace {
const Material kTable21{1e6, 0.33e6, 1000.0, 0.0};
RodModel table21() { return {0.1, Circle{0.01}, kTable21}; }
}  // namespace

// Reference: pure bending with constant curvature kappa stores U = 1/2 E I kappa^2 L (2.28).
BOOST_AUTO_TEST_CASE(strain_energy_of_pure_bending) {
  const auto m = table21();
  const double kappa = 2 * std::numbers::pi / m.length();
  Vector6 xi = m.xi_star();
  xi[0] = kappa;
  const double EI = m.K_diag()[0];
  std::vector<double> density(11, strain_energy_density(m, xi));
  BOOST_TEST(integrate_trapezoid(density, m.length() / 10) == 0.5 * EI * kappa * kappa * m.length(),
             tt::tolerance(1e-14));
  BOOST_TEST(strain_energy_density(m, m.xi_star()) == 0.0);
  // Extension by 1 %: 1/2 E A 0.01^2 per unit length.
  xi = m.xi_star();
  xi[5] = 1.01;
  BOOST_TEST(strain_energy_density(m, xi) == 0.5 * m.K_diag()[5] * 1e-4, tt::tolerance(1e-12));
}

// Reference: rigid translation at speed v: T = 1/2 rho A v^2 per length; spin about the axis:
// 1/2 rho J psi^2 (3.5).
BOOST_AUTO_TEST_CASE(kinetic_energy_density_closed_form) {
  const auto m = table21();
  Vector6 eta = Vector6::Zero();
  eta[3] = 2.0;
  BOOST_TEST(kinetic_energy_density(m, eta) == 0.5 * m.mass_per_length() * 4.0, tt::tolerance(1e-15));
  eta.setZero();
  eta[2] = 3.0;
  BOOST_TEST(kinetic_energy_density(m, eta) == 0.5 * 1000 * m.properties().J * 9.0, tt::tolerance(1e-15));
}

// Reference: lowering a rod of mass rho A per length by h along gravity releases rho A |g| h;
// buoyancy replaces rho by rho - rho_fluid (2.36); zero at the reference configuration.
BOOST_AUTO_TEST_CASE(gravity_energy_density_and_buoyancy) {
  const auto m = table21();
  const Vector3 g(-9.81, 0, 0), p_ref(0, 0, 0.05);
  BOOST_TEST(gravity_energy_density(m, g, p_ref, p_ref) == 0.0);
  const Vector3 lowered = p_ref + Vector3(-0.01, 0, 0);
  BOOST_TEST(gravity_energy_density(m, g, lowered, p_ref) == -m.mass_per_length() * 9.81 * 0.01,
             tt::tolerance(1e-14));
  BOOST_TEST(gravity_energy_density(m, g, lowered, p_ref, 1000.0) == 0.0);  // neutrally buoyant
}

// Reference: Kelvin-Voigt dissipation rate xi_dot^T V xi_dot.
BOOST_AUTO_TEST_CASE(viscous_power) {
  const RodModel m(0.1, Circle{0.01}, Material{1e6, 0.33e6, 1000.0, 300.0});
  Vector6 rate = Vector6::Zero();
  rate[0] = 0.5;
  BOOST_TEST(viscous_power_density(m, rate) == 3 * 300 * m.properties().Ix * 0.25, tt::tolerance(1e-15));
}

// Reference: the trapezoidal rule is exact for linear integrands.
BOOST_AUTO_TEST_CASE(trapezoid_exact_for_linear) {
  std::vector<double> f;
  for (int i = 0; i <= 8; ++i) f.push_back(1.0 + 2.0 * i * 0.125);
  BOOST_TEST(integrate_trapezoid(f, 0.125) == 2.0, tt::tolerance(1e-15));
  const std::vector<double> one{1.0};
  BOOST_CHECK_THROW(integrate_trapezoid(one, 0.1), std::invalid_argument);
}

// Reference: constant xi* = [kappa 0 0 0 0 1] is a circular arc in the y-z plane,
// p(s) = (0, (cos(kappa s) - 1)/kappa, sin(kappa s)/kappa), R(s) = rotation about x by kappa s.
BOOST_AUTO_TEST_CASE(reference_pose_of_precurved_rod) {
  const double kappa = 5.0;
  const RodModel m(0.3, Circle{0.01}, kTable21, ModelKind::cosserat,
                   (Vector6() << kappa, 0, 0, 0, 0, 1).finished());
  for (double s : {0.0, 0.1, 0.2, 0.3}) {
    const auto g = reference_pose(m, lie::SE3::identity(), s);
    const Vector3 expected(0, (std::cos(kappa * s) - 1) / kappa, std::sin(kappa * s) / kappa);
    BOOST_TEST((g.translation() - expected).norm() < 1e-15);
    const Eigen::Matrix3d R = Eigen::AngleAxisd(kappa * s, Vector3::UnitX()).toRotationMatrix();
    BOOST_TEST((g.rotation_matrix() - R).norm() < 1e-15);
  }
}
