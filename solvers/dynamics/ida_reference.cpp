#include "rodlab/solvers/dynamics/ida_reference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "rodlab/rod/characteristics.hpp"
#include "rodlab/solvers/common/ida_solver.hpp"

namespace rodlab::solvers::dynamics {
namespace {

namespace se3 = lie::se3;
using Vector = Eigen::VectorXd;
using ConstRef = Eigen::Ref<const Vector>;

/// Unknowns per node: p (3), q = [w x y z] (4), eta = [psi; kappa] (6).
constexpr int kBlock = 13;
constexpr int kP = 0, kQ = 3, kEta = 7;
/// Node colours of the finite-difference Jacobian: node j's rows depend on nodes j-1..j+1.
constexpr int kColours = 3;

class IdaReference final : public Stepper {
 public:
  IdaReference(const DynamicProblem& problem, const IdaOptions& options, std::span<const SE3> g0)
      : P_(problem), n_(options.nodes) {
    if (n_ < 3) throw std::invalid_argument("ida: nodes must be >= 3");
    if (static_cast<int>(g0.size()) != n_)
      throw std::invalid_argument("ida: expected " + std::to_string(n_) + " initial poses, got " +
                                  std::to_string(g0.size()));
    if (problem.is_kirchhoff())
      throw std::invalid_argument("ida: rod.model kirchhoff is not supported yet");
    if (!(options.rtol > 0.0) || !(options.atol > 0.0))
      throw std::invalid_argument("ida: rtol and atol must be > 0");
    if (options.max_steps < 1) throw std::invalid_argument("ida: max_steps must be >= 1");
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
    for (double s : problem.entry_points()) {
      const int j = static_cast<int>(std::lround(s / ds_));
      if (j > 0 && j < n_) entries_.push_back({s, j});
    }

    // Characteristic scales (ida_reference.hpp): omega_1, L omega_1, E_bend.
    const auto c = rod::characteristics(model, n_, rod::TipSupport::free);
    const double omega1 = 2.0 * std::numbers::pi * c.first_bending_frequency_hz;
    const double EI = std::min(model.K_diag()[0], model.K_diag()[1]);
    const double e_bend = 0.5 * EI * std::pow(0.5 * std::numbers::pi / L, 2) * L;
    scale_.resize(dim_);
    for (int j = 1; j < n_; ++j) {
      auto b = scale_.segment<kBlock>(kBlock * (j - 1));
      b.segment<3>(kP).setConstant(L);
      b.segment<4>(kQ).setConstant(1.0);
      b.segment<3>(kEta).setConstant(omega1);
      b.segment<3>(kEta + 3).setConstant(L * omega1);
    }
    scale_[iD_] = scale_[iW_] = e_bend;
    IdaSolverOptions io;
    io.rtol = options.rtol;
    io.atol = options.atol * scale_;
    // Positions are absolute in metres (not relative to L).
    for (int j = 1; j < n_; ++j) io.atol.segment<3>(kBlock * (j - 1) + kP).setConstant(options.atol);
    io.max_steps = options.max_steps;

    f0_.resize(dim_);
    f1_.resize(dim_);
    ytmp_.resize(dim_);
    seg0_diss_ = seg_diss_;
    seg0_work_ = seg_work_;
    node0_diss_ = node_diss_;
    node0_work_ = node_work_;

    ida_ = std::make_unique<IdaSolver>(
        pattern(),
        [this](double t, const ConstRef& y, const ConstRef& yp, Eigen::Ref<Vector> r) {
          evaluate(t, y, r);
          r = yp - r;
        },
        [this](double t, double cj, const ConstRef& y, const ConstRef&, const ConstRef&,
               IdaSolver::SparseMatrix& J) { jacobian(t, cj, y, J); },
        io);

    // At rest from g0: y'0 = f(0, y0) is consistent (the system is an ODE).
    Vector y0 = Vector::Zero(dim_);
    for (int j = 1; j < n_; ++j) {
      auto b = y0.segment<kBlock>(kBlock * (j - 1));
      b.segment<3>(kP) = g0[j].translation();
      const lie::Quaternion& q = g0[j].rotation().quaternion();
      b.segment<4>(kQ) << q.w(), q.x(), q.y(), q.z();
    }
    g_[0] = problem.base();
    Vector yp0(dim_);
    evaluate(0.0, y0, yp0);
    ida_->initialize(0.0, y0, yp0);
    unpack(ida_->y());
  }

