#include "rodlab/solvers/dynamics/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "rodlab/rod/characteristics.hpp"
#include "rodlab/solvers/schemes.hpp"

namespace rodlab::solvers::dynamics {
namespace {

using Matrix6c = Eigen::Matrix<std::complex<double>, 6, 6>;
/// Wave numbers sampled in [0, pi] (omega(k) is smooth; the maximum sits at k = pi or inside).
constexpr int kWaveNumbers = 256;
/// Steps per first bending period for the implicit schemes' automatic step. implicit-midpoint
/// (explicit Euler in s) has a lower step bound (thesis 3.4: 0.04 s at N = 20); measured on the
/// viscous cantilever at N = 20 over 10 s: dt = 0.05 and 0.02 s run, 0.01 s gains energy and
/// 5.7 ms fails after 6 s. 10 steps per period (22.6 ms there) stays above it.
constexpr double kStepsPerPeriod = 10.0;

}  // namespace

namespace {

/// max over k of eig(S(k)) / ds with S(k) = W C^H D^T K D C W^H / ds (see the header), where
/// W W^H = M^-1 (W = M^-1/2 for a diagonal M, the inverse Cholesky factor otherwise).
template <class Whiten>
double max_frequency(const lie::Matrix6& K, const Vector6& xi_star, double ds, Whiten whiten) {
  const lie::Matrix6 A = SE3::exp(ds * xi_star).inverse().Ad();
  const lie::Matrix6 D = lie::se3::dexp_inv(-ds * xi_star);
  const lie::Matrix6 KD = K * D;
  const lie::Matrix6 DtKD = D.transpose() * KD;
  double omega2 = 0.0;
  for (int i = 0; i <= kWaveNumbers; ++i) {
    const double k = std::numbers::pi * i / kWaveNumbers;
    const Matrix6c C = std::polar(1.0, k) * Matrix6c::Identity() - A.cast<std::complex<double>>();
    const Matrix6c S = whiten(Matrix6c(C.adjoint() * DtKD.cast<std::complex<double>>() * C / ds));
    const Eigen::SelfAdjointEigenSolver<Matrix6c> eig(S, Eigen::EigenvaluesOnly);
    omega2 = std::max(omega2, eig.eigenvalues().maxCoeff() / ds);
  }
  return std::sqrt(omega2);
}

}  // namespace

double variational_max_frequency(const rod::RodModel& model, int nodes) {
  if (nodes < 2) throw std::invalid_argument("nodes must be >= 2");
  const double ds = model.length() / (nodes - 1);
  const Vector6 m_inv_sqrt = model.M_diag().cwiseSqrt().cwiseInverse();
  double omega = 0.0;  // the largest over the rest-strain spans (one for a uniform rod)
  for (const auto& span : model.rest_spans())
    omega = std::max(omega, max_frequency(model.K(), span.xi_star, ds, [&](const Matrix6c& S) {
                       return Matrix6c(m_inv_sqrt.asDiagonal() * S * m_inv_sqrt.asDiagonal());
                     }));
  return omega;
}

double variational_max_frequency(const DynamicProblem& problem, int nodes) {
  if (!problem.has_muscles()) return variational_max_frequency(problem.model(), nodes);
  if (nodes < 2) throw std::invalid_argument("nodes must be >= 2");
  // With muscles the section is a composite (DynamicProblem::embedded_stiffness, node_inertia):
  // the largest over the grid's distinct (K, M) pairs, K at the segment midpoints and M of the
  // node cells on both sides.
  const auto& model = problem.model();
  const double ds = model.length() / (nodes - 1);
  const auto M = problem.node_inertia(nodes);
  double omega = 0.0;
  lie::Matrix6 K_last, M_last;
  Vector6 xs_last;
  for (int j = 0; j + 1 < nodes; ++j) {
    const lie::Matrix6 K = model.K() + problem.embedded_stiffness((j + 0.5) * ds);
    const Vector6& xs = model.xi_star((j + 0.5) * ds);  // the segment's span
    for (const lie::Matrix6& Mj : {M[j], M[j + 1]}) {
      if (j > 0 && K == K_last && Mj == M_last && xs == xs_last) continue;
      K_last = K;
      M_last = Mj;
      xs_last = xs;
      // W = L^-1 for M = L L^T: W S W^H has the eigenvalues of M^-1 S.
      const lie::Matrix6 W = Mj.llt().matrixL().solve(lie::Matrix6::Identity());
      const Matrix6c Wc = W.cast<std::complex<double>>();
      omega = std::max(omega, max_frequency(K, xs, ds, [&](const Matrix6c& S) {
                         return Matrix6c(Wc * S * Wc.adjoint());
                       }));
    }
  }
  return omega;
}

double variational_stable_step(const DynamicProblem& problem, int nodes) {
  const auto& model = problem.model();
  const double omega = variational_max_frequency(problem, nodes);
  double tau = 0.0;  // Kelvin-Voigt relaxation time, the largest over the components
  for (int i = 0; i < 6; ++i) tau = std::max(tau, model.V_diag()[i] / model.K_diag()[i]);
  for (const auto& a : problem.actuators())  // the muscles' own
    if (a.embedded)
      for (int i = 0; i < 6; ++i) tau = std::max(tau, a.embedded->V[i] / a.embedded->K[i]);
  // (3.11) laminar drag rate, the largest over the components (at a velocity small enough that
  // the turbulent part, quadratic in it, vanishes)
  constexpr double kSmall = 1e-9;
  double drag = 0.0;
  for (int i = 0; i < 6; ++i) {
    const double rate = -problem.drag_load(kSmall * Vector6::Unit(i))[i] / (kSmall * model.M_diag()[i]);
    drag = std::max(drag, rate);
  }
  // omega^2 dt^2 + 2 b dt - 4 = 0 with b = tau omega^2 + drag, positive root.
  const double b = tau * omega * omega + drag;
  return 4.0 / (b + std::sqrt(b * b + 4.0 * omega * omega));
}

double auto_time_step(const DynamicProblem& problem, std::string_view scheme, int nodes) {
  const auto info = find_scheme(scheme);
  if (info && info->id == SchemeId::variational)
    return kVariationalSafety * variational_stable_step(problem, nodes);
  const auto support = problem.tip_clamped() ? rod::TipSupport::clamped : rod::TipSupport::free;
  const auto c = rod::characteristics(problem.model(), nodes, support);
  return 1.0 / (c.first_bending_frequency_hz * kStepsPerPeriod);
}

}  // namespace rodlab::solvers::dynamics
