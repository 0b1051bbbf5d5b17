#include "rodlab/solvers/statics/kinsol_collocation.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <stdexcept>
#include <vector>

#include "rodlab/check.hpp"
#include "rodlab/lie/small_angle.hpp"
#include "rodlab/solvers/common/kinsol_solver.hpp"
#include "rodlab/solvers/statics/continuation.hpp"
#include "rodlab/solvers/statics/result_builder.hpp"

namespace rodlab::solvers::statics {
namespace {

using Eigen::VectorXd;
using Quaternion = Eigen::Quaterniond;
using State = Eigen::Matrix<double, 13, 1>;  // scaled unknowns of a node: (q_w, q_x, q_y, q_z, p/L, Lambda/scale)
using Rows = Eigen::Matrix<double, 13, 1>;   // rows of an interval: pose (6), wrench (6), |q|^2 - 1
using ConstRef = Eigen::Ref<const VectorXd>;
using Ref = Eigen::Ref<VectorXd>;
using Sparse = KinsolSolver::SparseMatrix;

constexpr int kState = 13;
constexpr int kFirstWrench = 7;  // a node's unknowns: q (4), p / L (3), then Lambda / scale (6)
constexpr int kBaseRows = 7;
constexpr int kTipRows = 6;

/// One side of a node: the wrench, strain and (2.34) seen by the interval on that side. They
/// differ only at a breakpoint: a cable entering there adds its pull to Lambda (strain
/// continuous), and a span end or routing knot changes the actuators in the strain law.
struct Side {
  Vector6 Lambda, xi, dLambda;
};

/// What the interval rows need of a node, computed once per node and evaluation. The unknown
/// Lambda of a node is its left value (before a cable entry); `right` adds the entry jump.
struct NodeData {
  Quaternion q;  // the unknown quaternion (norm enforced by a row)
  SO3 R;         // rotation of q / |q|
  Vector3 p;
  Side left, right;
};

using Lengths = std::array<double, StaticProblem::kMaxActuators>;

class Collocation {
 public:
  Collocation(const StaticProblem& problem, int nodes)
      : P_(problem), N_(nodes), L_(problem.length()), extra_(problem.extra_unknowns()), node_(nodes),
        rows_(nodes - 1), chart_(nodes - 1), end_rate_(nodes - 1), lengths_(nodes - 1) {
    scale_.head<4>().setOnes();
    scale_.segment<3>(4).setConstant(L_);
    scale_.tail<6>() = P_.wrench_scale();
    build_mesh();
  }

  StaticProblem& problem() { return P_; }
  const StaticProblem& problem() const { return P_; }
  int nodes() const { return N_; }
  int extra() const { return extra_; }
  int size() const { return kState * N_ + extra_; }
  /// What pattern() depends on: the nodes and the extra unknowns.
  std::pair<int, int> pattern_key() const { return {N_, extra_}; }
  double s(int i) const { return s_[i]; }

  /// Node i's data from the scaled unknowns x (the extra unknowns must be set in P_).
  NodeData node(const ConstRef& x, int i) const { return node_from(x.segment<kState>(kState * i), i); }

  Vector6 strain_at(const Vector6& Lambda, double s, StaticProblem::Mask mask) const {
    return P_.strain(Lambda, s, mask);
  }

  NodeData node_from(const State& xi_scaled, int i) const {
    NodeData n;
    n.q = Quaternion(xi_scaled[0], xi_scaled[1], xi_scaled[2], xi_scaled[3]);
    n.R = SO3::from_quaternion(n.q);
    n.p = L_ * xi_scaled.segment<3>(4);
    const Vector6 Lambda = xi_scaled.tail<6>().cwiseProduct(scale_.tail<6>());
    const auto mask_right = mask_[std::min(i, N_ - 2)];
    auto side = [&](const Vector6& W, double s, StaticProblem::Mask mask) {
      Side d;
      d.Lambda = W;
      d.xi = strain_at(W, s, mask);
      d.dLambda = P_.wrench_derivative(n.R, d.xi, W);  // (2.34)
      return d;
    };
    if (!breakpoint_[i]) {
      // At the tip, the left limit of the routing's r' (the path gives right limits).
      n.left = n.right = side(Lambda, i == N_ - 1 ? s_[i] - 1e-12 * L_ : s_[i], mask_right);
    } else {
      // One-sided evaluation: the routing's r' jumps at a knot (the path gives right limits).
      n.left = side(Lambda, s_[i] - 1e-12 * L_, mask_[i - 1]);
      n.right = side(Lambda + P_.entry_jump(s_[i], n.left.xi), s_[i], mask_right);
    }
    return n;
  }