  StepStatus step(double t, double dt) override {
    if (!(dt > 0.0) || !std::isfinite(t + dt)) return StepStatus::failed("ida: dt must be > 0");
    if (std::abs(t - ida_->time()) > 1e-12 * std::max(1.0, std::abs(t))) {
      // Not where IDA stands: restart there from the current state (an ODE: y' = f(t, y)).
      const Vector y = ida_->y();
      Vector yp(dim_);
      evaluate(t, y, yp);
      ida_->initialize(t, y, yp);
    }
    const IdaStats s = ida_->advance(t + dt);
    unpack(ida_->y());
    if (!s.ok) {
      StepStatus failed = StepStatus::failed("ida: IDASolve failed with " + s.flag_name +
                                             " at t = " + std::to_string(s.t) + " s" +
                                             (s.message.empty() ? "" : " (" + s.message + ")"));
      failed.iterations = static_cast<int>(s.nonlinear_iterations);
      return failed;
    }
    StepStatus ok;
    ok.iterations = static_cast<int>(s.nonlinear_iterations);
    return ok;
  }

  Energy energy() const override {
    const auto y = ida_->y();
    Energy e;
    e.kinetic = kinetic_energy(P_.model(), eta_, ds_);
    e.strain = strain_energy_segments(P_.model(), xi_, ds_);
    e.gravity = gravity_energy(P_, g_, ds_);
    e.dissipated = y[iD_];
    e.work_in = y[iW_];
    return e;
  }

  Vector3 tip_position() const override { return g_.back().translation(); }

  double max_det_deviation() const override {
    double worst = 0.0;
    for (const SE3& g : g_)
      worst = std::max(worst, std::abs(g.rotation_matrix().determinant() - 1.0));
    return worst;
  }

  std::vector<result::CenterlineSample> centerline() const override {
    std::vector<result::CenterlineSample> out(n_);
    for (int j = 0; j < n_; ++j) {
      // node strain: the adjacent segments' mean (one segment at the ends), as `variational`
      const Vector6 xi = j == 0        ? xi_[0]
                         : j == n_ - 1 ? xi_[n_ - 2]
                                       : Vector6(0.5 * (xi_[j - 1] + xi_[j]));
      out[j] = {j * ds_, g_[j], xi};
    }
    return out;
  }

 private:
  struct Entry {
    double s;
    int node;
  };

  /// Node poses (normalised quaternions), velocities and segment strains of y.
  void unpack_nodes(const ConstRef& y) const {
    g_[0] = P_.base();
    eta_[0].setZero();
    for (int j = 1; j < n_; ++j) {
      const double* b = y.data() + kBlock * (j - 1);
      const lie::Quaternion q(b[kQ], b[kQ + 1], b[kQ + 2], b[kQ + 3]);
      g_[j] = SE3(SO3::from_quaternion(q), Vector3(b[kP], b[kP + 1], b[kP + 2]));
      eta_[j] = Eigen::Map<const Vector6>(b + kEta);
    }
  }

  void unpack(const ConstRef& y) const {
    unpack_nodes(y);
    for (int j = 0; j + 1 < n_; ++j) xi_[j] = (g_[j].inverse() * g_[j + 1]).log() / ds_;
  }

  /// f(t, y) of y' = f(t, y), and the per-segment and per-node powers of the ledger.
  void evaluate(double t, const ConstRef& y, Eigen::Ref<Vector> f) const {
    unpack_nodes(y);
    for (int j = 0; j + 1 < n_; ++j) {
      const SE3 G = g_[j].inverse() * g_[j + 1];
      const Vector6 x = G.log();  // ds xi_j
      xi_[j] = x / ds_;
      const Vector6 rel = eta_[j + 1] - G.inverse().Ad_apply(eta_[j]);
      xi_dot_[j] = se3::dexp_inv_apply(-x, rel) / ds_;
      const double s_mid = (j + 0.5) * ds_;
      const Vector6 sigma = P_.internal_wrench(xi_[j], xi_dot_[j], s_mid, t);
      lambda_[j] = se3::dexp_inv_transpose_apply(x, sigma);
      moved_[j] = G.coAd_apply(lambda_[j]);
      seg_diss_[j] = ds_ * xi_dot_[j].dot(V_.cwiseProduct(xi_dot_[j]));
      seg_work_[j] = P_.has_actuators() ? ds_ * P_.actuator_power(xi_[j], xi_dot_[j], s_mid, t) : 0.0;
    }
    double diss = 0.0, work = 0.0;
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

      double* out = f.data() + kBlock * (j - 1);
      const double* b = y.data() + kBlock * (j - 1);
      Eigen::Map<Vector3>(out + kP) = R * Vector3(eta.tail<3>());
      // q_dot = q (x) [0; psi] / 2 on the stored (unnormalised) q.
      const double qw = b[kQ];
      const Vector3 qv(b[kQ + 1], b[kQ + 2], b[kQ + 3]);
      const Vector3 psi = eta.head<3>();
      out[kQ] = -0.5 * qv.dot(psi);
      Eigen::Map<Vector3>(out + kQ + 1) = 0.5 * (qw * psi + qv.cross(psi));
      Eigen::Map<Vector6>(out + kEta) = rhs.cwiseQuotient(M_);
    }
    f[iD_] = diss;
    f[iW_] = work;
  }

