#define BOOST_TEST_MODULE dynamics_segment_linearisation
#include <boost/test/unit_test.hpp>

// The linearisation of the semi-discrete rod's segment and node relations (docs/dynamics.md,
// "The analytic Jacobian of the semi-discrete rod"; issue #17 item 3), checked against central
// differences of the relations themselves, built from the lie kernels:
//   G = g_a^-1 g_b, x = log G, rel = eta_b - Ad_{G^-1} eta_a, xi_dot = dexp^-1_{-x} rel / ds,
//   sigma = K (x / ds - xi*) + V xi_dot, lambda = dexp^-T_x sigma, mu = Ad_G^T lambda,
// and the node's ad_eta^T M eta, gravity R^T g and p_dot = R kappa, under right perturbations
// g -> g exp(eps). Reference: central differences (step 1e-6, error ~1e-10 relative); the
// derivation truncates the derivative of dexp^-1 after its ad^2 term (the next is
// 4 |y|^3 / 720 against 1/2), so the tolerance is 2e-5 relative at segment angles of 0.05 rad
// per component (the scenes' ds |kappa|; measured 1e-8 .. 8e-6) and grows as angle^3.
// This pins the signs and conventions the analytic Jacobian is to be built on.
#include <array>
#include <random>

#include "rodlab/lie/se3.hpp"
#include "rodlab/lie/so3.hpp"

namespace {

using namespace rodlab::lie;
using Vector24 = Eigen::Matrix<double, 24, 1>;

constexpr double kDs = 0.01;

// The linearisation's kernels are the library's (se3.hpp): coad_matrix, dexp_inv_derivative and
// dexp_inv_transpose_derivative, the ones the analytic Jacobian (semi_discrete_jacobian.cpp) uses.
Matrix6 S(const Vector6& s) { return se3::coad_matrix(s); }
Matrix6 dT(const Vector6& y, const Vector6& r) { return se3::dexp_inv_derivative(y, r); }
Matrix6 dT_transpose(const Vector6& x, const Vector6& s) {
  return se3::dexp_inv_transpose_derivative(x, s);
}

struct Segment {
  Vector6 K, V, xi_star;
  Vector6 x, xi_dot, lambda, mu;
};

/// The segment relations at G, eta_a, eta_b.
Segment evaluate(const Segment& law, const SE3& G, const Vector6& eta_a, const Vector6& eta_b) {
  Segment s = law;
  s.x = G.log();
  const Vector6 rel = eta_b - G.inverse().Ad() * eta_a;
  s.xi_dot = se3::dexp_inv(-s.x) * rel / kDs;
  const Vector6 sigma = law.K.cwiseProduct(s.x / kDs - law.xi_star) + law.V.cwiseProduct(s.xi_dot);
  s.lambda = se3::dexp_inv(s.x).transpose() * sigma;
  s.mu = G.Ad().transpose() * s.lambda;
  return s;
}

/// The relations at the perturbation d = [eps_a; eps_b; deta_a; deta_b] (right perturbations).
Segment perturbed(const Segment& law, const SE3& G, const Vector6& eta_a, const Vector6& eta_b,
                  const Vector24& d) {
  const SE3 Gd = SE3::exp(-d.segment<6>(0)) * G * SE3::exp(d.segment<6>(6));
  return evaluate(law, Gd, eta_a + d.segment<6>(12), eta_b + d.segment<6>(18));
}

/// The linearisation (docs/dynamics.md): d x, d xi_dot, d lambda, d mu as 6 x 24 blocks.
std::array<Eigen::Matrix<double, 6, 24>, 4> linearisation(const Segment& s, const SE3& G,
                                                          const Vector6& eta_a,
                                                          const Vector6& eta_b) {
  const Matrix6 Ad_inv = G.inverse().Ad();
  // phi = eps_b - Ad_{G^-1} eps_a
  Eigen::Matrix<double, 6, 24> phi = Eigen::Matrix<double, 6, 24>::Zero();
  phi.block<6, 6>(0, 0) = -Ad_inv;
  phi.block<6, 6>(0, 6).setIdentity();
  const Vector6 a = Ad_inv * eta_a;
  const Vector6 rel = eta_b - a;
  const Eigen::Matrix<double, 6, 24> dx = se3::dexp_inv(-s.x) * phi;
  Eigen::Matrix<double, 6, 24> drel = -se3::ad(a) * phi;
  drel.block<6, 6>(0, 12) -= Ad_inv;
  drel.block<6, 6>(0, 18) += Matrix6::Identity();
  // d/dx of dexp^-1_{-x} rel is -DT(-x)[dx] rel.
  const Eigen::Matrix<double, 6, 24> dxi_dot =
      (se3::dexp_inv(-s.x) * drel - dT(-s.x, rel) * dx) / kDs;
  const Vector6 sigma = s.K.cwiseProduct(s.x / kDs - s.xi_star) + s.V.cwiseProduct(s.xi_dot);
  const Eigen::Matrix<double, 6, 24> dsigma =
      s.K.asDiagonal() * dx / kDs + s.V.asDiagonal() * dxi_dot;
  const Eigen::Matrix<double, 6, 24> dlambda =
      se3::dexp_inv(s.x).transpose() * dsigma + dT_transpose(s.x, sigma) * dx;
  const Eigen::Matrix<double, 6, 24> dmu = G.Ad().transpose() * dlambda + S(s.mu) * phi;
  return {dx, dxi_dot, dlambda, dmu};
}

/// max over the 24 directions of |L e_i - FD_i| / (|FD_i| + floor), per output.
std::array<double, 4> worst_relative_error(double angle, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  auto random6 = [&](double ang, double lin) {
    Vector6 v;
    for (int i = 0; i < 6; ++i) v[i] = n(rng) * (i < 3 ? ang : lin);
    return v;
  };
  Segment law;
  law.K << 2.0, 2.0, 1.5, 40.0, 40.0, 80.0;
  law.V = 0.3 * law.K;
  law.xi_star << 0, 0, 0, 0, 0, 1;
  Vector6 x0 = random6(angle / std::sqrt(3.0), 0.05 * kDs);
  x0[5] += kDs;  // stretch about 1
  const SE3 G = SE3::exp(x0);
  const Vector6 eta_a = random6(1.0, 0.1), eta_b = random6(1.0, 0.1);
  const Segment s0 = evaluate(law, G, eta_a, eta_b);
  const auto L = linearisation(s0, G, eta_a, eta_b);
  std::array<double, 4> worst{};
  constexpr double h = 1e-6;
  for (int i = 0; i < 24; ++i) {
    Vector24 d = Vector24::Zero();
    d[i] = h;
    const Segment p = perturbed(law, G, eta_a, eta_b, d), m = perturbed(law, G, eta_a, eta_b, -d);
    const std::array<Vector6, 4> fd = {(p.x - m.x) / (2 * h), (p.xi_dot - m.xi_dot) / (2 * h),
                                       (p.lambda - m.lambda) / (2 * h), (p.mu - m.mu) / (2 * h)};
    for (int o = 0; o < 4; ++o) {
      const double floor = 1e-3 * L[o].norm();  // columns that vanish
      worst[o] = std::max(worst[o], (L[o].col(i) - fd[o]).norm() / (fd[o].norm() + floor));
    }
  }
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_CASE(segment_relations_at_the_scenes_angles) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const auto worst = worst_relative_error(0.05, seed);
    BOOST_TEST_MESSAGE("angle 0.05, seed " << seed << ": x " << worst[0] << ", xi_dot "
                                           << worst[1] << ", lambda " << worst[2] << ", mu "
                                           << worst[3]);
    BOOST_TEST(worst[0] < 1e-10);  // dx = dexp^-1_{-x} phi is exact
    for (double w : worst) BOOST_TEST(w < 2e-5);
  }
}

