// The analytic Newton matrix a I - b df/dy of the semi-discrete rod (semi_discrete_rod.hpp):
// the linearisation derived in docs/dynamics.md, "The analytic Jacobian of the semi-discrete
// rod", with right pose perturbations g_j -> g_j exp(eps_j), eps = [dtheta; dp_body], mapped to
// the raw unknowns (p world, q unnormalised) at the end. Per segment j (nodes a = j, b = j + 1):
//   phi = eps_b - Ad_{G^-1} eps_a,  dx = dexp^-1_{-x} phi                      (x = ds xi_j)
//   drel = deta_b - Ad_{G^-1} deta_a - ad_{a'} phi,  a' = Ad_{G^-1} eta_a
//   d(xi_dot) = (dexp^-1_{-x} drel - DT(-x)[dx] rel) / ds
//   dsigma = (K + dA/dxi) dx / ds + V d(xi_dot)       (A: the actuators' F_k c_k(xi), (3.10))
//   dlambda = dexp^-T_x dsigma + (DT(x)[dx])^T sigma                              (3.40)
//   d(Ad_G^T lambda) = Ad_G^T dlambda + S(Ad_G^T lambda) phi
// with DT the derivative of T(y) = dexp^-1_y to its ad^2 term (a relative truncation that grows
// as the cube of the segment angle ds |kappa|: 1e-8 .. 8e-6 at 0.05 rad, 1.2e-4 at 0.3 rad,
// tests/dynamics/test_segment_linearisation.cpp; a Newton matrix's accuracy, also on coarse grids
// of strongly bent rods, where modified Newton only converges a little slower). Per node:
// d(ad_eta^T M eta) = S(M eta) deta + ad_eta^T M deta, p_dot = R kappa, q_dot = q (x) [0; psi] / 2
// (linear in the raw q), and the external loads (gravity, distributed, drag, tip), small functions
// of (R, eta) differenced locally (central, per node). The matrix is exact but for those
// truncations: tests/dynamics/test_analytic_jacobian.cpp compares it with central differences
// of rhs(), entry by entry and load by load.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "rodlab/lie/small_angle.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"

