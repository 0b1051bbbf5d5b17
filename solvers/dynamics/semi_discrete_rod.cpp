#include "rodlab/solvers/dynamics/semi_discrete_rod.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "rodlab/rod/characteristics.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {
namespace {

namespace se3 = lie::se3;
/// Node colours of the finite-difference Jacobian: node j's rows depend on nodes j-1..j+1.
constexpr int kColours = 3;

}  // namespace

SemiDiscreteRod::SemiDiscreteRod(const DynamicProblem& problem, int nodes, const std::string& who,
                                 bool constrained)
    : P_(problem), n_(nodes) {
  if (n_ < 3) throw std::invalid_argument(who + ": nodes must be >= 3");
  if (problem.is_kirchhoff() && !constrained)
    throw std::invalid_argument(who + ": rod.model kirchhoff is not supported yet");
  kirchhoff_ = problem.is_kirchhoff();
  const auto& model = problem.model();
  const double L = problem.length();
  ds_ = L / (n_ - 1);
  M_ = model.M_diag();
  V_ = model.V_diag();
  dim_ = kBlock * (n_ - 1) + 2;
  iD_ = kBlock * (n_ - 1);
  iW_ = iD_ + 1;

  g_.assign(n_, SE3::identity());
  eta_.assign(n_, Vector6::Zero());
  xi_.assign(n_ - 1, Vector6::Zero());
  xi_dot_.assign(n_ - 1, Vector6::Zero());
  lambda_.assign(n_ - 1, Vector6::Zero());
  moved_.assign(n_ - 1, Vector6::Zero());
  seg_diss_.assign(n_ - 1, 0.0);
  seg_work_.assign(n_ - 1, 0.0);
  node_diss_.assign(n_, 0.0);
  node_work_.assign(n_, 0.0);
  seg0_diss_ = seg_diss_;
  seg0_work_ = seg_work_;
  node0_diss_ = node_diss_;
  node0_work_ = node_work_;
  entries_ = problem.entry_nodes(n_);
  g_[0] = problem.base();

  // Characteristic scales (header): L, 1, omega_1, L omega_1, E_bend.
  const auto c = rod::characteristics(model, n_, rod::TipSupport::free);
  omega1_ = 2.0 * std::numbers::pi * c.first_bending_frequency_hz;
  const double EI = std::min(model.K_diag()[0], model.K_diag()[1]);
  nu_star_ = model.xi_star().tail<3>();
  force_scale_ = EI / (L * L);
  const double e_bend = 0.5 * EI * std::pow(0.5 * std::numbers::pi / L, 2) * L;
  scale_.resize(dim_);
  for (int j = 1; j < n_; ++j) {
    auto b = scale_.segment<kBlock>(kBlock * (j - 1));
    b.segment<3>(kP).setConstant(L);
    b.segment<4>(kQ).setConstant(1.0);
    b.segment<3>(kEta).setConstant(omega1_);
    b.segment<3>(kEta + 3).setConstant(L * omega1_);
  }
  scale_[iD_] = scale_[iW_] = e_bend;

  f0_.resize(dim_);
  f1_.resize(dim_);
  ytmp_.resize(dim_);
  yctmp_.resize(iD_);
  c0_ = c1_ = ftmp_ = Vector::Zero(constraint_size());
}

SemiDiscreteRod::Vector SemiDiscreteRod::tolerance_scale() const {
  Vector w = scale_;
  for (int j = 1; j < n_; ++j) w.segment<3>(kBlock * (j - 1) + kP).setConstant(1.0);
  return w;
}

SemiDiscreteRod::Vector SemiDiscreteRod::rest_state(std::span<const SE3> g0) const {
  if (static_cast<int>(g0.size()) != n_)
    throw std::invalid_argument("expected " + std::to_string(n_) + " initial poses, got " +
                                std::to_string(g0.size()));
  std::vector<SE3> g(g0.begin(), g0.end());
  if (kirchhoff_) {
    // Start on the constraint (as variational): a chord of the sampled initial shape is shorter
    // than its arc by O((kappa ds)^2); each segment keeps its rotation and gets nu = nu*.
    for (int j = 0; j + 1 < n_; ++j) {
      Vector6 x = (g0[j].inverse() * g0[j + 1]).log();
      x.tail<3>() = ds_ * nu_star_;
      g[j + 1] = g[j] * SE3::exp(x);
    }
  }
  Vector y0 = Vector::Zero(dim_);
  for (int j = 1; j < n_; ++j) {
    auto b = y0.segment<kBlock>(kBlock * (j - 1));
    b.segment<3>(kP) = g[j].translation();
    const lie::Quaternion& q = g[j].rotation().quaternion();
    b.segment<4>(kQ) << q.w(), q.x(), q.y(), q.z();
  }
  return y0;
}

