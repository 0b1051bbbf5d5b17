// The stabilised index-2 (Gear-Gupta-Leimkuhler) form of the constrained semi-discrete rod, for
// `ida` with Kirchhoff rods and length control (semi_discrete_rod.hpp, section "the stabilised
// index-2 form"; derivation in docs/dynamics.md "ida: Kirchhoff rods and length control").
//
// The position constraints c(y) = 0 (nu_k = nu* per segment; L_e(y) = L_target(t) per
// length-controlled actuator) have the right-trivialised gradient C with respect to the node
// velocities: dc/dt = C eta (for segment k, C eta = [xi_dot_k]_nu, the exact strain rate's force
// part; for a path length, sum_k o_k u_e(xi_k)^T xi_dot_k). C^T applied to a per-segment
// "stress" s_k is, up to the factor -ds, the node force of (3.40)-(3.41): lambda_k =
// dexp^-T_{ds xi_k} s_k at node k and -Ad^T_{G_k} lambda_k at node k + 1. So the constraint
// forces (f_k as the force part of s_k; the actuator force F_e as F_e u_e) act through C^T, and
// the GGL multipliers mu act through the same operator on the pose rates: the node velocity
// that moves the poses is eta_j + K_j(mu), K_j = (M w_j)^-1 (node force of the stresses
// [0; mu_k] + mu_e o_k u_e). Then d/dt c = C eta + C K mu, and with C eta = 0 imposed as well,
// c = 0 forces C K C^T-like mu = 0: mu vanishes on the exact solution (C K is -ds C W C^T with
// W = (M w)^-1 positive definite, nonsingular for a full-rank C), and the poses stay on c = 0.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "rodlab/check.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"


