#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "rodlab/check.hpp"
#include "rodlab/lie/small_angle.hpp"
#include "rodlab/rod/characteristics.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"
#include "../variational/packed_pair.hpp"  // private to solvers/dynamics

namespace rodlab::solvers::dynamics {
namespace {

namespace se3 = lie::se3;
namespace small = lie::small_angle;
/// Node colours of the finite-difference Jacobian: node j's rows depend on nodes j-1..j+1.
constexpr int kColours = 3;

}  // namespace

SemiDiscreteRod::SemiDiscreteRod(const DynamicProblem& problem, int nodes, const std::string& who,
                                 bool constrained, bool corrected_grid)
    : P_(problem), n_(nodes) {
  RODLAB_THROW_UNLESS(n_ >= 3, "{}: nodes must be >= 3", who);
  RODLAB_THROW_UNLESS(constrained || !problem.is_kirchhoff(),
                      "{}: rod.model kirchhoff is not supported yet", who);
  RODLAB_THROW_UNLESS(constrained || !problem.has_length_control(),
                      "{}: cable displacement and fluidic volume control are not supported (a "
                      "prescribed path length makes the semi-discrete system an index-3 DAE); use "
                      "implicit-midpoint-collocation, variational, implicit-midpoint or "
                      "bdf-alpha, or give a tension / pressure",
                      who);
  RODLAB_THROW_UNLESS(!(problem.is_kirchhoff() && problem.tip_clamped()),
                      "{}: rod.model kirchhoff with tip.clamped is not supported yet; use "
                      "implicit-midpoint or bdf-alpha, or rod.model cosserat",
                      who);
  kirchhoff_ = problem.is_kirchhoff();
  // A clamped tip node is prescribed like the base: nodes 1..N-2 are the unknowns.
  clamped_ = problem.tip_clamped();
  last_ = clamped_ ? n_ - 2 : n_ - 1;
  const auto& model = problem.model();
  const double L = problem.length();
  ds_ = L / (n_ - 1);
  M_ = model.M_diag();
  V_ = model.V_diag();
  m_ = problem.unknown_count();
  dim_ = kBlock * last_ + 2 + m_;
  iD_ = kBlock * last_;
  iW_ = iD_ + 1;
  iX_ = iD_ + 2;

  // Actuator unknowns: grid weights of their path lengths and rest lengths (at xi*).
  muscles_ = problem.has_muscles();
  length_control_ = problem.has_length_control();
  unknown_act_ = problem.unknown_actuators();
  is_muscle_.assign(m_, 0);
  rest_.assign(m_, 0.0);
  seg_weight_.assign(static_cast<std::size_t>(m_) * (n_ - 1), 0.0);
  for (int e = 0; e < m_; ++e) {
    const auto& act = problem.actuators()[unknown_act_[e]];
    is_muscle_[e] = act.drive == ActuatorDrive::muscle;
    for (int j = 0; j + 1 < n_; ++j) {
      const double o = problem.span_overlap(unknown_act_[e], j * ds_, (j + 1) * ds_);
      seg_weight_[e * (n_ - 1) + j] = o;
      rest_[e] += o * act.path.length_rate((j + 0.5) * ds_, model.xi_star((j + 0.5) * ds_));
    }
  }
  seg_len_.assign(seg_weight_.size(), 0.0);
  seg_len0_ = seg_lenc_ = seg_lenc0_ = seg_len_;
  rates_ = lengths_ = xtmp_ = Vector::Zero(m_);
  if (corrected_grid) {
    require_corrected_grid(problem);  // Cosserat, no actuators
    tip_cell_ = TipHalfCell::of(problem, n_);
  }
  full_inertia_ = muscles_ || tip_cell_;
  if (full_inertia_) {
    inertia_ = problem.node_inertia(n_);
    if (tip_cell_) inertia_.back() = tip_cell_->M;
    inertia_inv_.resize(n_);
    for (int j = 0; j < n_; ++j) inertia_inv_[j] = inertia_[j].inverse();
  }

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
  const auto c = rod::characteristics(
      model, n_, clamped_ ? rod::TipSupport::clamped : rod::TipSupport::free);
  omega1_ = 2.0 * std::numbers::pi * c.first_bending_frequency_hz;
  const double EI = std::min(model.K_diag()[0], model.K_diag()[1]);
  problem.model().require_spans_on_grid(n_, "the semi-discrete rod");
  xi_star_.resize(n_ - 1);
  for (int j = 0; j + 1 < n_; ++j) xi_star_[j] = model.segment_xi_star(j, n_);
  force_scale_ = EI / (L * L);
  const double e_bend = 0.5 * EI * std::pow(0.5 * std::numbers::pi / L, 2) * L;
  scale_.resize(dim_);
  for (int j = 1; j <= last_; ++j) {
    auto b = scale_.segment<kBlock>(kBlock * (j - 1));
    b.segment<3>(kP).setConstant(L);
    b.segment<4>(kQ).setConstant(1.0);
    b.segment<3>(kEta).setConstant(omega1_);
    b.segment<3>(kEta + 3).setConstant(L * omega1_);
  }
  scale_[iD_] = scale_[iW_] = e_bend;
  for (int e = 0; e < m_; ++e) scale_[iX_ + e] = unknown_scale(e);

  f0_.resize(dim_);
  f1_.resize(dim_);
  ytmp_.resize(dim_);
  yctmp_.resize(iD_);
  c0_ = c1_ = ftmp_ = Vector::Zero(constraint_size());
}

SemiDiscreteRod::Vector SemiDiscreteRod::tolerance_scale() const {
  Vector w = scale_;
  for (int j = 1; j <= last_; ++j) w.segment<3>(kBlock * (j - 1) + kP).setConstant(1.0);
  return w;
}

SemiDiscreteRod::Vector SemiDiscreteRod::rest_state(std::span<const SE3> g0) const {
  RODLAB_THROW_UNLESS(static_cast<int>(g0.size()) == n_, "expected {} initial poses, got {}", n_,
                      g0.size());
  std::vector<SE3> g(g0.begin(), g0.end());
  if (kirchhoff_) {
    // Start on the constraint (as variational): a chord of the sampled initial shape is shorter
    // than its arc by O((kappa ds)^2); each segment keeps its rotation and gets nu = nu*.
    for (int j = 0; j + 1 < n_; ++j) {
      Vector6 x = (g0[j].inverse_times(g0[j + 1])).log();
      x.tail<3>() = ds_ * xi_star_[j].tail<3>();
      g[j + 1] = g[j] * SE3::exp(x);
    }
  }
  Vector y0 = Vector::Zero(dim_);
  pack_nodes(g, std::vector<Vector6>(n_, Vector6::Zero()), y0);
  if (m_ > 0) y0.tail(m_) = initial_unknowns(y0);
  return y0;
}

void SemiDiscreteRod::pack_nodes(std::span<const SE3> g, std::span<const Vector6> eta,
                                 Eigen::Ref<Vector> y) const {
  RODLAB_THROW_UNLESS(static_cast<int>(g.size()) == n_ && static_cast<int>(eta.size()) == n_ &&
                          y.size() >= iD_,
                      "SemiDiscreteRod::pack_nodes: expected {} poses and velocities", n_);
  for (int j = 1; j <= last_; ++j) {
    auto b = y.segment<kBlock>(kBlock * (j - 1));
    b.segment<3>(kP) = g[j].translation();
    const lie::Quaternion& q = g[j].rotation().quaternion();
    Eigen::Vector4d wxyz(q.w(), q.x(), q.y(), q.z());
    if (wxyz.dot(b.segment<4>(kQ)) < 0.0) wxyz = -wxyz;
    b.segment<4>(kQ) = wxyz;
    b.segment<6>(kEta) = eta[j];
  }
}

SemiDiscreteRod::Vector SemiDiscreteRod::initial_unknowns(const ConstRef& y) const {
  Vector x = Vector::Zero(m_);
  if (m_ == 0) return x;
  path_lengths(y, x);
  for (int e = 0; e < m_; ++e)
    if (!is_muscle_[e]) x[e] = 0.0;
  return x;
}

void SemiDiscreteRod::segment_lengths(const double* y, std::vector<double>& seg) const {
  unpack_nodes(y);
  for (int j = 0; j + 1 < n_; ++j) {
    const Vector6 xk = model_strain((g_[j].inverse_times(g_[j + 1])).log() / ds_, j);
    for (int e = 0; e < m_; ++e) {
      const std::size_t i = static_cast<std::size_t>(e) * (n_ - 1) + j;
      seg[i] = seg_weight_[i] == 0.0 ? 0.0
                                     : seg_weight_[i] * P_.actuators()[unknown_act_[e]]
                                                            .path.length_rate((j + 0.5) * ds_, xk);
    }
  }
}

void SemiDiscreteRod::path_lengths(const ConstRef& y, Eigen::Ref<Vector> lengths) const {
  if (y.size() < iD_ || lengths.size() != m_)
    throw std::invalid_argument("SemiDiscreteRod::path_lengths: bad sizes");
  segment_lengths(y.data(), seg_lenc_);
  for (int e = 0; e < m_; ++e) {
    double sum = 0.0;
    for (int j = 0; j + 1 < n_; ++j) sum += seg_lenc_[static_cast<std::size_t>(e) * (n_ - 1) + j];
    lengths[e] = sum;
  }
}

double SemiDiscreteRod::target_length(int e, double t) const {
  return P_.actuators()[unknown_act_[e]].target_length(t, rest_[e]);
}

void SemiDiscreteRod::actuator_rows(double t_c, const ConstRef& y_c, const ConstRef& x,
                                    Eigen::Ref<Vector> rows) const {
  if (x.size() != m_ || rows.size() != m_)
    throw std::invalid_argument("SemiDiscreteRod::actuator_rows: bad sizes");
  if (length_control_) path_lengths(y_c, xtmp_);
  const double L = P_.length();
  for (int e = 0; e < m_; ++e)
    rows[e] = is_muscle_[e] ? (x[e] - lengths_[e]) / L : (xtmp_[e] - target_length(e, t_c)) / L;
}

void SemiDiscreteRod::unpack_nodes(const double* y) const {
  g_[0] = P_.base();
  eta_[0].setZero();
  for (int j = 1; j <= last_; ++j) {
    const double* b = y + kBlock * (j - 1);
    const lie::Quaternion q(b[kQ], b[kQ + 1], b[kQ + 2], b[kQ + 3]);
    g_[j] = SE3(SO3::from_quaternion(q), Vector3(b[kP], b[kP + 1], b[kP + 2]));
    eta_[j] = Eigen::Map<const Vector6>(b + kEta);
  }
  if (clamped_) {
    g_[n_ - 1] = P_.tip_target();  // held by the clamp (eta_[n_ - 1] stays zero)
    eta_[n_ - 1].setZero();
  }
}

void SemiDiscreteRod::set_state(const ConstRef& y) const {
  unpack_nodes(y.data());
  for (int j = 0; j + 1 < n_; ++j) xi_[j] = (g_[j].inverse_times(g_[j + 1])).log() / ds_;
}

void SemiDiscreteRod::ida_residual(double t, const ConstRef& y, const ConstRef& yp,
                                   Eigen::Ref<Vector> r) const {
  rhs(t, y, r);  // (3.38)-(3.41), (3.8) on the staggered grid
  r = yp - r;
  // muscle lengths: algebraic, Delta - L(y)
  const int m = unknown_size();
  if (m > 0) actuator_rows(t, y, y.tail(m), r.tail(m));
}

void SemiDiscreteRod::constraint(const double* y, double* c) const {
  unpack_nodes(y);
  for (int j = 0; j + 1 < n_; ++j) {
    const Vector6 x = (g_[j].inverse_times(g_[j + 1])).log();
    Eigen::Map<Vector3>(c + 3 * j) = x.tail<3>() / ds_ - xi_star_[j].tail<3>();
  }
}

void SemiDiscreteRod::constraint(const ConstRef& y, Eigen::Ref<Vector> c) const {
  if (!kirchhoff_ || y.size() < iD_ || c.size() != constraint_size())
    throw std::invalid_argument("SemiDiscreteRod::constraint: not a Kirchhoff rod or bad sizes");
  constraint(y.data(), c.data());
}

void SemiDiscreteRod::segment(int j, double t, bool actuators, const double* forces) const {
  const double inv_ds = 1.0 / ds_;  // products, not divisions
  const SE3 G = g_[j].inverse_times(g_[j + 1]);
  // The segment's angle is small (ds |kappa|): log, dexp^-1 and dexp^-T share the coefficients
  // e, f of the small-angle kernels (as in `variational`); the two adjoint maps share R^T.
  small::EF k;
  const Vector6 x_seg = small::log(G, k);  // ds xi_j
  xi_[j] = x_seg * inv_ds;
  const lie::SE3Adjoints adjoints(G);
  const Vector6 rel = eta_[j + 1] - adjoints.inverse_Ad_apply(eta_[j]);
  xi_dot_[j] = small::dexp_inv_apply(-x_seg, rel, k) * inv_ds;
  const double s_mid = (j + 0.5) * ds_;
  // Kirchhoff rods: the rod's own force part is replaced by the constraint force (header).
  Vector6 xk = model_strain(xi_[j], j), xk_dot = xi_dot_[j];
  if (kirchhoff_) xk_dot.tail<3>().setZero();
  Vector6 sigma = actuators ? P_.internal_wrench(xk, xk_dot, s_mid, F_)
                            : P_.internal_wrench(xk, xk_dot, s_mid, t);
  if (kirchhoff_ && forces) sigma.tail<3>() += Eigen::Map<const Vector3>(forces + 3 * j);
  lambda_[j] = small::dexp_inv_transpose_apply(x_seg, sigma, k);
  moved_[j] = adjoints.coAd_apply(lambda_[j]);
  seg_diss_[j] = ds_ * xk_dot.dot(V_.cwiseProduct(xk_dot));
  if (muscles_) seg_diss_[j] += ds_ * P_.embedded_dissipation(xk_dot, s_mid);
  seg_work_[j] = actuators ? ds_ * P_.actuator_power(xk, xk_dot, s_mid, F_) : 0.0;
  for (int e = 0; e < m_; ++e) {
    const std::size_t i = static_cast<std::size_t>(e) * (n_ - 1) + j;
    if (seg_weight_[i] == 0.0) {
      seg_len_[i] = 0.0;
      continue;
    }
    const auto& path = P_.actuators()[unknown_act_[e]].path;
    seg_len_[i] = seg_weight_[i] * path.length_rate(s_mid, xk);
    rates_[e] += seg_weight_[i] * path.unit_wrench(s_mid, xk).dot(xk_dot);  // d|u|/dt
  }
}

bool SemiDiscreteRod::segment_pair(int j, int k) const {
  const packed::Pose G = packed::inverse_compose(packed::load(g_[j], g_[k]),
                                                 packed::load(g_[j + 1], g_[k + 1]));
  packed::D2 e, f;
  bool small_angles;
  const packed::V6 x = packed::log(G, e, f, small_angles);  // ds xi
  if (!small_angles) return false;
  const double inv_ds = 1.0 / ds_;
  const packed::V6 xi = inv_ds * x;
  const packed::V6 rel = packed::load(eta_[j + 1], eta_[k + 1]) -
                         packed::inverse_Ad_apply(G, packed::load(eta_[j], eta_[k]));
  const packed::V6 xi_dot = inv_ds * packed::dexp_inv_apply(-1.0 * x, rel, e, f);
  const double* K = P_.model().K_diag().data();
  const packed::V6 sigma = packed::diag(K, xi - packed::load(xi_star_[j], xi_star_[k])) +
                           packed::diag(V_.data(), xi_dot);  // (3.10)
  const packed::V6 lambda = packed::dexp_inv_transpose_apply(x, sigma, e, f);
  const packed::V6 moved = packed::coAd_apply(G, lambda);
  const packed::D2 power = packed::dot(xi_dot, packed::diag(V_.data(), xi_dot));
  for (int l = 0; l < 2; ++l) {
    const int s = l == 0 ? j : k;
    xi_[s] = packed::lane(xi, l);
    xi_dot_[s] = packed::lane(xi_dot, l);
    lambda_[s] = packed::lane(lambda, l);
    moved_[s] = packed::lane(moved, l);
    seg_diss_[s] = ds_ * power[l];
    seg_work_[s] = 0.0;
  }
  return true;
}

void SemiDiscreteRod::evaluate(double t, const double* y, double* f, double& diss,
                               double& work, const double* forces, const double* x) const {
  unpack_nodes(y);
  const bool actuators = P_.has_actuators();
  if (actuators) F_ = P_.forces(t, x, rest_.data());
  if (m_ > 0) rates_.setZero();
  // the plain rod's segments in pairs (the packed kernels), the others one by one
  const bool pairs = packed_ && !actuators && !kirchhoff_ && !muscles_ && m_ == 0;
  for (int j = 0; j + 1 < n_; j += 2) {
    const int k = j + 2 < n_ ? j + 1 : j;  // an odd count: the last segment alone
    if (pairs && k != j && segment_pair(j, k)) continue;
    segment(j, t, actuators, forces);
    if (k != j) segment(k, t, actuators, forces);
  }
  for (int e = 0; e < m_; ++e) {
    double sum = 0.0;
    for (int j = 0; j + 1 < n_; ++j) sum += seg_len_[static_cast<std::size_t>(e) * (n_ - 1) + j];
    lengths_[e] = sum;
  }
  diss = 0.0;
  work = 0.0;
  for (int j = 0; j + 1 < n_; ++j) diss += seg_diss_[j], work += seg_work_[j];
  const double inv_ds = 1.0 / ds_;  // products, not divisions, in the loop
  for (int j = 1; j <= last_; ++j) {
    const bool tip = j == n_ - 1;
    const double w = tip ? 0.5 * ds_ : ds_, inv_w = tip ? 2.0 * inv_ds : inv_ds;
    const SO3& R = g_[j].rotation();
    const Vector6& eta = eta_[j];
    const Vector6 inner = tip ? P_.tip_load(R, t) : lambda_[j];
    const Vector6 applied = P_.applied_load(R, t);
    const Vector6 drag = P_.drag_load(eta);
    Vector6 entry = Vector6::Zero();
    for (const auto& e : entries_)
      if (e.node == j) entry += P_.entry_load(e.s, xi_[tip ? j - 1 : j], F_);
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
    if (full_inertia_) {
      // M_j eta_dot = ad_eta^T M_j eta + ... with the full node inertia (3.16)-(3.20), and the
      // muscles' weight at their offsets; the corrected grid's tip: the half cell's inertia,
      // its weight at its centre of mass.
      const double s = j * ds_;
      const Vector6 weight =
          muscles_ ? P_.embedded_weight(R, s - 0.5 * ds_, std::min(P_.length(), s + 0.5 * ds_), s)
                   : Vector6::Zero();
      const Vector6 rhs = se3::coad_apply(eta, inertia_[j] * eta) +
                          (inner - moved_[j - 1] + entry) * inv_w + node_gravity(j, R) + weight +
                          applied + drag;
      Eigen::Map<Vector6>(out + kEta) = inertia_inv_[j] * rhs;
    } else {
      const Vector6 rhs = se3::coad_apply(eta, M_.cwiseProduct(eta)) +
                          (inner - moved_[j - 1] + entry) * inv_w + P_.gravity_load(R) + applied + drag;
      Eigen::Map<Vector6>(out + kEta) = rhs.cwiseQuotient(M_);
    }
  }
}

void SemiDiscreteRod::rhs(double t, const ConstRef& y, Eigen::Ref<Vector> f) const {
  if (m_ > 0 && y.size() != dim_)
    throw std::invalid_argument("SemiDiscreteRod::rhs: y must carry the actuator unknowns");
  rhs(t, y, Vector(), m_ > 0 ? ConstRef(y.tail(m_)) : ConstRef(Vector()), f);
}

void SemiDiscreteRod::rhs(double t, const ConstRef& y, const ConstRef& forces,
                          Eigen::Ref<Vector> f) const {
  if (m_ > 0 && y.size() != dim_)
    throw std::invalid_argument("SemiDiscreteRod::rhs: y must carry the actuator unknowns");
  rhs(t, y, forces, m_ > 0 ? ConstRef(y.tail(m_)) : ConstRef(Vector()), f);
}

void SemiDiscreteRod::rhs(double t, const ConstRef& y, const ConstRef& forces, const ConstRef& x,
                          Eigen::Ref<Vector> f) const {
  if (y.size() < iD_ || (f.size() != dim_ && f.size() != iD_) ||
      (forces.size() != 0 && forces.size() != constraint_size()) || x.size() != m_)
    throw std::invalid_argument("SemiDiscreteRod::rhs: bad sizes");
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f.data(), diss, work, forces.size() ? forces.data() : nullptr,
           m_ ? x.data() : nullptr);
  if (f.size() == dim_) {
    f[iD_] = diss;
    f[iW_] = work;
    if (m_ > 0) f.tail(m_) = rates_;
  }
}