void SemiDiscreteRod::unpack_nodes(const double* y) const {
  g_[0] = P_.base();
  eta_[0].setZero();
  for (int j = 1; j < n_; ++j) {
    const double* b = y + kBlock * (j - 1);
    const lie::Quaternion q(b[kQ], b[kQ + 1], b[kQ + 2], b[kQ + 3]);
    g_[j] = SE3(SO3::from_quaternion(q), Vector3(b[kP], b[kP + 1], b[kP + 2]));
    eta_[j] = Eigen::Map<const Vector6>(b + kEta);
  }
}

void SemiDiscreteRod::set_state(const ConstRef& y) const {
  unpack_nodes(y.data());
  for (int j = 0; j + 1 < n_; ++j) xi_[j] = (g_[j].inverse() * g_[j + 1]).log() / ds_;
}

void SemiDiscreteRod::constraint(const double* y, double* c) const {
  unpack_nodes(y);
  for (int j = 0; j + 1 < n_; ++j) {
    const Vector6 x = (g_[j].inverse() * g_[j + 1]).log();
    Eigen::Map<Vector3>(c + 3 * j) = x.tail<3>() / ds_ - nu_star_;
  }
}

void SemiDiscreteRod::constraint(const ConstRef& y, Eigen::Ref<Vector> c) const {
  if (!kirchhoff_ || y.size() < iD_ || c.size() != constraint_size())
    throw std::invalid_argument("SemiDiscreteRod::constraint: not a Kirchhoff rod or bad sizes");
  constraint(y.data(), c.data());
}

void SemiDiscreteRod::evaluate(double t, const double* y, double* f, double& diss,
                               double& work, const double* forces) const {
  unpack_nodes(y);
  for (int j = 0; j + 1 < n_; ++j) {
    const SE3 G = g_[j].inverse() * g_[j + 1];
    const Vector6 x = G.log();  // ds xi_j
    xi_[j] = x / ds_;
    const Vector6 rel = eta_[j + 1] - G.inverse().Ad_apply(eta_[j]);
    xi_dot_[j] = se3::dexp_inv_apply(-x, rel) / ds_;
    const double s_mid = (j + 0.5) * ds_;
    // Kirchhoff rods: the rod's own force part is replaced by the constraint force (header).
    Vector6 xk = xi_[j], xk_dot = xi_dot_[j];
    if (kirchhoff_) {
      xk.tail<3>() = nu_star_;
      xk_dot.tail<3>().setZero();
    }
    Vector6 sigma = P_.internal_wrench(xk, xk_dot, s_mid, t);
    if (kirchhoff_ && forces) sigma.tail<3>() += Eigen::Map<const Vector3>(forces + 3 * j);
    lambda_[j] = se3::dexp_inv_transpose_apply(x, sigma);
    moved_[j] = G.coAd_apply(lambda_[j]);
    seg_diss_[j] = ds_ * xk_dot.dot(V_.cwiseProduct(xk_dot));
    seg_work_[j] = P_.has_actuators() ? ds_ * P_.actuator_power(xk, xk_dot, s_mid, t) : 0.0;
  }
  diss = 0.0;
  work = 0.0;
  for (int j = 0; j + 1 < n_; ++j) diss += seg_diss_[j], work += seg_work_[j];
  for (int j = 1; j < n_; ++j) {
    const bool tip = j == n_ - 1;
    const double w = tip ? 0.5 * ds_ : ds_;
    const SO3& R = g_[j].rotation();
    const Vector6& eta = eta_[j];
    const Vector6 inner = tip ? P_.tip_load(R, t) : lambda_[j];
    const Vector6 applied = P_.applied_load(R, t);
    const Vector6 drag = P_.drag_load(eta);
    Vector6 entry = Vector6::Zero();
    for (const auto& e : entries_)
      if (e.node == j) entry += P_.entry_load(e.s, xi_[tip ? j - 1 : j], t);
    const Vector6 rhs = se3::coad_apply(eta, M_.cwiseProduct(eta)) +
                        (inner - moved_[j - 1] + entry) / w + P_.gravity_load(R) + applied + drag;
    node_diss_[j] = -w * drag.dot(eta);
    node_work_[j] = w * applied.dot(eta) + entry.dot(eta) + (tip ? inner.dot(eta) : 0.0);
    diss += node_diss_[j];
    work += node_work_[j];

    double* out = f + kBlock * (j - 1);
    const double* b = y + kBlock * (j - 1);
    Eigen::Map<Vector3>(out + kP) = R * Vector3(eta.tail<3>());
    // q_dot = q (x) [0; psi] / 2 on the stored (unnormalised) q.
    const double qw = b[kQ];
    const Vector3 qv(b[kQ + 1], b[kQ + 2], b[kQ + 3]);
    const Vector3 psi = eta.head<3>();
    out[kQ] = -0.5 * qv.dot(psi);
    Eigen::Map<Vector3>(out + kQ + 1) = 0.5 * (qw * psi + qv.cross(psi));
    Eigen::Map<Vector6>(out + kEta) = rhs.cwiseQuotient(M_);
  }
}