namespace rodlab::solvers::dynamics {
namespace {

namespace se3 = lie::se3;
using Vector = Eigen::VectorXd;
constexpr int kColours = 3;

/// Newton on r(z) = 0 with a dense forward-difference Jacobian (steps sqrt(eps) max(|z_i|, s_i)),
/// recomputed every `refresh` iterations; stops when max |r| <= tol or after max_it iterations.
/// Returns the final max |r|.
template <class Residual>
double dense_newton(Residual&& residual, Vector& z, const Vector& s, double tol, int max_it,
                    int refresh = 1) {
  const auto n = z.size();
  Vector r(n), r1(n);
  residual(z, r);
  double norm = r.lpNorm<Eigen::Infinity>();
  Eigen::PartialPivLU<Eigen::MatrixXd> lu;
  Eigen::MatrixXd J(n, n);
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (int it = 0; it < max_it && norm > tol && std::isfinite(norm); ++it) {
    if (it % refresh == 0) {
      Vector zt = z;
      for (Eigen::Index i = 0; i < n; ++i) {
        const double h = root_eps * std::max(std::abs(z[i]), s[i]);
        zt[i] = z[i] + h;
        residual(zt, r1);
        J.col(i) = (r1 - r) / ((z[i] + h) - z[i]);
        zt[i] = z[i];
      }
      lu.compute(J);
    }
    z -= lu.solve(r);
    residual(z, r);
    norm = r.lpNorm<Eigen::Infinity>();
  }
  return norm;
}

/// The right derivative of a piecewise-linear schedule's value at t (scene/schedule.hpp: a
/// ramp's slope on the piece [t_k, t_(k+1)) holding t; zero for constants and steps, before the
/// first time and from the last one on).
double schedule_slope(const scene::ScalarSchedule& s, double t) {
  const auto& p = s.points();
  if (s.kind() != scene::ScalarSchedule::Kind::ramp || t < p.front().first || t >= p.back().first)
    return 0.0;
  std::size_t k = 0;
  while (k + 1 < p.size() && p[k + 1].first <= t) ++k;
  return (p[k + 1].second - p[k].second) / (p[k + 1].first - p[k].first);
}

/// d/dt of TendonActuator::target_length (right derivative): -d'(t) for a cable, V'(t) / A_c
/// for a chamber.
double target_rate(const TendonActuator& a, double t) {
  const double slope = schedule_slope(a.input, t);
  return a.is_cable ? -slope : loads::chamber_length(slope, a.chamber_area);  // (2.53)
}

}  // namespace

int SemiDiscreteRod::length_count() const {
  return static_cast<int>(std::count(is_muscle_.begin(), is_muscle_.end(), 0));
}

int SemiDiscreteRod::stabilised_force_index() const { return layout(true, kirchhoff_).iF; }
int SemiDiscreteRod::stabilised_unknown_index() const { return layout(true, kirchhoff_).iX; }
int SemiDiscreteRod::stabilised_multiplier_index() const { return layout(true, kirchhoff_).n; }
int SemiDiscreteRod::stabilised_size() const {
  return layout(true, kirchhoff_).n + constraint_size() + length_count();
}

SemiDiscreteRod::Vector SemiDiscreteRod::stabilised_id() const {
  Vector id = Vector::Zero(stabilised_size());
  id.head(iD_ + 2).setOnes();
  return id;
}

SemiDiscreteRod::Vector SemiDiscreteRod::stabilised_tolerance_scale() const {
  const Layout lay = layout(true, kirchhoff_);
  Vector w(stabilised_size());
  w.head(iD_ + 2) = tolerance_scale().head(iD_ + 2);
  w.segment(lay.iF, constraint_size()).setConstant(force_scale_);
  for (int e = 0; e < m_; ++e) w[lay.iX + e] = unknown_scale(e);
  w.tail(w.size() - lay.n).setConstant(force_scale_ / omega1_);
  return w;
}

SemiDiscreteRod::Vector SemiDiscreteRod::stabilised_from_rest(const ConstRef& rest) const {
  if (rest.size() != dim_)
    throw std::invalid_argument("SemiDiscreteRod::stabilised_from_rest: bad size");
  const Layout lay = layout(true, kirchhoff_);
  Vector y = Vector::Zero(stabilised_size());
  y.head(iD_ + 2) = rest.head(iD_ + 2);
  y.segment(lay.iX, m_) = rest.tail(m_);
  return y;
}

double SemiDiscreteRod::piece_target(int e, double t, double t_piece) const {
  return target_length(e, t_piece) +
         target_rate(P_.actuators()[unknown_act_[e]], t_piece) * (t - t_piece);
}

std::vector<double> SemiDiscreteRod::stabilised_breakpoints() const {
  std::vector<double> out;
  for (int e = 0; e < m_; ++e) {
    if (is_muscle_[e]) continue;
    const auto& input = P_.actuators()[unknown_act_[e]].input;
    if (input.is_constant()) continue;
    for (const auto& point : input.points()) out.push_back(point.first);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void SemiDiscreteRod::pose_correction(const double* mu, const double* mu_x,
                                      std::vector<Vector6>& out) const {
  const auto nseg = static_cast<std::size_t>(n_ - 1);
  if (corr_lambda_.size() != nseg) {
    corr_lambda_.assign(nseg, Vector6::Zero());
    corr_moved_.assign(nseg, Vector6::Zero());
  }
  out.resize(n_);
  for (int k = 0; k + 1 < n_; ++k) {
    Vector6 s = Vector6::Zero();
    if (kirchhoff_) s.tail<3>() = Eigen::Map<const Vector3>(mu + 3 * k);
    const Vector6 xk = model_strain(xi_[k], k);
    for (int e = 0, l = 0; e < m_; ++e) {
      if (is_muscle_[e]) continue;
      const std::size_t i = static_cast<std::size_t>(e) * nseg + k;
      if (seg_weight_[i] != 0.0) {
        Vector6 u = seg_weight_[i] * P_.actuators()[unknown_act_[e]].path.unit_wrench(
                                         (k + 0.5) * ds_, xk);
        if (kirchhoff_) u.tail<3>().setZero();  // L(y) sees the curvatures only
        s += mu_x[l] * u;
      }
      ++l;
    }
    const SE3 G = g_[k].inverse() * g_[k + 1];
    corr_lambda_[k] = se3::dexp_inv_transpose_apply(ds_ * xi_[k], s);
    corr_moved_[k] = G.coAd_apply(corr_lambda_[k]);
  }
  out[0].setZero();
  for (int j = 1; j < n_; ++j) {
    const bool tip = j == n_ - 1;
    const double w = tip ? 0.5 * ds_ : ds_;
    const Vector6 n = (tip ? Vector6::Zero() : corr_lambda_[j]) - corr_moved_[j - 1];
    out[j] = n.cwiseQuotient(M_) / w;
  }
}

void SemiDiscreteRod::add_pose_correction(const double* mu, const double* mu_x, double* f) const {
  pose_correction(mu, mu_x, corr_node_);
  for (int j = 1; j < n_; ++j) {
    const Vector6& d = corr_node_[j];
    double* out = f + kBlock * (j - 1);
    Eigen::Map<Vector3>(out + kP) += g_[j].rotation() * Vector3(d.tail<3>());
    const lie::Quaternion& q = g_[j].rotation().quaternion();  // normalised: f's q is too
    const Vector3 qv(q.x(), q.y(), q.z()), psi = d.head<3>();
    out[kQ] += -0.5 * qv.dot(psi);
    Eigen::Map<Vector3>(out + kQ + 1) += 0.5 * (q.w() * psi + qv.cross(psi));
  }
}

void SemiDiscreteRod::velocity_rows(double t_piece, double* kin, double* len) const {
  if (kirchhoff_)
    for (int k = 0; k + 1 < n_; ++k)
      Eigen::Map<Vector3>(kin + 3 * k) = xi_dot_[k].tail<3>() / omega1_;
  const double L = P_.length();
  for (int e = 0, l = 0; e < m_; ++e) {
    if (is_muscle_[e]) continue;
    len[l++] = (rates_[e] - target_rate(P_.actuators()[unknown_act_[e]], t_piece)) / (L * omega1_);
  }
}

void SemiDiscreteRod::segment_rates(std::vector<double>& seg) const {
  const auto nseg = static_cast<std::size_t>(n_ - 1);
  seg.assign(static_cast<std::size_t>(length_count()) * nseg, 0.0);
  for (int e = 0, l = 0; e < m_; ++e) {
    if (is_muscle_[e]) continue;
    for (int k = 0; k + 1 < n_; ++k) {
      const std::size_t i = static_cast<std::size_t>(e) * nseg + k;
      if (seg_weight_[i] == 0.0) continue;
      Vector6 xk_dot = xi_dot_[k];
      if (kirchhoff_) xk_dot.tail<3>().setZero();
      const auto& path = P_.actuators()[unknown_act_[e]].path;
      seg[l * nseg + k] =
          seg_weight_[i] * path.unit_wrench((k + 0.5) * ds_, model_strain(xi_[k], k)).dot(xk_dot);
    }
    ++l;
  }
}

void SemiDiscreteRod::ida_residual_stabilised(double t, double t_piece, const ConstRef& y,
                                          const ConstRef& yp, Eigen::Ref<Vector> r) const {
  const Layout lay = layout(true, kirchhoff_);
  const int nc = constraint_size(), iMu = lay.n, iMuX = lay.n + nc;
  if (y.size() != stabilised_size() || yp.size() != y.size() || r.size() != y.size())
    throw std::invalid_argument("SemiDiscreteRod::ida_residual_stabilised: bad sizes");
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), r.data(), diss, work, kirchhoff_ ? y.data() + lay.iF : nullptr,
           m_ ? y.data() + lay.iX : nullptr);
  add_pose_correction(y.data() + iMu, y.data() + iMuX, r.data());
  velocity_rows(t_piece, r.data() + iMu, r.data() + iMuX);
  r.head(iD_) = yp.head(iD_) - r.head(iD_);
  r[iD_] = yp[iD_] - diss;
  r[iW_] = yp[iW_] - work;
  const double L = P_.length();
  if (length_control_) path_lengths(y, xtmp_);
  for (int e = 0; e < m_; ++e)
    r[lay.iX + e] = is_muscle_[e] ? (y[lay.iX + e] - lengths_[e]) / L
                                  : (xtmp_[e] - piece_target(e, t, t_piece)) / L;
  if (kirchhoff_) constraint(y.data(), r.data() + lay.iF);
}

SemiDiscreteRod::SparseMatrix SemiDiscreteRod::stabilised_pattern() const {
  const Layout lay = layout(true, kirchhoff_);
  const int nc = constraint_size(), ml = length_count(), iMu = lay.n, iMuX = lay.n + nc;
  const int n = stabilised_size();
  stab_base_ = build_pattern(lay);
  std::vector<Eigen::Triplet<double>> t;
  for (int col = 0; col < stab_base_.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(stab_base_, col); it; ++it)
      t.emplace_back(static_cast<int>(it.row()), col, 1.0);
  for (int k = 1; k < n_; ++k) {
    // node k: the velocity rows of segments k - 1, k (Kirchhoff) and of every path (length)
    for (int c = 0; c < kBlock; ++c) {
      const int col = kBlock * (k - 1) + c;
      if (kirchhoff_)
        for (int seg = k - 1; seg <= std::min(k, n_ - 2); ++seg)
          for (int r = 0; r < 3; ++r) t.emplace_back(iMu + 3 * seg + r, col, 1.0);
      for (int l = 0; l < ml; ++l) t.emplace_back(iMuX + l, col, 1.0);
    }
    // the multipliers move the pose rows of node k: mu of segments k - 1, k, every mu_x
    for (int c = 0; c < kEta; ++c) {
      const int row = kBlock * (k - 1) + c;
      if (kirchhoff_)
        for (int seg = k - 1; seg <= std::min(k, n_ - 2); ++seg)
          for (int r = 0; r < 3; ++r) t.emplace_back(row, iMu + 3 * seg + r, 1.0);
      for (int l = 0; l < ml; ++l) t.emplace_back(row, iMuX + l, 1.0);
    }
  }
  SparseMatrix J(n, n);
  J.setFromTriplets(t.begin(), t.end());
  J.makeCompressed();
  return J;
}

void SemiDiscreteRod::stabilised_newton_matrix(double t, double t_piece, const ConstRef& y,
                                               double cj, SparseMatrix& J) const {
  const Layout lay = layout(true, kirchhoff_);
  const int nc = constraint_size(), ml = length_count(), iMu = lay.n, iMuX = lay.n + nc;
  if (y.size() != stabilised_size() || J.rows() != y.size() || J.cols() != y.size())
    throw std::invalid_argument("SemiDiscreteRod::stabilised_newton_matrix: bad sizes");
  if (stab_base_.rows() != lay.n) stab_base_ = build_pattern(lay);
  const double* forces = kirchhoff_ ? y.data() + lay.iF : nullptr;
  const double* x = m_ ? y.data() + lay.iX : nullptr;
  // Node, ledger, position-constraint and actuator rows; node, force and actuator columns.
  fill_newton_matrix(lay, t, y, forces, x, cj, 1.0, y, 1.0, stab_base_);
  for (int col = 0; col < stab_base_.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(stab_base_, col); it; ++it)
      J.coeffRef(it.row(), col) = it.value();

  // Velocity rows against the node columns: three node colours.
  const auto nseg = static_cast<std::size_t>(n_ - 1);
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), f0_.data(), diss, work, forces, x);
  Vector v0 = Vector::Zero(nc), v1 = Vector::Zero(nc), unused(std::max(ml, 1));
  std::vector<double> seg0, seg1;
  velocity_rows(t_piece, v0.data(), unused.data());
  segment_rates(seg0);
  const double L = P_.length();
  ytmp_.head(iD_) = y.head(iD_);
  for (int colour = 0; colour < kColours; ++colour) {
    const int first = colour == 0 ? kColours : colour;
    if (first > n_ - 1) continue;
    for (int c = 0; c < kBlock; ++c) {
      for (int k = first; k < n_; k += kColours) {
        const int i = kBlock * (k - 1) + c;
        ytmp_[i] = y[i] + root_eps * std::max(std::abs(y[i]), scale_[i]);
      }
      evaluate(t, ytmp_.data(), f1_.data(), diss, work, forces, x);
      velocity_rows(t_piece, v1.data(), unused.data());
      segment_rates(seg1);
      for (int k = first; k < n_; k += kColours) {
        const int col = kBlock * (k - 1) + c;
        const double h = ytmp_[col] - y[col];
        ytmp_[col] = y[col];
        if (kirchhoff_)
          for (int seg = k - 1; seg <= std::min(k, n_ - 2); ++seg)
            for (int r = 0; r < 3; ++r)
              J.coeffRef(iMu + 3 * seg + r, col) = (v1[3 * seg + r] - v0[3 * seg + r]) / h;
        for (int l = 0; l < ml; ++l) {
          double d = seg1[l * nseg + k - 1] - seg0[l * nseg + k - 1];
          if (k + 1 < n_) d += seg1[l * nseg + k] - seg0[l * nseg + k];
          J.coeffRef(iMuX + l, col) = d / h / (L * omega1_);
        }
      }
    }
  }

  // Multiplier columns: K is linear in (mu, mu_x), so unit multipliers give the columns exactly
  // (the pose rows' residual is y' - ... - K mu: minus the pose-rate change). Kirchhoff: two
  // segment colours (mu_k moves nodes k, k + 1).
  set_state(y.head(iD_));
  Vector mu = Vector::Zero(nc), mu_x = Vector::Zero(std::max(ml, 1));
  Vector rate(iD_);
  auto fill_columns = [&](auto&& columns_of_node) {
    rate.setZero();
    add_pose_correction(mu.data(), mu_x.data(), rate.data());
    for (int j = 1; j < n_; ++j)
      for (int c = 0; c < kEta; ++c) {
        const int row = kBlock * (j - 1) + c;
        columns_of_node(j, row, -rate[row]);
      }
  };
  if (kirchhoff_) {
    for (int colour = 0; colour < 2; ++colour)
      for (int r = 0; r < 3; ++r) {
        for (int k = colour; k + 1 < n_; k += 2) mu[3 * k + r] = 1.0;
        fill_columns([&](int j, int row, double value) {
          // node j is moved by segment j - 1 or j, whichever has this colour
          for (int seg = j - 1; seg <= std::min(j, n_ - 2); ++seg)
            if (seg >= 0 && seg % 2 == colour) J.coeffRef(row, iMu + 3 * seg + r) = value;
        });
        for (int k = colour; k + 1 < n_; k += 2) mu[3 * k + r] = 0.0;
      }
  }
  for (int l = 0; l < ml; ++l) {
    mu_x[l] = 1.0;
    fill_columns([&](int, int row, double value) { J.coeffRef(row, iMuX + l) = value; });
    mu_x[l] = 0.0;
  }
}