namespace rodlab::solvers::dynamics {
namespace {

namespace se3 = lie::se3;
namespace so3 = lie::so3;
using lie::Matrix3;
using lie::Matrix6;
using Matrix67 = Eigen::Matrix<double, 6, 7>;
using Matrix13 = Eigen::Matrix<double, SemiDiscreteRod::kBlock, SemiDiscreteRod::kBlock>;

/// d eps / d(p world, q raw) of a node: [[0, Q], [R^T, 0]], Q = 2 [-v | w I - v^] / |q|^2 the
/// rotation dtheta = 2 vec(conj(q) (x) dq) / |q|^2 of a quaternion column.
Matrix67 pose_map(const double* b, const Matrix3& R) {
  const double w = b[SemiDiscreteRod::kQ];
  const Vector3 v(b[SemiDiscreteRod::kQ + 1], b[SemiDiscreteRod::kQ + 2],
                  b[SemiDiscreteRod::kQ + 3]);
  const double c = 2.0 / (w * w + v.squaredNorm());
  Matrix67 E = Matrix67::Zero();
  E.block<3, 1>(0, 3) = -c * v;
  E.block<3, 3>(0, 4) = c * (w * Matrix3::Identity() - so3::hat(v));
  E.block<3, 3>(3, 0) = R.transpose();
  return E;
}

}  // namespace

bool SemiDiscreteRod::analytic_jacobian() const {
  return !kirchhoff_ && m_ == 0 && !muscles_ && entries_.empty();
}

void SemiDiscreteRod::linearise_segment(int j, SegmentLinearisation& out) const {
  const SE3 G = g_[j].inverse_times(g_[j + 1]);
  const Vector6 x = ds_ * xi_[j];
  const Matrix6 Ad_inv = G.inverse().Ad(), coAd = G.Ad().transpose();
  const Matrix6 T_minus = se3::dexp_inv(-x), T_plus_T = se3::dexp_inv(x).transpose();
  const Vector6 a = Ad_inv * eta_[j];
  const Vector6 rel = eta_[j + 1] - a;
  const double s_mid = (j + 0.5) * ds_;
  const bool actuators = P_.has_actuators();
  // (3.10) without muscles (analytic_jacobian()): the rod's wrench and the actuators' A(xi)
  const Vector6 act = actuators ? Vector6(P_.actuator_wrench(xi_[j], s_mid, F_)) : Vector6::Zero();
  const Vector6 sigma = P_.rod_wrench(xi_[j], xi_dot_[j], s_mid) + act;
  // dA/dxi of the actuators' F_k c_k(xi), by central differences in xi.
  Matrix6 dA_dxi = Matrix6::Zero();
  if (actuators) {
    for (int i = 0; i < 6; ++i) {
      const double h = 1e-6 * std::max(std::abs(xi_[j][i]), i < 3 ? 1.0 / P_.length() : 1.0);
      Vector6 xp = xi_[j], xm = xi_[j];
      xp[i] += h;
      xm[i] -= h;
      dA_dxi.col(i) =
          (P_.actuator_wrench(xp, s_mid, F_) - P_.actuator_wrench(xm, s_mid, F_)) / (xp[i] - xm[i]);
    }
  }
  // The far node's inputs (kFarPose: phi = I, drel = -ad_a; kFarVelocity: phi = 0, drel = I).
  // The near node's are these times -Ad_{G^-1} (phi = -Ad_inv eps_a, drel = -(drel of eps_b)
  // Ad_inv for its pose; drel = -Ad_inv deta_a for its velocity): the relations are linear in
  // (phi, drel).
  const Vector6 V_xi_dot = V_.cwiseProduct(xi_dot_[j]);
  auto finish = [&](int in, const Matrix6& dx, const Matrix6& dxi_dot, const Matrix6& dsigma) {
    out.lambda[in] = T_plus_T * dsigma;
    if (in == kFarPose) out.lambda[in] += se3::dexp_inv_transpose_derivative(x, sigma) * dx;
    out.moved[in] = coAd * out.lambda[in];
    if (in == kFarPose) out.moved[in] += se3::coad_matrix(moved_[j]);
    // seg_diss = ds xi_dot^T V xi_dot; seg_work = -ds A(xi)^T xi_dot (actuator_power)
    out.diss[in] = 2.0 * ds_ * dxi_dot.transpose() * V_xi_dot;
    out.work[in].setZero();
    if (actuators)
      out.work[in] = -ds_ * (dxi_dot.transpose() * act) -
                     dx.transpose() * (dA_dxi.transpose() * xi_dot_[j]);
  };
  {  // the far pose: dx = T(-x), d(xi_dot) = (-T(-x) ad_a - DT(-x)[dx] rel) / ds
    const Matrix6 dxi_dot =
        -(T_minus * se3::ad(a) + se3::dexp_inv_derivative(-x, rel) * T_minus) / ds_;
    Matrix6 stiffness = dA_dxi;
    stiffness.diagonal() += P_.model().K_diag();
    finish(kFarPose, T_minus, dxi_dot, (stiffness * T_minus) / ds_ + V_.asDiagonal() * dxi_dot);
  }
  {  // the far velocity: dx = 0, d(xi_dot) = T(-x) / ds
    const Matrix6 dxi_dot = T_minus / ds_;
    finish(kFarVelocity, Matrix6::Zero(), dxi_dot, V_.asDiagonal() * dxi_dot);
  }
  for (int far : {kFarPose, kFarVelocity}) {
    const int near = far - 1;
    out.lambda[near] = -out.lambda[far] * Ad_inv;
    out.moved[near] = -out.moved[far] * Ad_inv;
    out.diss[near] = -Ad_inv.transpose() * out.diss[far];
    out.work[near] = -Ad_inv.transpose() * out.work[far];
  }
}

void SemiDiscreteRod::linearise_node(int j, double t, NodeLinearisation& out) const {
  const bool tip = j == n_ - 1;
  const double w = tip ? 0.5 * ds_ : ds_;
  const SO3& R = g_[j].rotation();
  const Vector6& eta = eta_[j];
  const Matrix6 M = full_inertia_ ? inertia_[j] : Matrix6(M_.asDiagonal());
  // d(ad_eta^T M eta) = S(M eta) deta + ad_eta^T M deta
  out.eta_velocity = se3::coad_matrix(M * eta) + se3::ad(eta).transpose() * M;
  // Loads of the pose (gravity, distributed, tip): central differences in dtheta.
  const Vector6 applied = P_.applied_load(R, t);
  const Vector6 tip_load = tip ? P_.tip_load(R, t) : Vector6::Zero();
  out.eta_pose.setZero();
  out.work_pose.setZero();
  constexpr double kAngle = 1e-5;
  for (int i = 0; i < 3; ++i) {
    const SO3 Rp = R * SO3::exp(kAngle * Vector3::Unit(i));
    const SO3 Rm = R * SO3::exp(-kAngle * Vector3::Unit(i));
    const Vector6 d_applied = (P_.applied_load(Rp, t) - P_.applied_load(Rm, t)) / (2 * kAngle);
    Vector6 d_load = (node_gravity(j, Rp) - node_gravity(j, Rm)) / (2 * kAngle) + d_applied;
    double d_work = w * d_applied.dot(eta);
    if (tip) {
      const Vector6 d_tip = (P_.tip_load(Rp, t) - P_.tip_load(Rm, t)) / (2 * kAngle);
      d_load += d_tip / w;
      d_work += d_tip.dot(eta);
    }
    out.eta_pose.col(i) = d_load;
    out.work_pose[i] = d_work;
  }
  // work = w applied . eta + tip . eta; diss = -w drag . eta
  out.work_velocity = w * applied + tip_load;
  out.diss_pose.setZero();
  out.diss_velocity.setZero();
  if (P_.has_drag()) {
    const Vector6 drag = P_.drag_load(eta);
    Matrix6 d_drag;
    for (int i = 0; i < 6; ++i) {
      const double h = 1e-6 * std::max(std::abs(eta[i]), i < 3 ? omega1_ : omega1_ * P_.length());
      Vector6 ep = eta, em = eta;
      ep[i] += h;
      em[i] -= h;
      d_drag.col(i) = (P_.drag_load(ep) - P_.drag_load(em)) / (ep[i] - em[i]);
    }
    out.eta_velocity += d_drag;
    out.diss_velocity = -w * (drag + d_drag.transpose() * eta);
  }
}

void SemiDiscreteRod::analytic_newton_matrix(const Layout& lay, double t, const ConstRef& y,
                                             double a, double b, SparseMatrix& J) const {
  if (!J.isCompressed())
    throw std::logic_error("SemiDiscreteRod::analytic_newton_matrix: J must be compressed");
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f0_.data(), diss, work);
  seg_lin_.resize(n_ - 1);
  node_lin_.resize(n_);
  for (int j = 0; j + 1 < n_; ++j) linearise_segment(j, seg_lin_[j]);
  for (int j = 1; j <= last_; ++j) linearise_node(j, t, node_lin_[j]);