BOOST_AUTO_TEST_CASE(the_truncation_grows_as_the_angle_cubed) {
  // At 0.3 rad (coarse grids, large curvature) the ad^2 truncation of DT shows: still a good
  // Newton matrix (1.2e-4 measured), and the growth as the cube of the angle (x 224 for x 6)
  // confirms that the rest of the linearisation is exact.
  const auto small = worst_relative_error(0.05, 7), large = worst_relative_error(0.3, 7);
  BOOST_TEST_MESSAGE("xi_dot: " << small[1] << " at 0.05 rad, " << large[1] << " at 0.3 rad");
  BOOST_TEST(large[1] < 1e-3);
  BOOST_TEST(large[1] / small[1] > 0.5 * 216.0);  // (0.3 / 0.05)^3
}

BOOST_AUTO_TEST_CASE(node_relations) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  Vector6 eta, M;
  for (int i = 0; i < 6; ++i) eta[i] = n(rng), M[i] = 0.5 + std::abs(n(rng));
  const Vector3 g_world(-9.81, 0.3, 0.1);
  const SO3 R = SO3::exp(Vector3(0.3, -0.2, 0.5));
  // d(ad_eta^T M eta) = S(M eta) deta + ad_eta^T M deta
  const Matrix6 predicted = S(M.cwiseProduct(eta)) + se3::ad(eta).transpose() * M.asDiagonal();
  // gravity R^T g and p_dot = R kappa under R -> R exp(dtheta)
  const Matrix3 d_gravity = so3::hat(R.inverse() * g_world);
  const Matrix3 d_pdot = -R.matrix() * so3::hat(eta.tail<3>());
  constexpr double h = 1e-6;
  double worst = 0.0;
  for (int i = 0; i < 6; ++i) {
    const Vector6 d = h * Vector6::Unit(i);
    auto f = [&](const Vector6& e) { return se3::coad_apply(e, M.cwiseProduct(e)); };
    const Vector6 fd = (f(eta + d) - f(eta - d)) / (2 * h);
    worst = std::max(worst, (predicted.col(i) - fd).norm() / fd.norm());
  }
  for (int i = 0; i < 3; ++i) {
    const Vector3 d = h * Vector3::Unit(i);
    const SO3 Rp = R * SO3::exp(d), Rm = R * SO3::exp(-d);
    const Vector3 fd_g = (Rp.inverse() * g_world - Rm.inverse() * g_world) / (2 * h);
    const Vector3 kappa = eta.tail<3>();
    const Vector3 fd_p = (Rp * kappa - Rm * kappa) / (2 * h);
    worst = std::max(worst, (d_gravity.col(i) - fd_g).norm() / fd_g.norm());
    worst = std::max(worst, (d_pdot.col(i) - fd_p).norm() / fd_p.norm());
  }
  BOOST_TEST_MESSAGE("node relations: worst relative error " << worst);
  BOOST_TEST(worst < 1e-8);
}