  /// node_from(xp, j) for xp = node j's unknowns with only component k moved (a Jacobian
  /// column), from node_[j] (the data at the unmoved unknowns): a position moves nothing else,
  /// a quaternion component moves R and with it (2.34) but not the strains (the strain law
  /// does not see the pose); only a wrench component needs the strains (the tendon law's solve
  /// with actuators) again.
  NodeData moved_node(const State& xp, int j, int k) const {
    if (k >= kFirstWrench) return node_from(xp, j);
    NodeData n = node_[j];
    if (k >= 4) {
      n.p = L_ * xp.segment<3>(4);
      return n;
    }
    n.q = Quaternion(xp[0], xp[1], xp[2], xp[3]);
    n.R = SO3::from_quaternion(n.q);
    n.left.dLambda = P_.wrench_derivative(n.R, n.left.xi, n.left.Lambda);
    n.right.dLambda = breakpoint_[j] ? P_.wrench_derivative(n.R, n.right.xi, n.right.Lambda)
                                     : n.left.dLambda;
    return n;
  }

  /// The 13 scaled rows of interval i, from node a to node b (see the header):
  /// Hermite-Simpson (Lobatto IIIA) on the chart ODE Theta' = dexp^-1_{-Theta} xi (2.84),
  /// Lambda' = ad_xi^T Lambda - W_bar(R_a exp(Theta)), Theta(0) = 0, Theta(h) = log(g_a^-1 g_b).
  /// With actuators the strain is the tendon law with the interval's active set, and `lengths`
  /// (if given) receives the Simpson quadrature of each active path's length rate (the
  /// scheme's own quadrature: order 4).
  Rows interval(int i, const NodeData& a, const NodeData& b, Lengths* lengths = nullptr) const {
    return interval(i, a, b, chart(a, b), lengths);
  }

  /// Theta(h) = log(g_a^-1 g_b) of an interval: the part of its rows that depends on the two
  /// poses only (the Jacobian's wrench columns keep it).
  static Vector6 chart(const NodeData& a, const NodeData& b) {
    const Vector3 phi = (a.R.inverse() * b.R).log();
    Vector6 Theta;
    Theta << phi, lie::so3::dexp_inv_apply(phi, a.R.inverse() * Vector3(b.p - a.p));
    return Theta;
  }

  /// The chart's rate at the interval's end b, dexp^-1_{-Theta} xi_b.
  static Vector6 end_rate(const NodeData& b, const Vector6& Theta) {
    return lie::small_angle::dexp_inv_apply(-Theta, b.left.xi);
  }

  /// The rows with the chart Theta of the two poses given, and with end_rate(b, Theta) if
  /// known (the Jacobian's wrench columns of node a keep it).
  Rows interval(int i, const NodeData& a, const NodeData& b, const Vector6& Theta,
                Lengths* lengths, const Vector6* F_b_known = nullptr) const {
    const double h = h_[i];
    const Side& A = a.right;
    const Side& B = b.left;
    const Vector6 F_a = A.xi;  // dexp^-1_0 = I
    const Vector6 F_b = F_b_known ? *F_b_known : end_rate(b, Theta);
    // Midpoint stage from the cubic Hermite interpolants (compressed form).
    const Vector6 Theta_m = 0.5 * Theta + (h / 8.0) * (F_a - F_b);
    const Vector6 Lambda_m = 0.5 * (A.Lambda + B.Lambda) + (h / 8.0) * (A.dLambda - B.dLambda);
    const double s_m = s_[i] + 0.5 * h;
    const Vector6 xi_m = strain_at(Lambda_m, s_m, mask_[i]);
    const SO3 R_m = a.R * SO3::exp(Theta_m.head<3>());
    const Vector6 F_m = lie::small_angle::dexp_inv_apply(-Theta_m, xi_m);
    const Vector6 dLambda_m = P_.wrench_derivative(R_m, xi_m, Lambda_m);
    const Vector6 pose = Theta - (h / 6.0) * (F_a + 4.0 * F_m + F_b);
    const Vector6 wrench = (B.Lambda - A.Lambda) - (h / 6.0) * (A.dLambda + 4.0 * dLambda_m + B.dLambda);
    Rows r;
    r.head<3>() = (L_ / h) * pose.head<3>();     // rad per unit s/L
    r.segment<3>(3) = pose.tail<3>() / h;         // m per m
    r.segment<6>(6) = (L_ / h) * wrench.cwiseQuotient(scale_.tail<6>());
    r[12] = b.q.squaredNorm() - 1.0;
    if (lengths) {
      lengths->fill(0.0);
      const auto& acts = P_.actuators();
      const double sa = s_[i] + 1e-12 * L_, sb = s_[i + 1] - 1e-12 * L_;
      for (std::size_t k = 0; k < acts.size(); ++k)
        if ((mask_[i] >> k) & 1U)
          (*lengths)[k] = (h / 6.0) * (acts[k].path.length_rate(sa, A.xi) + 4.0 * acts[k].path.length_rate(s_m, xi_m) +
                                       acts[k].path.length_rate(sb, B.xi));
    }
    return r;
  }

  /// Tip rows (see the header).
  Vector6 tip_rows(const NodeData& n) const {
    if (P_.tip_clamped()) {
      const SE3 target = P_.tip_target();
      const Quaternion e = target.rotation().quaternion().conjugate() * n.R.quaternion();
      return lie::se3::join(2.0 * e.vec(), (n.p - target.translation()) / L_);
    }
    return P_.tip_residual(SE3(n.R, n.p), n.left.Lambda);
  }