  /// Newton matrix cj I - df/dy: block tridiagonal node blocks, the two ledger rows over every
  /// node column, and cj on the ledger columns' diagonal.
  IdaSolver::SparseMatrix pattern() const {
    std::vector<Eigen::Triplet<double>> t;
    for (int k = 1; k < n_; ++k) {
      const int first = std::max(1, k - 1), last = std::min(n_ - 1, k + 1);
      for (int c = 0; c < kBlock; ++c) {
        const int col = kBlock * (k - 1) + c;
        for (int row = kBlock * (first - 1); row < kBlock * last; ++row) t.emplace_back(row, col, 1.0);
        t.emplace_back(iD_, col, 1.0);
        t.emplace_back(iW_, col, 1.0);
      }
    }
    t.emplace_back(iD_, iD_, 1.0);
    t.emplace_back(iW_, iW_, 1.0);
    IdaSolver::SparseMatrix J(dim_, dim_);
    J.setFromTriplets(t.begin(), t.end());
    J.makeCompressed();
    return J;
  }

  /// Finite differences with the nodes of one colour (j mod 3) perturbed together: every row
  /// sees at most one of them; the ledger rows are split into per-segment and per-node terms,
  /// of which a perturbed node k moves segments k-1, k and node k only.
  void jacobian(double t, double cj, const ConstRef& y, IdaSolver::SparseMatrix& J) {
    evaluate(t, y, f0_);
    seg0_diss_ = seg_diss_;
    seg0_work_ = seg_work_;
    node0_diss_ = node_diss_;
    node0_work_ = node_work_;
    const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
    ytmp_ = y;
    for (int colour = 0; colour < kColours; ++colour) {
      const int first = colour == 0 ? kColours : colour;
      if (first > n_ - 1) continue;
      for (int c = 0; c < kBlock; ++c) {
        for (int k = first; k < n_; k += kColours) {
          const int i = kBlock * (k - 1) + c;
          ytmp_[i] = y[i] + root_eps * std::max(std::abs(y[i]), scale_[i]);
        }
        evaluate(t, ytmp_, f1_);
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
          for (IdaSolver::SparseMatrix::InnerIterator it(J, col); it; ++it) {
            const auto row = it.row();
            const double df = row == iD_ ? d_diss : row == iW_ ? d_work : f1_[row] - f0_[row];
            it.valueRef() = (row == col ? cj : 0.0) - df / h;
          }
        }
      }
    }
    J.coeffRef(iD_, iD_) = cj;
    J.coeffRef(iW_, iW_) = cj;
  }

  const DynamicProblem& P_;
  int n_;
  double ds_ = 0.0;
  int dim_ = 0, iD_ = 0, iW_ = 0;
  Vector6 M_, V_;
  Vector scale_;
  std::vector<Entry> entries_;
  std::unique_ptr<IdaSolver> ida_;
  // Work arrays of evaluate() (mutable: energy() and friends unpack the current state).
  mutable std::vector<SE3> g_;
  mutable std::vector<Vector6> eta_, xi_, xi_dot_, lambda_, moved_;
  mutable std::vector<double> seg_diss_, seg_work_, node_diss_, node_work_;
  // Finite-difference Jacobian work arrays.
  Vector f0_, f1_, ytmp_;
  std::vector<double> seg0_diss_, seg0_work_, node0_diss_, node0_work_;
};

}  // namespace

std::unique_ptr<Stepper> make_ida(const DynamicProblem& problem, const IdaOptions& options,
                                  std::span<const SE3> g0) {
  return std::make_unique<IdaReference>(problem, options, g0);
}

}  // namespace rodlab::solvers::dynamics
