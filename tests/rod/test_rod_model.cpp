#define BOOST_TEST_MODULE rod_model
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "rodlab/rod/rod_model.hpp"

using namespace rodlab::rod;
using std::numbers::pi;
namespace tt = boost::test_tools;

namespace {
// Thesis Table 2.1: E = 1 MPa, G = 0.33 MPa, rho = 1000 kg/m^3, D = 1 cm, L = 10 cm.
const Material kTable21{1e6, 0.33e6, 1000.0, 300.0};
RodModel table21(ModelKind kind = ModelKind::cosserat) { return {0.1, Circle{0.01}, kTable21, kind}; }
}  // namespace

// Reference: K = diag(E Ix, E Iy, G J, G A, G A, E A) (2.28), M = rho diag(Ix, Iy, J, A, A, A)
// (3.5), V = alpha diag(3 Ix, 3 Iy, J, A, A, 3 A) (3.10), all in closed form for a circle.
BOOST_AUTO_TEST_CASE(stiffness_inertia_viscosity_matrices) {
  const auto m = table21();
  const double D = 0.01, A = pi * D * D / 4, I = pi * std::pow(D, 4) / 64, J = 2 * I;
  const double E = 1e6, G = 0.33e6, rho = 1000, alpha = 300;
  const double K[6] = {E * I, E * I, G * J, G * A, G * A, E * A};
  const double M[6] = {rho * I, rho * I, rho * J, rho * A, rho * A, rho * A};
  const double V[6] = {3 * alpha * I, 3 * alpha * I, alpha * J, alpha * A, alpha * A, 3 * alpha * A};
  for (int i = 0; i < 6; ++i) {
    BOOST_TEST(m.K_diag()[i] == K[i], tt::tolerance(1e-14));
    BOOST_TEST(m.M_diag()[i] == M[i], tt::tolerance(1e-14));
    BOOST_TEST(m.V_diag()[i] == V[i], tt::tolerance(1e-14));
    BOOST_TEST(m.K_inv_diag()[i] * K[i] == 1.0, tt::tolerance(1e-15));
  }
  BOOST_TEST((m.K() - m.K_diag().asDiagonal().toDenseMatrix()).norm() == 0.0);
  BOOST_TEST(m.mass_per_length() == rho * A, tt::tolerance(1e-15));
  BOOST_TEST((m.xi_star() - RodModel::straight_twist()).norm() == 0.0);
  BOOST_TEST(!m.is_kirchhoff());
  BOOST_TEST(table21(ModelKind::kirchhoff).is_kirchhoff());
}

// Reference: the torsion entry uses the Saint-Venant constant (not the polar moment) for
// non-circular sections, and the inertia entry the polar moment (3.4).
BOOST_AUTO_TEST_CASE(rectangle_uses_torsion_constant_for_stiffness_only) {
  const RodModel m(0.1, Rectangle{0.01, 0.01}, kTable21);
  BOOST_TEST(m.K_diag()[2] == 0.33e6 * m.properties().Jt, tt::tolerance(1e-14));
  BOOST_TEST(m.M_diag()[2] == 1000 * m.properties().J, tt::tolerance(1e-14));
  BOOST_TEST(m.K_diag()[2] < 0.33e6 * m.properties().J);
}

// Reference: isotropic elasticity G = E / (2 (1 + poisson)).
BOOST_AUTO_TEST_CASE(material_from_poisson) {
  const auto mat = Material::from_poisson(2e6, 0.5, 1100);
  BOOST_TEST(mat.G == 2e6 / 3.0, tt::tolerance(1e-15));
  BOOST_TEST(mat.poisson() == 0.5, tt::tolerance(1e-14));
  BOOST_CHECK_THROW(Material::from_poisson(1e6, 0.6, 1000), std::invalid_argument);
  BOOST_CHECK_THROW(Material::from_poisson(1e6, -1.0, 1000), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(bad_models_throw) {
  BOOST_CHECK_THROW(RodModel(0.0, Circle{0.01}, kTable21), std::invalid_argument);
  BOOST_CHECK_THROW(RodModel(-0.1, Circle{0.01}, kTable21), std::invalid_argument);
  BOOST_CHECK_THROW(RodModel(0.1, Circle{0.01}, Material{-1, 1, 1, 0}), std::invalid_argument);
  BOOST_CHECK_THROW(RodModel(0.1, Circle{0.01}, Material{1, 0, 1, 0}), std::invalid_argument);
  BOOST_CHECK_THROW(RodModel(0.1, Circle{0.01}, Material{1, 1, 0, 0}), std::invalid_argument);
  BOOST_CHECK_THROW(RodModel(0.1, Circle{0.01}, Material{1, 1, 1, -1}), std::invalid_argument);
  const Vector6 no_centreline = (Vector6() << 1, 0, 0, 0, 0, 0).finished();
  BOOST_CHECK_THROW(RodModel(0.1, Circle{0.01}, kTable21, ModelKind::cosserat, no_centreline),
                    std::invalid_argument);
}