  /// Sets the extra unknowns (actuator forces or muscle lengths) of x in the problem.
  void set_extra(const ConstRef& x) {
    if (extra_) P_.set_extra_unknowns(std::span<const double>(x.data() + kState * N_, extra_));
  }

  void residual(const ConstRef& x, Ref F) {
    set_extra(x);
    for (int i = 0; i < N_; ++i) node_[i] = node(x, i);
    base_rows(x, F);
    Lengths total{};
    for (int i = 0; i + 1 < N_; ++i) {
      F.segment<kState>(kBaseRows + kState * i) = interval(i, node_[i], node_[i + 1], extra_ ? &lengths_[i] : nullptr);
      if (extra_)
        for (int k = 0; k < StaticProblem::kMaxActuators; ++k) total[k] += lengths_[i][k];
    }
    F.segment<kTipRows>(kState * N_ - kTipRows) = tip_rows(node_[N_ - 1]);
    if (extra_) P_.extra_residuals(total, std::span<double>(F.data() + kState * N_, extra_));
  }

  /// Block-bidiagonal pattern: the columns of node j have the rows [first_row(j), last_row(j)]
  /// and the extra rows (path-length conditions); the extra columns are dense. A function of
  /// pattern_key() alone.
  Sparse pattern() const {
    std::vector<int> outer(size() + 1), inner;
    inner.reserve(static_cast<std::size_t>(kState) * (2 * kState + extra_) * N_ +
                  static_cast<std::size_t>(extra_) * size());
    auto rows = [&](int first, int last) {
      for (int r = first; r <= last; ++r) inner.push_back(r);
    };
    for (int j = 0; j < N_; ++j)
      for (int c = kState * j; c < kState * (j + 1); ++c) {
        outer[c] = static_cast<int>(inner.size());
        rows(first_row(j), last_row(j));
        rows(kState * N_, size() - 1);
      }
    for (int c = kState * N_; c < size(); ++c) {
      outer[c] = static_cast<int>(inner.size());
      rows(0, size() - 1);
    }
    const int nnz = outer[size()] = static_cast<int>(inner.size());
    const std::vector<double> ones(nnz, 1.0);
    return Sparse(Eigen::Map<const Sparse>(size(), size(), nnz, outer.data(), inner.data(), ones.data()));
  }

  /// Forward differences node by node: a column of node j re-evaluates node j's data and the
  /// (at most two) intervals, base or tip rows it enters; the base rows are exact. An extra
  /// unknown's column re-evaluates the whole residual.
  void jacobian(const ConstRef& x, Sparse& J) {
    set_extra(x);
    for (int i = 0; i < N_; ++i) node_[i] = node(x, i);
    Lengths total{};
    for (int i = 0; i + 1 < N_; ++i) {
      chart_[i] = chart(node_[i], node_[i + 1]);
      end_rate_[i] = end_rate(node_[i + 1], chart_[i]);
      rows_[i] = interval(i, node_[i], node_[i + 1], chart_[i], extra_ ? &lengths_[i] : nullptr,
                          &end_rate_[i]);
      if (extra_)
        for (int k = 0; k < StaticProblem::kMaxActuators; ++k) total[k] += lengths_[i][k];
    }
    std::vector<double> extra0(extra_);
    extra1_.resize(extra_);
    if (extra_) P_.extra_residuals(total, extra0);
    const Vector6 tip0 = tip_rows(node_[N_ - 1]);
    double* values = J.valuePtr();
    const int* outer = J.outerIndexPtr();
    const FdBase base{total, extra0, tip0};
    p_columns_.resize(N_ - 1);
    Column d, dq[3];
    for (int j = 0; j < N_; ++j) {
      const State xj = x.segment<kState>(kState * j);
      auto write = [&](int k) {  // column k of node j: the base rows (exact), then d
        double* v = values + outer[kState * j + k];  // its rows, contiguous from first_row(j)
        if (j == 0)
          for (int r = 0; r < kBaseRows; ++r) *v++ = r == k ? 1.0 : 0.0;
        std::copy(d.data(), d.data() + d.size(), v);
      };
      // The quaternion: R depends on q / |q| alone, so the rows but |q|^2 - 1 have no radial
      // derivative, and its four columns are combinations of three tangent ones.
      const Eigen::Vector4d q = xj.head<4>();
      const Eigen::Matrix<double, 4, 3> T = quaternion_tangents(q);
      for (int i = 0; i < 3; ++i) {
        State xp = xj;
        xp.head<4>() += kFdStep * T.col(i);
        differences(j, moved_node(xp, j, 0), false, kFdStep, true, base, dq[i]);
      }
      for (int k = 0; k < 4; ++k) {
        d = T(k, 0) * dq[0] + T(k, 1) * dq[1] + T(k, 2) * dq[2];
        if (j >= 1) d[kState - 1] = 2.0 * q[k];  // interval j - 1's |q_j|^2 - 1
        write(k);
      }
      // The position: the rows depend on it through R_a^T (p_b - p_a) alone, so an interval's
      // columns of p_b are those of p_a negated (kept in p_columns_ from node j - 1's).
      for (int c = 0; c < 3; ++c) {
        const int k = 4 + c;
        State xp = xj;
        xp[k] += kFdStep * std::max(1.0, std::abs(xj[k]));
        differences(j, moved_node(xp, j, k), false, xp[k] - xj[k], false, base, d);
        if (j >= 1) d.head<kState>() = -p_columns_[j - 1].col(c);
        if (j + 1 < N_) p_columns_[j].col(c) = d.segment<kState>(j >= 1 ? kState : 0);
        write(k);
      }
      for (int k = kFirstWrench; k < kState; ++k) {
        State xp = xj;
        xp[k] += kFdStep * std::max(1.0, std::abs(xj[k]));
        differences(j, moved_node(xp, j, k), true, xp[k] - xj[k], true, base, d);
        write(k);
      }
    }
    if (extra_) {
      VectorXd F0(size()), F1(size());
      residual(x, F0);
      VectorXd xp = x;
      for (int e = 0; e < extra_; ++e) {
        const int column = kState * N_ + e;
        const double x0 = x[column];
        xp[column] = x0 + kFdStep * std::max(1.0, std::abs(x0));
        const double step = xp[column] - x0;
        residual(xp, F1);
        xp[column] = x0;
        double* v = values + outer[column];
        for (int r = 0; r < size(); ++r) *v++ = (F1[r] - F0[r]) / step;
      }
      set_extra(x);
    }
  }