void SemiDiscreteRod::stabilised_consistent_state(double t, double t_piece, Vector& y,
                                                  Vector& yp) const {
  const Layout lay = layout(true, kirchhoff_);
  const int nc = constraint_size(), nm = nc + length_count();  // multipliers
  if (y.size() != stabilised_size())
    throw std::invalid_argument("SemiDiscreteRod::stabilised_consistent_state: bad size");
  const double L = P_.length();
  const double impulse = force_scale_ / omega1_;
  Vector x = y.segment(lay.iX, m_);
  Vector forces = y.segment(lay.iF, nc);

  // K as a dense matrix at the current poses: node velocities (6 per node) of unit multipliers.
  auto k_matrix = [&]() {
    set_state(y.head(iD_));
    Eigen::MatrixXd K(6 * (n_ - 1), nm);
    Vector unit = Vector::Zero(std::max(nm, 1));
    std::vector<Vector6> d;
    for (int i = 0; i < nm; ++i) {
      unit[i] = 1.0;
      pose_correction(unit.data(), unit.data() + nc, d);
      unit[i] = 0.0;
      for (int j = 1; j < n_; ++j) K.block<6, 1>(6 * (j - 1), i) = d[j];
    }
    return K;
  };
  // Position rows: c(y) and (L(y) - L_target) / L of the length-controlled unknowns.
  Vector lengths(m_);
  auto position_rows = [&](const Vector& ys, Vector& r) {
    if (kirchhoff_) constraint(ys.data(), r.data());
    if (length_control_) path_lengths(ys.head(iD_), lengths);
    for (int e = 0, l = 0; e < m_; ++e)
      if (!is_muscle_[e]) r[nc + l++] = (lengths[e] - piece_target(e, t, t_piece)) / L;
  };
  if (nm == 0) throw std::logic_error("stabilised_consistent_state: nothing to constrain");
  const Vector scales = Vector::Constant(nm, impulse);

  // 1. Poses onto c = 0 (skipped at rounding level: rest_state() puts Kirchhoff rods on it).
  {
    Vector r(nm);
    position_rows(y, r);
    if (r.lpNorm<Eigen::Infinity>() > 1e-13) {
      const Eigen::MatrixXd K = k_matrix();
      const Vector y0 = y;
      Vector nu = Vector::Zero(nm), ys = y;
      auto moved = [&](const Vector& z, Vector& out) {
        const Vector d = K * z;
        for (int j = 1; j < n_; ++j) {
          const int b = kBlock * (j - 1);
          const lie::Quaternion q0(y0[b + kQ], y0[b + kQ + 1], y0[b + kQ + 2], y0[b + kQ + 3]);
          const SE3 g0(SO3::from_quaternion(q0), Vector3(y0.segment<3>(b + kP)));
          const SE3 g = g0 * SE3::exp(Vector6(d.segment<6>(6 * (j - 1))));
          ys.segment<3>(b + kP) = g.translation();
          const lie::Quaternion& q = g.rotation().quaternion();
          ys.segment<4>(b + kQ) << q.w(), q.x(), q.y(), q.z();
        }
        position_rows(ys, out);
      };
      const double norm = dense_newton(moved, nu, scales, 1e-13, 30);
      if (!(norm <= 1e-10))
        throw std::runtime_error(
            rodlab::format("the initial poses could not be put on the constraints (Kirchhoff / "
                           "prescribed lengths): residual {:g}",
                           norm));
      y.head(iD_) = ys.head(iD_);  // dense_newton's last evaluation was at its solution
    }
  }

  // 2. Velocities onto C eta = L_target' (an impulse K lambda; linear: two Newton steps).
  {
    auto velocity = [&](const Vector& ys, Vector& r) {
      double diss = 0.0, work = 0.0;
      evaluate(t, ys.data(), f0_.data(), diss, work, kirchhoff_ ? forces.data() : nullptr,
               m_ ? x.data() : nullptr);
      velocity_rows(t_piece, r.data(), r.data() + nc);
    };
    Vector r(nm);
    velocity(y, r);
    if (r.lpNorm<Eigen::Infinity>() > 1e-13) {
      const Eigen::MatrixXd K = k_matrix();
      const Vector y0 = y;
      Vector lambda = Vector::Zero(nm), ys = y;
      auto pushed = [&](const Vector& z, Vector& out) {
        const Vector d = K * z;
        for (int j = 1; j < n_; ++j)
          ys.segment<6>(kBlock * (j - 1) + kEta) =
              y0.segment<6>(kBlock * (j - 1) + kEta) + d.segment<6>(6 * (j - 1));
        velocity(ys, out);
      };
      const double norm = dense_newton(pushed, lambda, scales, 0.0, 2, 2);
      if (!std::isfinite(norm))
        throw std::runtime_error("the initial velocities could not be put on the constraints");
      y.head(iD_) = ys.head(iD_);
    }
  }

  // 3. Muscle lengths, then the constraint and length-controlled forces from d/dt (C eta) = 0:
  //    the central difference of the velocity rows along the flow y' (t +- h; their targets'
  //    rates are constant on the piece), affine in the forces: two Newton steps.
  if (m_ > 0) {
    path_lengths(y.head(iD_), lengths);
    for (int e = 0; e < m_; ++e)
      if (is_muscle_[e]) x[e] = lengths[e];
  }
  const double h = 1e-6 / omega1_;
  Vector z(nm), zs(nm);
  z.head(nc) = forces;
  for (int e = 0, l = 0; e < m_; ++e)
    if (!is_muscle_[e]) z[nc + l++] = x[e];
  zs.setConstant(force_scale_);
  Vector ydot(iD_), yh(iD_), vp(nm), vm(nm);
  auto acceleration = [&](const Vector& u, Vector& out) {
    for (int e = 0, l = 0; e < m_; ++e)
      if (!is_muscle_[e]) x[e] = u[nc + l++];
    double diss = 0.0, work = 0.0;
    evaluate(t, y.data(), ydot.data(), diss, work, kirchhoff_ ? u.data() : nullptr,
             m_ ? x.data() : nullptr);
    for (const double sign : {1.0, -1.0}) {
      yh = y.head(iD_) + sign * h * ydot;
      evaluate(t + sign * h, yh.data(), f1_.data(), diss, work,
               kirchhoff_ ? u.data() : nullptr, m_ ? x.data() : nullptr);
      Vector& v = sign > 0 ? vp : vm;
      velocity_rows(t_piece, v.data(), v.data() + nc);
    }
    out = (vp - vm) / (2.0 * h);
  };
  const double anorm = dense_newton(acceleration, z, zs, 0.0, 2, 2);
  if (!std::isfinite(anorm))
    throw std::runtime_error("the initial constraint forces could not be computed");
  forces = z.head(nc);
  for (int e = 0, l = 0; e < m_; ++e)
    if (!is_muscle_[e]) x[e] = z[nc + l++];

  y.segment(lay.iF, nc) = forces;
  y.segment(lay.iX, m_) = x;
  y.tail(nm).setZero();
  yp = Vector::Zero(y.size());
  double diss = 0.0, work = 0.0;
  evaluate(t, y.data(), yp.data(), diss, work, kirchhoff_ ? forces.data() : nullptr,
           m_ ? x.data() : nullptr);
  yp[iD_] = diss;
  yp[iW_] = work;
  set_state(y.head(iD_));
}

}  // namespace rodlab::solvers::dynamics