  // df_r/dy_k for the node rows r = k - 1 .. k + 1 of node column k, raw unknowns, and the
  // ledger gradients, then J's column k.
  for (int k = 1; k <= last_; ++k) {
    const double* yk = y.data() + kBlock * (k - 1);
    const Matrix3 Rk = g_[k].rotation_matrix();
    const Matrix67 E = pose_map(yk, Rk);
    // Contributions to node r's (r in k-1..k+1) force balance by [eps_k; eta_k]: segment r
    // (inner lambda_r, node r = a side or b side) and segment r - 1 (- Ad^T lambda_(r-1)).
    std::array<Eigen::Matrix<double, 6, 12>, 3> force{};
    for (auto& m : force) m.setZero();
    Vector6 diss_pose = Vector6::Zero(), diss_vel = Vector6::Zero();
    Vector6 work_pose = Vector6::Zero(), work_vel = Vector6::Zero();
    // segment k - 1 (a = k - 1, b = k): moved to node k, lambda to node k - 1
    {
      const SegmentLinearisation& s = seg_lin_[k - 1];
      force[1].leftCols<6>() -= s.moved[kFarPose];
      force[1].rightCols<6>() -= s.moved[kFarVelocity];
      force[0].leftCols<6>() += s.lambda[kFarPose];
      force[0].rightCols<6>() += s.lambda[kFarVelocity];
      diss_pose += s.diss[kFarPose], diss_vel += s.diss[kFarVelocity];
      work_pose += s.work[kFarPose], work_vel += s.work[kFarVelocity];
    }
    // segment k (a = k, b = k + 1): lambda to node k, moved to node k + 1
    if (k + 1 < n_) {
      const SegmentLinearisation& s = seg_lin_[k];
      force[1].leftCols<6>() += s.lambda[kNearPose];
      force[1].rightCols<6>() += s.lambda[kNearVelocity];
      force[2].leftCols<6>() -= s.moved[kNearPose];
      force[2].rightCols<6>() -= s.moved[kNearVelocity];
      diss_pose += s.diss[kNearPose], diss_vel += s.diss[kNearVelocity];
      work_pose += s.work[kNearPose], work_vel += s.work[kNearVelocity];
    }
    const NodeLinearisation& nk = node_lin_[k];
    diss_pose += nk.diss_pose, diss_vel += nk.diss_velocity;
    work_pose += nk.work_pose, work_vel += nk.work_velocity;

    // The raw 13 x 13 blocks df_r/dy_k.
    std::array<Matrix13, 3> block;
    for (int o = 0; o < 3; ++o) {
      const int r = k - 1 + o;
      block[o].setZero();
      if (r < 1 || r > last_) continue;
      const double w = r == n_ - 1 ? 0.5 * ds_ : ds_;
      Eigen::Matrix<double, 6, 12> dforce = force[o] / w;
      if (o == 1) {
        dforce.leftCols<6>() += nk.eta_pose;
        dforce.rightCols<6>() += nk.eta_velocity;
      }
      // eta_dot = M^-1 (...)
      const Eigen::Matrix<double, 6, 12> deta_dot =
          full_inertia_ ? Eigen::Matrix<double, 6, 12>(inertia_inv_[r] * dforce)
                        : Eigen::Matrix<double, 6, 12>(M_.cwiseInverse().asDiagonal() * dforce);
      block[o].bottomLeftCorner<6, 7>() = deta_dot.leftCols<6>() * E;
      block[o].bottomRightCorner<6, 6>() = deta_dot.rightCols<6>();
    }
    // Node k's kinematic rows: p_dot = R kappa, q_dot = q (x) [0; psi] / 2.
    {
      Matrix13& B = block[1];
      const Vector3 kappa = eta_[k].tail<3>(), psi = eta_[k].head<3>();
      Eigen::Matrix<double, 3, 6> dp_eps = Eigen::Matrix<double, 3, 6>::Zero();
      dp_eps.leftCols<3>() = -Rk * so3::hat(kappa);
      B.block<3, 7>(kP, 0) = dp_eps * E;
      B.block<3, 3>(kP, kEta + 3) = Rk;
      const double qw = yk[kQ];
      const Vector3 qv(yk[kQ + 1], yk[kQ + 2], yk[kQ + 3]);
      B(kQ, kQ) = 0.0;
      B.block<1, 3>(kQ, kQ + 1) = -0.5 * psi.transpose();
      B.block<3, 1>(kQ + 1, kQ) = 0.5 * psi;
      B.block<3, 3>(kQ + 1, kQ + 1) = -0.5 * so3::hat(psi);
      B.block<1, 3>(kQ, kEta) = -0.5 * qv.transpose();
      B.block<3, 3>(kQ + 1, kEta) = 0.5 * (qw * Matrix3::Identity() + so3::hat(qv));
    }
    Eigen::Matrix<double, 1, kBlock> d_diss, d_work;
    d_diss << diss_pose.transpose() * E, diss_vel.transpose();
    d_work << work_pose.transpose() * E, work_vel.transpose();

    // Column col of the pattern (build_pattern, compressed, rows ascending) holds the node rows
    // of nodes k - 1 .. k + 1 (13 each, those that are unknowns), then the ledger's two.
    const int* outer = J.outerIndexPtr();
    const int* inner = J.innerIndexPtr();
    double* values = J.valuePtr();
    for (int c = 0; c < kBlock; ++c) {
      const int col = kBlock * (k - 1) + c;
      int at = outer[col];
      for (int o = 0; o < 3; ++o) {
        const int r = k - 1 + o;
        if (r < 1 || r > last_) continue;
        if (inner[at] != kBlock * (r - 1))
          throw std::logic_error("SemiDiscreteRod::analytic_newton_matrix: not its pattern");
        Eigen::Map<Eigen::Matrix<double, kBlock, 1>>(values + at) = -b * block[o].col(c);
        if (o == 1) values[at + c] += a;
        at += kBlock;
      }
      if (lay.ledger) {
        values[at++] = -b * d_diss[c];
        values[at++] = -b * d_work[c];
      }
      if (at != outer[col + 1])
        throw std::logic_error("SemiDiscreteRod::analytic_newton_matrix: not its pattern");
    }
  }
  if (lay.ledger) {
    J.coeffRef(iD_, iD_) = a;
    J.coeffRef(iW_, iW_) = a;
  }
}

}  // namespace rodlab::solvers::dynamics