  /// A Jacobian column's entries below the base rows (at most two intervals, the tip rows, the
  /// extra rows), with no allocation.
  using Column = Eigen::Matrix<double, Eigen::Dynamic, 1, 0,
                               2 * kState + kTipRows + StaticProblem::kMaxActuators, 1>;
  /// What the columns are differenced against: the path lengths, extra rows and tip rows at x.
  struct FdBase {
    const Lengths& total;
    const std::vector<double>& extra0;
    const Vector6& tip0;
  };

  /// The forward differences (F(x + step e) - F(x)) / step of the rows node j enters below the
  /// base rows (interval j - 1, interval j, the tip rows, the extra rows), node j's data moved to
  /// np; `before` false leaves interval j - 1's rows to the caller (a position column, whose
  /// path lengths do not change). A wrench column keeps the intervals' charts.
  void differences(int j, const NodeData& np, bool wrench_column, double step, bool before,
                   const FdBase& base, Column& d) {
    d.resize((j >= 1 ? kState : 0) + (j + 1 < N_ ? kState : 0) + (j == N_ - 1 ? kTipRows : 0) +
             extra_);
    Lengths changed = base.total, dl{};
    int at = 0;
    if (j >= 1) {  // interval j - 1: node j is its right end
      if (before) {
        const Vector6 Theta = wrench_column ? chart_[j - 1] : chart(node_[j - 1], np);
        d.segment<kState>(at) =
            (interval(j - 1, node_[j - 1], np, Theta, extra_ ? &dl : nullptr) - rows_[j - 1]) /
            step;
        if (extra_)
          for (int a = 0; a < StaticProblem::kMaxActuators; ++a)
            changed[a] += dl[a] - lengths_[j - 1][a];
      }
      at += kState;
    }
    if (j + 1 < N_) {  // interval j: node j is its left end
      const Vector6 Theta = wrench_column ? chart_[j] : chart(np, node_[j + 1]);
      d.segment<kState>(at) = (interval(j, np, node_[j + 1], Theta, extra_ ? &dl : nullptr,
                                        wrench_column ? &end_rate_[j] : nullptr) -
                               rows_[j]) /
                              step;
      if (extra_)
        for (int a = 0; a < StaticProblem::kMaxActuators; ++a) changed[a] += dl[a] - lengths_[j][a];
      at += kState;
    }
    if (j == N_ - 1) {
      d.segment<kTipRows>(at) = (tip_rows(np) - base.tip0) / step;
      at += kTipRows;
    }
    if (extra_) {
      P_.extra_residuals(changed, extra1_);
      for (int r = 0; r < extra_; ++r) d[at + r] = (extra1_[r] - base.extra0[r]) / step;
    }
  }

  /// An orthonormal basis of the tangent space at q / |q| of the unit quaternions, [w x y z]
  /// columns: (q / |q|) (x) [0; e_i] = [-v_i; w e_i + v x e_i].
  static Eigen::Matrix<double, 4, 3> quaternion_tangents(const Eigen::Vector4d& q) {
    const Eigen::Vector4d u = q.normalized();
    const Vector3 v = u.tail<3>();
    Eigen::Matrix<double, 4, 3> T;
    for (int i = 0; i < 3; ++i) {
      T(0, i) = -v[i];
      T.block<3, 1>(1, i) = u[0] * Vector3::Unit(i) + v.cross(Vector3::Unit(i));
    }
    return T;
  }