SemiDiscreteRod::Layout SemiDiscreteRod::layout(bool ledger, bool forces) const {
  Layout lay;
  lay.ledger = ledger;
  lay.forces = forces;
  lay.iF = iD_ + (ledger ? 2 : 0);
  lay.iX = lay.iF + (forces ? constraint_size() : 0);
  lay.n = lay.iX + m_;
  return lay;
}

SemiDiscreteRod::SparseMatrix SemiDiscreteRod::build_pattern(const Layout& lay) const {
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 1; k <= last_; ++k) {
    const int first = std::max(1, k - 1), last = std::min(last_, k + 1);
    for (int c = 0; c < kBlock; ++c) {
      const int col = kBlock * (k - 1) + c;
      for (int row = kBlock * (first - 1); row < kBlock * last; ++row) t.emplace_back(row, col, 1.0);
      if (lay.ledger) {
        t.emplace_back(iD_, col, 1.0);
        t.emplace_back(iW_, col, 1.0);
      }
      if (c >= kEta) continue;
      // c_(k-1) and c_k see the pose of node k; path lengths see every pose
      if (lay.forces)
        for (int seg = k - 1; seg <= std::min(k, n_ - 2); ++seg)
          for (int r = 0; r < 3; ++r) t.emplace_back(lay.iF + 3 * seg + r, col, 1.0);
      for (int e = 0; e < m_; ++e) t.emplace_back(lay.iX + e, col, 1.0);
    }
  }
  if (lay.ledger) {
    t.emplace_back(iD_, iD_, 1.0);
    t.emplace_back(iW_, iW_, 1.0);
  }
  if (lay.forces)
    for (int seg = 0; seg + 1 < n_; ++seg)
      for (int r = 0; r < 3; ++r)
        for (int node = std::max(1, seg); node <= seg + 1; ++node)
          for (int e = 0; e < 6; ++e)
            t.emplace_back(kBlock * (node - 1) + kEta + e, lay.iF + 3 * seg + r, 1.0);
  // Actuator unknowns: their forces reach every eta row (and the ledger); their rows see
  // their own unknown.
  for (int e = 0; e < m_; ++e) {
    for (int node = 1; node <= last_; ++node)
      for (int i = 0; i < 6; ++i) t.emplace_back(kBlock * (node - 1) + kEta + i, lay.iX + e, 1.0);
    if (lay.ledger) {
      t.emplace_back(iD_, lay.iX + e, 1.0);
      t.emplace_back(iW_, lay.iX + e, 1.0);
    }
    t.emplace_back(lay.iX + e, lay.iX + e, 1.0);
  }
  SparseMatrix J(lay.n, lay.n);
  J.setFromTriplets(t.begin(), t.end());
  J.makeCompressed();
  return J;
}