void SemiDiscreteRod::rhs(double t, const ConstRef& y, Eigen::Ref<Vector> f) const {
  if (y.size() < iD_ || (f.size() != dim_ && f.size() != iD_))
    throw std::invalid_argument("SemiDiscreteRod::rhs: bad sizes");
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f.data(), diss, work);
  if (f.size() == dim_) {
    f[iD_] = diss;
    f[iW_] = work;
  }
}

void SemiDiscreteRod::rhs(double t, const ConstRef& y, const ConstRef& forces,
                          Eigen::Ref<Vector> f) const {
  if (y.size() < iD_ || (f.size() != dim_ && f.size() != iD_) ||
      forces.size() != constraint_size())
    throw std::invalid_argument("SemiDiscreteRod::rhs: bad sizes");
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f.data(), diss, work, forces.size() ? forces.data() : nullptr);
  if (f.size() == dim_) {
    f[iD_] = diss;
    f[iW_] = work;
  }
}

SemiDiscreteRod::SparseMatrix SemiDiscreteRod::constrained_pattern() const {
  if (!kirchhoff_) throw std::invalid_argument("SemiDiscreteRod::constrained_pattern: not Kirchhoff");
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 1; k < n_; ++k) {
    const int first = std::max(1, k - 1), last = std::min(n_ - 1, k + 1);
    for (int c = 0; c < kBlock; ++c) {
      const int col = kBlock * (k - 1) + c;
      for (int row = kBlock * (first - 1); row < kBlock * last; ++row) t.emplace_back(row, col, 1.0);
      if (c >= kEta) continue;
      // c_(k-1) and c_k see the pose of node k
      for (int seg = k - 1; seg <= std::min(k, n_ - 2); ++seg)
        for (int r = 0; r < 3; ++r) t.emplace_back(iD_ + 3 * seg + r, col, 1.0);
    }
  }
  for (int seg = 0; seg + 1 < n_; ++seg)
    for (int r = 0; r < 3; ++r)
      for (int node = std::max(1, seg); node <= seg + 1; ++node)
        for (int e = 0; e < 6; ++e) t.emplace_back(kBlock * (node - 1) + kEta + e, iD_ + 3 * seg + r, 1.0);
  const int n = iD_ + constraint_size();
  SparseMatrix J(n, n);
  J.setFromTriplets(t.begin(), t.end());
  J.makeCompressed();
  return J;
}

void SemiDiscreteRod::constrained_newton_matrix(double t, const ConstRef& y,
                                                const ConstRef& forces, double a, double b,
                                                const ConstRef& y_c, double cy,
                                                SparseMatrix& J) const {
  const int nc = constraint_size();
  if (!kirchhoff_ || J.rows() != iD_ + nc || J.cols() != J.rows() || y.size() < iD_ ||
      y_c.size() < iD_ || forces.size() != nc)
    throw std::invalid_argument("SemiDiscreteRod::constrained_newton_matrix: bad sizes");
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f0_.data(), diss, work, forces.data());
  constraint(y_c.data(), c0_.data());
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  ytmp_.head(iD_) = y.head(iD_);
  yctmp_ = y_c.head(iD_);
  // Node columns: three node colours; node k moves the node rows k-1..k+1 and c_(k-1), c_k.
  for (int colour = 0; colour < kColours; ++colour) {
    const int first = colour == 0 ? kColours : colour;
    if (first > n_ - 1) continue;
    for (int c = 0; c < kBlock; ++c) {
      for (int k = first; k < n_; k += kColours) {
        const int i = kBlock * (k - 1) + c;
        const double h = root_eps * std::max(std::abs(y[i]), scale_[i]);
        ytmp_[i] = y[i] + h;
        yctmp_[i] = y_c[i] + h;
      }
      evaluate(t, ytmp_.data(), f1_.data(), diss, work, forces.data());
      if (c < kEta) constraint(yctmp_.data(), c1_.data());
      for (int k = first; k < n_; k += kColours) {
        const int col = kBlock * (k - 1) + c;
        const double h = ytmp_[col] - y[col], hc = yctmp_[col] - y_c[col];
        ytmp_[col] = y[col];
        yctmp_[col] = y_c[col];
        for (SparseMatrix::InnerIterator it(J, col); it; ++it) {
          const auto row = it.row();
          if (row < iD_)
            it.valueRef() = (row == col ? a : 0.0) - b * ((f1_[row] - f0_[row]) / h);
          else
            it.valueRef() = cy * ((c1_[row - iD_] - c0_[row - iD_]) / hc);
        }
      }
    }
  }
  // Force columns: two segment colours; f_k moves the eta rows of nodes k and k + 1.
  ftmp_ = forces;
  for (int colour = 0; colour < 2; ++colour) {
    for (int r = 0; r < 3; ++r) {
      for (int k = colour; k + 1 < n_; k += 2) {
        const int i = 3 * k + r;
        ftmp_[i] = forces[i] + root_eps * std::max(std::abs(forces[i]), force_scale_);
      }
      evaluate(t, y.data(), f1_.data(), diss, work, ftmp_.data());
      for (int k = colour; k + 1 < n_; k += 2) {
        const int i = 3 * k + r;
        const double h = ftmp_[i] - forces[i];
        ftmp_[i] = forces[i];
        for (SparseMatrix::InnerIterator it(J, iD_ + i); it; ++it)
          it.valueRef() = -b * ((f1_[it.row()] - f0_[it.row()]) / h);
      }
    }
  }
}