  /// The reference configuration g(s) = base exp(s xi*) with, for a free tip, the undeformed
  /// rod's equilibrium wrench ((2.34) marched back from the tip with RK4 along it, minus the
  /// pull of cables entering at breakpoints); zero wrench for a clamped tip (its reaction is
  /// unknown; zero keeps the pose rows exact). Extra unknowns at their initial guess. Scaled.
  VectorXd reference_guess() {
    const rod::RodModel& model = P_.model();
    const SE3& base = P_.base();
    VectorXd x(size());
    const auto z = P_.extra_initial_guess();
    for (int e = 0; e < extra_; ++e) x[kState * N_ + e] = z[e];
    set_extra(x);
    auto rotation_at = [&](double s) { return base.rotation() * model.rest_rotation(s); };
    Vector6 xi_star = model.xi_star();  // of the interval in progress (nodes at every break)
    auto dLambda = [&](double s, const Vector6& Lambda) {
      return P_.wrench_derivative(rotation_at(s), xi_star, Lambda);
    };
    const bool march = !P_.tip_clamped();
    Vector6 Lambda = march ? P_.tip_load(rotation_at(L_)) : Vector6::Zero();
    for (int i = N_ - 1; i >= 0; --i) {
      const double s = s_[i];
      if (march && i < N_ - 1) {  // classical RK4 from s + h back to s
        const double h = h_[i];
        const double sb = s_[i + 1];
        xi_star = model.xi_star(s + 0.5 * h);
        const Vector6 k1 = dLambda(sb, Lambda);
        const Vector6 k2 = dLambda(sb - 0.5 * h, Lambda - 0.5 * h * k1);
        const Vector6 k3 = dLambda(sb - 0.5 * h, Lambda - 0.5 * h * k2);
        const Vector6 k4 = dLambda(s, Lambda - h * k3);
        Lambda -= h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
        if (breakpoint_[i]) Lambda -= P_.entry_jump(s, model.xi_star(s - 1e-12 * L_));
      }
      x.segment<kState>(kState * i) = scaled(i == 0 ? base : base * model.rest_pose(s), Lambda);
    }
    return x;
  }

  /// For a clamped tip: the rod of constant strain xi_c = log(base^-1 g_target) / L that joins
  /// base and target (the reference configuration when the target is the reference tip), with
  /// Lambda = K (xi_c - xi*). It is the exact answer for targets on a constant-strain arc, and
  /// away from the straight rod, where a Kirchhoff rod's axial force is indeterminate.
  VectorXd geodesic_guess() {
    const SE3& base = P_.base();
    const Vector6 xi_c = (base.inverse() * P_.tip_target()).log() / L_;
    const Vector6 Lambda = P_.rod_wrench(xi_c, 0.0);  // (rest-strain spans: the first span's)
    VectorXd x(size());
    const auto z = P_.extra_initial_guess();
    for (int e = 0; e < extra_; ++e) x[kState * N_ + e] = z[e];
    for (int i = 0; i < N_; ++i)
      x.segment<kState>(kState * i) = scaled(i == 0 ? base : base * SE3::exp(s_[i] * xi_c), Lambda);
    return x;
  }

  /// The scaled unknowns of a node.
  State scaled(const SE3& g, const Vector6& Lambda) const {
    const Quaternion& q = g.rotation().quaternion();
    State y;
    y << q.w(), q.x(), q.y(), q.z(), g.translation() / L_, Lambda.cwiseQuotient(scale_.tail<6>());
    return y;
  }

  /// Below this max norm a residual is at the rounding level of the rows (differences of O(1)
  /// unknowns divided by h / L, and the unknowns' own size).
  double rounding_floor(const ConstRef& x) const {
    return 64.0 * std::numeric_limits<double>::epsilon() * (L_ / h_min_) *
           std::max(1.0, x.lpNorm<Eigen::Infinity>());
  }

 private:
  static constexpr double kFdStep = 1.5e-8;  // ~ sqrt(eps), relative to max(1, |x|)

  /// Nodes at every breakpoint: the N - 1 intervals are shared among the stretches between
  /// breakpoints in proportion to their lengths (at least one each), uniform within a stretch.
  /// Without breakpoints the mesh is uniform, s_i = i L / (N - 1).
  void build_mesh() {
    std::vector<double> cuts{0.0};
    for (double b : P_.breakpoints()) cuts.push_back(b);
    cuts.push_back(L_);
    const int stretches = static_cast<int>(cuts.size()) - 1;
    const int intervals = N_ - 1;
    RODLAB_THROW_UNLESS(
        intervals >= stretches,
        "kinsol: {} nodes cannot hold the {} breakpoints (need at least {})", N_,
        stretches - 1, stretches + 1);
    std::vector<double> ideal(stretches);
    std::vector<int> count(stretches);
    int total = 0;
    for (int k = 0; k < stretches; ++k) {
      ideal[k] = (cuts[k + 1] - cuts[k]) / L_ * intervals;
      count[k] = std::max(1, static_cast<int>(std::floor(ideal[k])));
      total += count[k];
    }
    while (total > intervals) {  // take from the most over-served stretch that can spare one
      int best = -1;
      for (int k = 0; k < stretches; ++k)
        if (count[k] > 1 && (best < 0 || count[k] - ideal[k] > count[best] - ideal[best])) best = k;
      --count[best];
      --total;
    }
    while (total < intervals) {  // give to the most under-served stretch
      int best = 0;
      for (int k = 1; k < stretches; ++k)
        if (ideal[k] - count[k] > ideal[best] - count[best]) best = k;
      ++count[best];
      ++total;
    }
    s_.assign(N_, 0.0);
    h_.assign(N_ - 1, 0.0);
    mask_.assign(N_ - 1, 0U);
    breakpoint_.assign(N_, false);
    int i = 0;
    h_min_ = L_;
    for (int k = 0; k < stretches; ++k) {
      const double a = cuts[k], h = (cuts[k + 1] - a) / count[k];
      h_min_ = std::min(h_min_, h);
      const auto mask = P_.has_actuators() ? P_.active_mask(a + 0.5 * h) : 0U;
      breakpoint_[i] = k > 0;
      for (int c = 0; c < count[k]; ++c, ++i) {
        s_[i] = c == 0 ? a : a + c * h;
        h_[i] = h;
        mask_[i] = mask;
      }
    }
    s_[N_ - 1] = L_;
  }