SemiDiscreteRod::SparseMatrix SemiDiscreteRod::pattern(bool with_ledger) const {
  if (!with_ledger && kirchhoff_)
    throw std::invalid_argument("SemiDiscreteRod::pattern: Kirchhoff rods use constrained_pattern");
  return build_pattern(layout(with_ledger, false));
}

SemiDiscreteRod::SparseMatrix SemiDiscreteRod::constrained_pattern() const {
  if (!kirchhoff_ && m_ == 0)
    throw std::invalid_argument("SemiDiscreteRod::constrained_pattern: nothing to constrain");
  return build_pattern(layout(false, kirchhoff_));
}

void SemiDiscreteRod::newton_matrix(double t, const ConstRef& y, double a, double b,
                                    SparseMatrix& J, JacobianMethod method) const {
  const bool ledger = J.rows() == dim_;
  const Layout lay = layout(ledger, false);
  if ((!ledger && J.rows() != lay.n) || J.cols() != J.rows() || y.size() < iD_ ||
      (m_ > 0 && y.size() != dim_))
    throw std::invalid_argument("SemiDiscreteRod::newton_matrix: bad sizes");
  if (method == JacobianMethod::automatic && analytic_jacobian())
    analytic_newton_matrix(lay, t, y, a, b, J);
  else
    fill_newton_matrix(lay, t, y, nullptr, m_ ? y.data() + iX_ : nullptr, a, b, y, 0.0, J);
}