SemiDiscreteRod::SparseMatrix SemiDiscreteRod::pattern(bool with_ledger) const {
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 1; k < n_; ++k) {
    const int first = std::max(1, k - 1), last = std::min(n_ - 1, k + 1);
    for (int c = 0; c < kBlock; ++c) {
      const int col = kBlock * (k - 1) + c;
      for (int row = kBlock * (first - 1); row < kBlock * last; ++row) t.emplace_back(row, col, 1.0);
      if (with_ledger) {
        t.emplace_back(iD_, col, 1.0);
        t.emplace_back(iW_, col, 1.0);
      }
    }
  }
  if (with_ledger) {
    t.emplace_back(iD_, iD_, 1.0);
    t.emplace_back(iW_, iW_, 1.0);
  }
  const int n = with_ledger ? dim_ : iD_;
  SparseMatrix J(n, n);
  J.setFromTriplets(t.begin(), t.end());
  J.makeCompressed();
  return J;
}

void SemiDiscreteRod::newton_matrix(double t, const ConstRef& y, double a, double b,
                                    SparseMatrix& J) const {
  const bool ledger = J.rows() == dim_;
  if ((!ledger && J.rows() != iD_) || J.cols() != J.rows() || y.size() < iD_)
    throw std::invalid_argument("SemiDiscreteRod::newton_matrix: bad sizes");
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f0_.data(), diss, work);
  seg0_diss_ = seg_diss_;
  seg0_work_ = seg_work_;
  node0_diss_ = node_diss_;
  node0_work_ = node_work_;
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  ytmp_.head(iD_) = y.head(iD_);
  for (int colour = 0; colour < kColours; ++colour) {
    const int first = colour == 0 ? kColours : colour;
    if (first > n_ - 1) continue;
    for (int c = 0; c < kBlock; ++c) {
      for (int k = first; k < n_; k += kColours) {
        const int i = kBlock * (k - 1) + c;
        ytmp_[i] = y[i] + root_eps * std::max(std::abs(y[i]), scale_[i]);
      }
      evaluate(t, ytmp_.data(), f1_.data(), diss, work);
      for (int k = first; k < n_; k += kColours) {
        const int col = kBlock * (k - 1) + c;
        const double h = ytmp_[col] - y[col];
        ytmp_[col] = y[col];
        double d_diss = seg_diss_[k - 1] - seg0_diss_[k - 1] + node_diss_[k] - node0_diss_[k];
        double d_work = seg_work_[k - 1] - seg0_work_[k - 1] + node_work_[k] - node0_work_[k];
        if (k + 1 < n_) {
          d_diss += seg_diss_[k] - seg0_diss_[k];
          d_work += seg_work_[k] - seg0_work_[k];
        }
        for (SparseMatrix::InnerIterator it(J, col); it; ++it) {
          const auto row = it.row();
          const double df = row == iD_ ? d_diss : row == iW_ ? d_work : f1_[row] - f0_[row];
          it.valueRef() = (row == col ? a : 0.0) - b * (df / h);
        }
      }
    }
  }
  if (ledger) {
    J.coeffRef(iD_, iD_) = a;
    J.coeffRef(iW_, iW_) = a;
  }
}

Energy SemiDiscreteRod::energy(double dissipated, double work_in) const {
  Energy e;
  e.kinetic = kinetic_energy(P_.model(), eta_, ds_);
  e.strain = strain_energy_segments(P_.model(), xi_, ds_);
  e.gravity = gravity_energy(P_, g_, ds_);
  e.dissipated = dissipated;
  e.work_in = work_in;
  return e;
}

double SemiDiscreteRod::max_det_deviation() const { return dynamics::max_det_deviation(g_); }

std::vector<result::CenterlineSample> SemiDiscreteRod::centerline() const {
  return staggered_centerline(g_, xi_, ds_);
}

}  // namespace rodlab::solvers::dynamics