  int first_row(int j) const { return j == 0 ? 0 : kBaseRows + kState * (j - 1); }
  int last_row(int j) const { return j == N_ - 1 ? kState * N_ - 1 : kBaseRows + kState * (j + 1) - 1; }

  void base_rows(const ConstRef& x, Ref F) const {
    const Quaternion& qb = P_.base().rotation().quaternion();
    F[0] = x[0] - qb.w();
    F[1] = x[1] - qb.x();
    F[2] = x[2] - qb.y();
    F[3] = x[3] - qb.z();
    F.segment<3>(4) = x.segment<3>(4) - P_.base().translation() / L_;
  }

  StaticProblem P_;
  int N_;
  double L_;
  int extra_;
  double h_min_ = 0.0;
  State scale_;
  std::vector<double> s_, h_;                 // node positions; interval lengths
  std::vector<StaticProblem::Mask> mask_;     // per interval: its active actuators
  std::vector<bool> breakpoint_;              // per node: at a breakpoint (never 0 or L)
  std::vector<NodeData> node_;  // workspace: node data at the current x
  std::vector<Rows> rows_;      // workspace: interval rows at the current x
  std::vector<Vector6> chart_;  // workspace: interval charts Theta at the current x
  std::vector<Vector6> end_rate_;  // workspace: their end_rate at the current x
  std::vector<Lengths> lengths_;  // workspace: interval path-length quadratures at the current x
  std::vector<Eigen::Matrix<double, kState, 3>> p_columns_;  // workspace: interval i's rows' d/dp_a
  std::vector<double> extra1_;  // workspace: the extra rows of a moved column
};

/// KINSOL for the collocation's pattern, kept on this thread from one solve to the next of the
/// same pattern (repeated solves: a study's sweep, the inverse statics and controllers that call
/// the statics as their model, the benchmarks): its SUNDIALS objects are made once. The Newton
/// systems go to the almost block diagonal LU (the Jacobian's staircase, bordered by the extra
/// unknowns' dense rows and columns; KLU, analysed once, for a bordered matrix it refuses). Every
/// KINSOL run factorises its first Jacobian afresh, so a solve does not depend on the ones
/// before; with KLU alone, keeping the factors too
/// (refactorising on the last solve's pivots) was faster still, 1.9 against 2.1 ms at N = 100,
/// but lost kinsol's large-tension case (tests/statics/test_chebyshev_actuators.cpp, N = 161):
/// pivots from the previous continuation step left its line search without descent. A solve
/// that starts while another holds the kept solver (nested solves) gets a solver of its own.
class ThreadSolver {
 public:
  explicit ThreadSolver(const Collocation& C) {
    Slot& slot = this_thread_slot();
    auto make = [&C] {
      return std::make_unique<KinsolSolver>(C.pattern(), KluReuse::analysis, KluOrder::natural,
                                            NewtonLinearSolver::almost_block_diagonal);
    };
    if (slot.in_use) {
      own_ = make();
      solver_ = own_.get();
      return;
    }
    if (!slot.solver || slot.key != C.pattern_key()) {
      slot.solver.reset();  // releases the old factors first
      slot.solver = make();
      slot.key = C.pattern_key();
    }
    slot.in_use = true;
    slot_ = &slot;
    solver_ = slot.solver.get();
  }
  ~ThreadSolver() {
    if (slot_) slot_->in_use = false;
  }
  ThreadSolver(const ThreadSolver&) = delete;
  ThreadSolver& operator=(const ThreadSolver&) = delete;

  KinsolSolver& get() { return *solver_; }