void SemiDiscreteRod::constrained_newton_matrix(double t, const ConstRef& y,
                                                const ConstRef& forces, double a, double b,
                                                const ConstRef& y_c, double cy,
                                                SparseMatrix& J) const {
  if (m_ > 0)
    throw std::invalid_argument(
        "SemiDiscreteRod::constrained_newton_matrix: give the actuator unknowns");
  constrained_newton_matrix(t, y, forces, Vector(), a, b, y_c, cy, J);
}

void SemiDiscreteRod::constrained_newton_matrix(double t, const ConstRef& y,
                                                const ConstRef& forces, const ConstRef& x,
                                                double a, double b, const ConstRef& y_c,
                                                double cy, SparseMatrix& J) const {
  const Layout lay = layout(false, kirchhoff_);
  if ((!kirchhoff_ && m_ == 0) || J.rows() != lay.n || J.cols() != J.rows() || y.size() < iD_ ||
      y_c.size() < iD_ || forces.size() != constraint_size() || x.size() != m_)
    throw std::invalid_argument("SemiDiscreteRod::constrained_newton_matrix: bad sizes");
  fill_newton_matrix(lay, t, y, kirchhoff_ ? forces.data() : nullptr, m_ ? x.data() : nullptr, a,
                     b, y_c, cy, J);
}