 private:
  struct Slot {
    std::pair<int, int> key;  // Collocation::pattern_key
    std::unique_ptr<KinsolSolver> solver;
    bool in_use = false;
  };
  static Slot& this_thread_slot() {
    static thread_local Slot slot;
    return slot;
  }
  Slot* slot_ = nullptr;
  std::unique_ptr<KinsolSolver> own_;
  KinsolSolver* solver_ = nullptr;
};

class Driver {
 public:
  Driver(const StaticProblem& problem, const KinsolCollocationOptions& options)
      : C_(problem, options.nodes), options_(options),
        solver_(C_) {
    kinsol_.fnormtol = options.tol;
    kinsol_.scsteptol = options.step_tol;
    kinsol_.max_iterations = options.max_iterations;
    kinsol_.line_search = true;
    // A Jacobian (finite differences and a factorisation) at every third iteration: the
    // gravity cantilever at N = 100 takes 5 iterations and 2 Jacobians, 2.2 ms, against 4 and 4,
    // 3.6 ms with one per iteration (6 and 7 iterations, 2.24 and 2.42 ms, with one every 4th
    // or 5th; bench_statics). The converged residual is held to the same tolerance.
    kinsol_.max_setup_calls = 3;
  }

  /// One KINSOL run (line search) at a load factor, with at most max_iterations if > 0, to the
  /// tolerance `tol` if > 0 (else the options'). A stop (KIN_STEP_LT_STPTOL: no further progress,
  /// KIN_LINESEARCH_NONCONV: no descent, KIN_MAXITER_REACHED) at a residual on the rounding floor
  /// of the rows counts as converged: a tolerance below that floor cannot be met by any iterate
  /// (N = 200, tol 1e-12 under a dead load of P L^2/EI = 41 stalled the continuation at load
  /// factor 0.81 by line search failures at 3e-12; test_dead_load_branch).
  KinsolStats solve_at(double load_factor, VectorXd& x, int max_iterations = 0, double tol = 0.0) {
    C_.problem().set_load_factor(load_factor);
    KinsolOptions options = kinsol_;
    if (max_iterations > 0) options.max_iterations = std::min(max_iterations, options.max_iterations);
    if (tol > 0.0) options.fnormtol = tol;
    KinsolStats stats = solver_.get().solve(
        x, [this](const ConstRef& u, Ref F) { C_.residual(u, F); },
        [this](const ConstRef& u, const ConstRef&, Sparse& J) { C_.jacobian(u, J); }, options);
    ++report_.kinsol_solves;
    report_.nonlinear_iterations += stats.nonlinear_iterations;
    report_.function_evaluations += stats.function_evaluations;
    report_.jacobian_evaluations += stats.jacobian_evaluations;
    report_.backtracks += stats.backtracks;
    report_.flag = stats.flag_name;
    if (!stats.converged &&
        (stats.flag_name == "KIN_STEP_LT_STPTOL" || stats.flag_name == "KIN_LINESEARCH_NONCONV" ||
         stats.flag_name == "KIN_MAXITER_REACHED") &&
        residual_norm(x) <= std::max(options.fnormtol, C_.rounding_floor(x)))
      stats.converged = true;
    return stats;
  }

  double residual_norm(const VectorXd& x) {
    VectorXd F(C_.size());
    C_.residual(x, F);
    return F.lpNorm<Eigen::Infinity>();
  }

  /// The initial guess at a load factor: the reference configuration, or for a clamped tip the
  /// constant-strain rod to the target.
  VectorXd guess_at(double load_factor) {
    C_.problem().set_load_factor(load_factor);
    return C_.problem().tip_clamped() ? C_.geodesic_guess() : C_.reference_guess();
  }

  /// 1. Direct: Newton with KINSOL's line search at load factor 1 from the initial guess(es)
  ///    (a clamped tip has two: the constant-strain rod to the target and the reference
  ///    configuration with zero wrench, tried in the order of their residual norms), at most
  ///    15 iterations. Accepted only when the line search never had to cut a step, i.e. the
  ///    guess was inside Newton's basin: from further away Newton can land on another
  ///    equilibrium (a coiled rod under a large dead load, say) than the load path reaches.
  /// 2. Otherwise load continuation, which follows the load path from the unloaded rod.
  /// 3. If that fails too, the direct solves again with the full iteration budget, accepting
  ///    backtracking.
  KinsolCollocationReport run() {
    const auto start = std::chrono::steady_clock::now();
    std::vector<VectorXd> guesses{guess_at(1.0)};
    if (C_.problem().tip_clamped()) {
      guesses.push_back(C_.reference_guess());
      if (residual_norm(guesses[1]) < residual_norm(guesses[0])) std::swap(guesses[0], guesses[1]);
    }
    std::string reason;
    VectorXd best;  // the first direct iterate, reported if nothing converges
    auto note = [&](const KinsolStats& stats, const char* what) {
      reason += (reason.empty() ? "" : "; ") + describe(stats) + " (" + what +
                (stats.converged ? ", with backtracking)" : ")");
    };
    if (options_.direct) {
      for (const VectorXd& guess : guesses) {
        VectorXd x = guess;
        const KinsolStats stats = solve_at(1.0, x, kDirectIterations);
        if (stats.converged && stats.backtracks == 0) return finish(x, true, "", "direct", start);
        if (best.size() == 0) best = x;
        note(stats, "direct");
      }
    }
    if (options_.continuation) {
      report_.used_continuation = true;
      VectorXd xc;
      std::string why;
      if (continuation(xc, why)) return finish(xc, true, "", "continuation", start);
      reason += "; continuation: " + why;
    }
    if (options_.direct && options_.max_iterations > kDirectIterations) {
      for (const VectorXd& guess : guesses) {
        VectorXd x = guess;
        const KinsolStats stats = solve_at(1.0, x);
        if (stats.converged) return finish(x, true, "", "direct, with backtracking", start);
        note(stats, "direct, full budget");
      }
    }
    if (best.size() == 0) best = guesses.front();
    return finish(best, false, reason, "none", start);
  }

 private:
  static std::string describe(const KinsolStats& s) { return s.flag_name; }

  /// Load continuation through the shared driver (continuation.hpp): from load factor 0, where
  /// the initial guess is exact, to 1; each corrector is a KINSOL solve with the line search
  /// (at most kCorrectorIterations). A walk that fails below kWalkTol is walked again to it and
  /// polished (continue_load_to): a soft cantilever, E = 2500 Pa under gravity, N = 100, tol
  /// 1e-12, stalled at load factor 0.30, its correctors stopping at residuals of 1.1-2.4e-12
  /// with line-search cuts in the rounding noise (test_kinsol).
  bool continuation(VectorXd& x, std::string& why) {
    auto walk_at = [this](double tol) {
      Continuation walk;
      walk.correct = [this, tol](double lf, const VectorXd& guess) {
        CorrectorResult r;
        r.state = guess;
        const KinsolStats stats = solve_at(lf, r.state, kCorrectorIterations, tol);
        // A corrector that needs many iterations or cuts a step has left the branch's basin:
        // the step is halved instead (so the walk cannot jump to another branch).
        r.converged = stats.converged && stats.backtracks == 0;
        r.reason = describe(stats);
        r.residual_norm = residual_norm(r.state);
        return r;
      };
      walk.first_predictor = [this](double from, double to, const VectorXd& state) {
        return VectorXd(state + guess_at(to) - guess_at(from));
      };
      return walk;
    };
    auto polish = [this](const VectorXd& state) {
      CorrectorResult r;
      r.state = state;
      const KinsolStats stats = solve_at(1.0, r.state);
      r.converged = stats.converged;
      r.reason = describe(stats);
      r.residual_norm = residual_norm(r.state);
      return r;
    };
    const ContinuationResult result =
        continue_load_to(kinsol_.fnormtol, walk_at, guess_at(0.0), polish);
    x = result.state;
    why = result.reason;
    return result.converged;
  }

  KinsolCollocationReport finish(const VectorXd& x, bool converged, const std::string& reason,
                                 const char* strategy, std::chrono::steady_clock::time_point start) {
    C_.problem().set_load_factor(1.0);
    const StaticProblem& P = C_.problem();
    VectorXd F(C_.size());
    C_.residual(x, F);
    const int N = C_.nodes();
    std::vector<double> s(N);
    std::vector<SE3> g(N);
    std::vector<Vector6> Lambda(N);
    double q_error = 0.0;
    for (int i = 0; i < N; ++i) {
      const NodeData n = C_.node(x, i);
      q_error = std::max(q_error, std::abs(n.q.norm() - 1.0));
      s[i] = P.breakpoints().empty() ? P.length() * i / (N - 1) : C_.s(i);
      g[i] = SE3(n.R, n.p);
      Lambda[i] = i + 1 < N ? n.right.Lambda : n.left.Lambda;  // as shooting: after an entry
    }
    auto& out = report_.result;
    fill_static_result(P, s, g, Lambda, out);
    out.scene = P.name();
    out.scheme = "kinsol";
    out.converged = converged;
    out.reason = reason;
    out.iterations = static_cast<int>(report_.nonlinear_iterations);
    out.residual_norm = F.lpNorm<Eigen::Infinity>();
    check_cables_taut(P, out);
    out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_.max_quaternion_norm_error = q_error;
    report_.strategy = strategy;
    return report_;
  }

  static constexpr int kDirectIterations = 15;    // Newton inside its basin needs fewer
  static constexpr int kCorrectorIterations = 8;  // per continuation step

  Collocation C_;
  KinsolCollocationOptions options_;
  ThreadSolver solver_;  // block-banded in node order (the KLU fallback's natural order)
  KinsolOptions kinsol_;
  KinsolCollocationReport report_;
};

}  // namespace

KinsolCollocationReport solve_kinsol_collocation_report(const StaticProblem& problem,
                                                        const KinsolCollocationOptions& options) {
  RODLAB_THROW_UNLESS(options.nodes >= 2, "kinsol: nodes must be >= 2, got {}", options.nodes);
  if (!(options.tol > 0.0) || !(options.step_tol > 0.0) || options.max_iterations < 1)
    throw std::invalid_argument("kinsol: tol and step_tol must be > 0 and max_iterations >= 1");
  if (!options.direct && !options.continuation)
    throw std::invalid_argument("kinsol: direct and continuation cannot both be off");
  return Driver(problem, options).run();
}

result::StaticResult solve_kinsol_collocation(const StaticProblem& problem,
                                              const KinsolCollocationOptions& options) {
  return solve_kinsol_collocation_report(problem, options).result;
}

}  // namespace rodlab::solvers::statics