void SemiDiscreteRod::fill_newton_matrix(const Layout& lay, double t, const ConstRef& y,
                                         const double* forces, const double* x, double a,
                                         double b, const ConstRef& y_c, double cy,
                                         SparseMatrix& J) const {
  const std::size_t nseg = static_cast<std::size_t>(n_ - 1);
  const double L = P_.length();
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f0_.data(), diss, work, forces, x);
  const double diss0 = diss, work0 = work;
  seg0_diss_ = seg_diss_;
  seg0_work_ = seg_work_;
  node0_diss_ = node_diss_;
  node0_work_ = node_work_;
  seg_len0_ = seg_len_;
  if (lay.forces) constraint(y_c.data(), c0_.data());
  if (length_control_) segment_lengths(y_c.data(), seg_lenc0_);
  const bool perturb_c = lay.forces || length_control_;
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  ytmp_.head(iD_) = y.head(iD_);
  if (perturb_c) yctmp_ = y_c.head(iD_);
  // Change of unknown e's path length when node k moves: its two segments' terms.
  auto length_change = [&](const std::vector<double>& seg1, const std::vector<double>& seg0,
                           int e, int k) {
    const std::size_t i = static_cast<std::size_t>(e) * nseg;
    double d = seg1[i + k - 1] - seg0[i + k - 1];
    if (k + 1 < n_) d += seg1[i + k] - seg0[i + k];
    return d;
  };
  // Node columns: three node colours; node k moves the node rows k-1..k+1, the ledger powers of
  // segments k - 1, k and node k, c_(k-1), c_k, and the path-length terms of segments k - 1, k.
  for (int colour = 0; colour < kColours; ++colour) {
    const int first = colour == 0 ? kColours : colour;
    if (first > last_) continue;
    for (int c = 0; c < kBlock; ++c) {
      for (int k = first; k <= last_; k += kColours) {
        const int i = kBlock * (k - 1) + c;
        const double h = root_eps * std::max(std::abs(y[i]), scale_[i]);
        ytmp_[i] = y[i] + h;
        if (perturb_c) yctmp_[i] = y_c[i] + h;
      }
      evaluate(t, ytmp_.data(), f1_.data(), diss, work, forces, x);
      if (c < kEta && lay.forces) constraint(yctmp_.data(), c1_.data());
      if (c < kEta && length_control_) segment_lengths(yctmp_.data(), seg_lenc_);
      for (int k = first; k <= last_; k += kColours) {
        const int col = kBlock * (k - 1) + c;
        const double h = ytmp_[col] - y[col];
        const double hc = perturb_c ? yctmp_[col] - y_c[col] : h;
        ytmp_[col] = y[col];
        if (perturb_c) yctmp_[col] = y_c[col];
        double d_diss = 0.0, d_work = 0.0;
        if (lay.ledger) {
          d_diss = seg_diss_[k - 1] - seg0_diss_[k - 1] + node_diss_[k] - node0_diss_[k];
          d_work = seg_work_[k - 1] - seg0_work_[k - 1] + node_work_[k] - node0_work_[k];
          if (k + 1 < n_) {
            d_diss += seg_diss_[k] - seg0_diss_[k];
            d_work += seg_work_[k] - seg0_work_[k];
          }
        }
        for (SparseMatrix::InnerIterator it(J, col); it; ++it) {
          const auto row = static_cast<int>(it.row());
          if (row < iD_) {
            it.valueRef() = (row == col ? a : 0.0) - b * ((f1_[row] - f0_[row]) / h);
          } else if (lay.ledger && row < lay.iF) {
            const double df = row == iD_ ? d_diss : d_work;
            it.valueRef() = (row == col ? a : 0.0) - b * (df / h);
          } else if (row < lay.iX) {
            it.valueRef() = cy * ((c1_[row - lay.iF] - c0_[row - lay.iF]) / hc);
          } else {
            const int e = row - lay.iX;
            it.valueRef() = is_muscle_[e]
                                ? -length_change(seg_len_, seg_len0_, e, k) / h / L
                                : cy * length_change(seg_lenc_, seg_lenc0_, e, k) / hc / L;
          }
        }
      }
    }
  }
  if (lay.ledger) {
    J.coeffRef(iD_, iD_) = a;
    J.coeffRef(iW_, iW_) = a;
  }
  // Force columns (Kirchhoff): two segment colours; f_k moves the eta rows of nodes k and k + 1.
  if (lay.forces) {
    ftmp_ = Eigen::Map<const Vector>(forces, constraint_size());
    for (int colour = 0; colour < 2; ++colour) {
      for (int r = 0; r < 3; ++r) {
        for (int k = colour; k + 1 < n_; k += 2) {
          const int i = 3 * k + r;
          ftmp_[i] = forces[i] + root_eps * std::max(std::abs(forces[i]), force_scale_);
        }
        evaluate(t, y.data(), f1_.data(), diss, work, ftmp_.data(), x);
        for (int k = colour; k + 1 < n_; k += 2) {
          const int i = 3 * k + r;
          const double h = ftmp_[i] - forces[i];
          ftmp_[i] = forces[i];
          for (SparseMatrix::InnerIterator it(J, lay.iF + i); it; ++it)
            it.valueRef() = -b * ((f1_[it.row()] - f0_[it.row()]) / h);
        }
      }
    }
  }
  // Actuator unknown columns: one evaluation each.
  if (m_ > 0) {
    xtmp_ = Eigen::Map<const Vector>(x, m_);
    for (int e = 0; e < m_; ++e) {
      const double h = root_eps * std::max(std::abs(x[e]), unknown_scale(e));
      xtmp_[e] = x[e] + h;
      evaluate(t, y.data(), f1_.data(), diss, work, forces, xtmp_.data());
      xtmp_[e] = x[e];
      const double dh = (x[e] + h) - x[e];
      for (SparseMatrix::InnerIterator it(J, lay.iX + e); it; ++it) {
        const auto row = static_cast<int>(it.row());
        if (row < iD_)
          it.valueRef() = -b * ((f1_[row] - f0_[row]) / dh);
        else if (lay.ledger && row < lay.iF)
          it.valueRef() = -b * ((row == iD_ ? diss - diss0 : work - work0) / dh);
        else  // its own row: a muscle's (x_e - L_e) / L, a length constraint's 0
          it.valueRef() = is_muscle_[e] ? 1.0 / L : 0.0;
      }
    }
  }
}

Energy SemiDiscreteRod::energy(double dissipated, double work_in) const {
  Energy e = staggered_energy(P_, g_, eta_, xi_, ds_,
                              full_inertia_ ? std::span<const lie::Matrix6>(inertia_)
                                            : std::span<const lie::Matrix6>());
  if (tip_cell_)  // the half cell's weight at its centre of mass (corrected_grid.hpp)
    e.gravity += tip_cell_->gravity_energy(P_.weight_per_length(), g_.back().rotation(), ds_);
  e.dissipated = dissipated;
  e.work_in = work_in;
  return e;
}

double SemiDiscreteRod::max_det_deviation() const { return dynamics::max_det_deviation(g_); }

std::vector<result::CenterlineSample> SemiDiscreteRod::centerline() const {
  return staggered_centerline(g_, xi_, ds_);
}

}  // namespace rodlab::solvers::dynamics
