#include "rodlab/solvers/dynamics/variational.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rodlab/lie/small_angle.hpp"
#include "rodlab/solvers/common/block_tridiagonal.hpp"

namespace rodlab::solvers::dynamics {
namespace {

namespace se3 = lie::se3;
namespace small = lie::small_angle;
using lie::Matrix6;

/// |nu - nu*| that the Kirchhoff constraint solve reaches (relative to max(1, |nu*|)).
constexpr double kConstraintTol = 1e-12;

class Variational final : public Stepper {
 public:
  Variational(const DynamicProblem& problem, const VariationalOptions& options,
              const RestState& initial)
      : P_(problem), opt_(options), n_(options.nodes), ds_(problem.length() / (n_ - 1)) {
    if (n_ < 3) throw std::invalid_argument("variational: nodes must be >= 3");
    const auto& g0 = initial.g;
    if (static_cast<int>(g0.size()) != n_)
      throw std::invalid_argument("variational: expected " + std::to_string(n_) +
                                  " initial poses, got " + std::to_string(g0.size()));
    kirchhoff_ = problem.is_kirchhoff();
    nu_star_ = problem.model().xi_star().tail<3>();
    g_.assign(g0.begin(), g0.end());
    G_.resize(n_ - 1);
    xi_.resize(n_ - 1);
    for (int j = 0; j + 1 < n_; ++j) {
      G_[j] = g_[j].inverse() * g_[j + 1];
      xi_[j] = G_[j].log() / ds_;
      if (kirchhoff_) {
        // Start on the constraint: a chord of the sampled initial shape is shorter than its arc
        // by O((kappa ds)^2); the segment keeps its rotation and gets nu = nu*.
        xi_[j].tail<3>() = nu_star_;
        G_[j] = SE3::exp(ds_ * xi_[j]);
        g_[j + 1] = g_[j] * G_[j];
      }
    }
    eta_.assign(n_, Vector6::Zero());
    mu_.assign(n_, Vector6::Zero());
    M_ = problem.model().M_diag();
    M_inv_ = M_.cwiseInverse();
    entries_ = problem.entry_nodes(n_);
    if (kirchhoff_) {
      mu_free_.assign(n_, Vector6::Zero());
      f_.assign(n_ - 1, Vector3::Zero());
      c_.assign(n_ - 1, Vector3::Zero());
      B_.assign(n_ - 1, Matrix63::Zero());
      C_.assign(n_ - 1, Matrix63::Zero());
      A_.resize(n_ - 1);
    }
  }

  StepStatus step(double t, double dt) override {
    const double t1 = t + dt;
    const Vector6& V = P_.model().V_diag();
    // A scene pays only for the loads it has: the distributed wrench and drag are skipped when
    // absent (adding their zeros changed nothing, so the result is the same bit for bit).
    const bool applied = (P_.applied_load(SO3(), t1).array() != 0.0).any();
    const bool drag = P_.has_drag();
    const bool actuators = P_.has_actuators();
    double dissipated = 0.0, work = 0.0;
    kinetic_old_ = 0.0;
    // One pass from the base to the tip: segment j needs E^j and E^(j+1) (3.26) from the old
    // velocities; node j needs the stresses of segments j - 1 and j (3.41) and then updates its
    // velocity (3.42), which no later segment reads.
    SE3 E = SE3::identity();  // E^j; the base does not move
    Vector6 lambda_prev = Vector6::Zero();
    for (int j = 0; j + 1 < n_; ++j) {
      const SE3 E_next = small::exp(dt * eta_[j + 1]);
      // (3.38)-(3.40): the new strain from exact compatibility, the pose, the stress.
      G_[j] = E.inverse() * G_[j] * E_next;
      small::EF k;
      const Vector6 x = small::log(G_[j], k);  // ds xi
      const Vector6 xi = x / ds_;
      const Vector6 xi_dot = (xi - xi_[j]) / dt;
      const double s_mid = (j + 0.5) * ds_;
      xi_[j] = xi;
      g_[j + 1] = g_[j] * G_[j];
      const Vector6 lambda = small::dexp_inv_transpose_apply(
          x, kirchhoff_ ? kirchhoff_stress(xi, xi_dot, s_mid, t1)
                        : P_.internal_wrench(xi, xi_dot, s_mid, t1),
          k);
      dissipated += ds_ * xi_dot.dot(V.cwiseProduct(xi_dot));
      if (actuators) work += ds_ * P_.actuator_power(xi, xi_dot, s_mid, t1);
      if (j > 0 && !node(j, t1, dt, E, lambda, lambda_prev, applied, drag, dissipated, work))
        return diverged(j, t1, dt);
      lambda_prev = lambda;
      E = E_next;
    }
    const int tip = n_ - 1;
    if (!node(tip, t1, dt, E, P_.tip_load(g_[tip].rotation(), t1), lambda_prev, applied, drag,
              dissipated, work))
      return diverged(tip, t1, dt);
    if (kirchhoff_) {
      if (const auto failure = enforce_constraints(dt); !failure.empty())
        return StepStatus::failed("variational: the Kirchhoff constraint solve " + failure +
                                  " (t = " + std::to_string(t1) + " s, dt = " +
                                  std::to_string(dt) + " s)");
    }
    ledger_.dissipated += dt * dissipated;
    ledger_.work_in += dt * work;
    return {};
  }

  Energy energy() const override {
    Energy e = ledger_;
    // eta is the velocity over the coming step and the one before was summed during the step:
    // their mean is the kinetic energy at the current time, to O(dt^2).
    e.kinetic = 0.5 * (kinetic_old_ + kinetic_energy(P_.model(), eta_, ds_));
    e.strain = strain_energy_segments(P_.model(), xi_, ds_);
    e.gravity = gravity_energy(P_, g_, ds_);
    return e;
  }

  Vector3 tip_position() const override { return g_.back().translation(); }

  double max_det_deviation() const override { return dynamics::max_det_deviation(g_); }

  std::vector<result::CenterlineSample> centerline() const override {
    return staggered_centerline(g_, xi_, ds_);
  }

 private:
  /// (3.41)-(3.42) at node j: the momentum balance with the inner wrench (lambda^j, or the tip
  /// wrench) and the outer one (lambda^(j-1)), then the new velocity. Accumulates the node's
  /// kinetic energy (old velocity), drag dissipation and external power.
  bool node(int j, double t1, double dt, const SE3& E, const Vector6& inner,
            const Vector6& lambda_prev, bool applied, bool drag, double& dissipated,
            double& work) {
    const bool tip = j == n_ - 1;
    const double w = tip ? 0.5 * ds_ : ds_;
    const SO3& R = g_[j].rotation();
    const Vector6 outer = G_[j - 1].coAd_apply(lambda_prev);
    const Vector6& eta_old = eta_[j];
    kinetic_old_ += 0.5 * w * eta_old.dot(M_.cwiseProduct(eta_old));
    Vector6 bar = P_.gravity_load(R);
    if (applied) {
      const Vector6 a = P_.applied_load(R, t1);
      bar += a;
      work += w * a.dot(eta_old);
    }
    if (drag) {
      const Vector6 d = P_.drag_load(eta_old);
      bar += d;
      dissipated -= w * d.dot(eta_old);
    }
    if (tip) work += inner.dot(eta_old);
    Vector6 force = inner - outer + w * bar;
    for (const auto& e : entries_) {
      if (e.node != j) continue;
      // a point load at the node: its power is entry . eta (as in ida_reference)
      const Vector6 entry = P_.entry_load(e.s, xi_[tip ? j - 1 : j], t1);
      force += entry;
      work += entry.dot(eta_old);
    }
    const Vector6 mu_old = mu_[j];
    mu_[j] = E.coAd_apply(mu_old) + (dt / w) * force;
    if (kirchhoff_) mu_free_[j] = mu_[j];
    return solve_velocity(j, dt, mu_old - mu_[j]);
  }

  /// Kirchhoff rods: the rod's own wrench has no force part (nu = nu* holds; the force across
  /// the section is the constraint force f of enforce_constraints), the actuators act as usual.
  Vector6 kirchhoff_stress(Vector6 xi, Vector6 xi_dot, double s, double t) const {
    xi.tail<3>() = nu_star_;
    xi_dot.tail<3>().setZero();
    return P_.internal_wrench(xi, xi_dot, s, t);
  }

  /// The Kirchhoff restriction (3.45) done with constraint forces (docs/dynamics.md): segment k
  /// carries an unknown force f_k in its stress, lambda^k += dexp^-T_{ds xi^k} [0; f_k] = B_k f_k,
  /// which enters the momenta of nodes k (+B_k f_k) and k + 1 (-Ad^T_{G^k} B_k f_k = -C_k f_k)
  /// through (3.41). The f_k are chosen so that the velocities of (3.42) take every segment of
  /// the next step's compatibility (3.38) onto the constraint:
  ///   c_k = nu-part of log((E^k)^-1 G^k E^(k+1)) / ds - nu* = 0,   E^j = exp(dt eta^j),
  /// (SHAKE: the constraint on the next positions through this step's impulses; the constraint
  /// forces do no work to the solve's tolerance). Newton with the chord matrix of the linearised
  /// map, block tridiagonal in the segments with 3 x 3 blocks:
  ///   dc_k = (dt/ds) [dexp^-1_{-ds xi^k}]_nu (d eta^(k+1) - Ad_{(G^k)^-1} d eta^k),
  ///   d eta^j = (dt / w_j) M^-1 (B_j f_j - C_(j-1) f_(j-1)).
  /// Returns an empty string on success, else what failed.
  std::string enforce_constraints(double dt) {
    const int m = n_ - 1;  // segments
    auto weight = [&](int j) { return j == n_ - 1 ? 0.5 * ds_ : ds_; };
    // Chord matrix at the configuration of this step.
    for (int k = 0; k < m; ++k) {
      const Vector6 x = ds_ * xi_[k];
      B_[k] = se3::dexp_inv(x).transpose().rightCols<3>();
      C_[k] = G_[k].Ad().transpose() * B_[k];
    }
    for (int k = 0; k < m; ++k) {
      const Eigen::Matrix<double, 3, 6> D =
          (dt / ds_) * se3::dexp_inv(-ds_ * xi_[k]).bottomRows<3>();
      const Matrix6 H = G_[k].inverse().Ad();
      const Vector6 Q_next = (dt / weight(k + 1)) * M_inv_;
      A_.Di[k] = -D * (Q_next.asDiagonal() * C_[k]);
      A_.Up[k].setZero();
      A_.Lo[k].setZero();
      if (k + 1 < m) A_.Up[k] = D * (Q_next.asDiagonal() * B_[k + 1]);
      if (k >= 1) {
        const Vector6 Q = (dt / weight(k)) * M_inv_;
        A_.Di[k] -= D * H * (Q.asDiagonal() * B_[k]);
        A_.Lo[k] = D * H * (Q.asDiagonal() * C_[k - 1]);
      }
    }
    if (!A_.factor()) return "has a singular matrix";
    for (auto& f : f_) f.setZero();
    double worst = 0.0;
    for (int it = 0; it <= opt_.max_iterations; ++it) {
      // residuals of the velocities at the current forces
      worst = 0.0;
      SE3 E = SE3::identity();
      for (int k = 0; k < m; ++k) {
        const SE3 E_next = small::exp(dt * eta_[k + 1]);
        const Vector6 x = (E.inverse() * G_[k] * E_next).log();
        c_[k] = x.tail<3>() / ds_ - nu_star_;
        worst = std::max(worst, c_[k].lpNorm<Eigen::Infinity>());
        E = E_next;
      }
      if (!(worst <= kConstraintTol * std::max(1.0, nu_star_.norm()))) {
        if (it == opt_.max_iterations || !std::isfinite(worst)) break;
      } else {
        return {};
      }
      for (auto& c : c_) c = -c;
      A_.solve(c_);
      for (int k = 0; k < m; ++k) f_[k] += c_[k];
      // the momenta with the constraint impulses, and their velocities (3.42)
      for (int j = 1; j < n_; ++j) {
        Vector6 impulse = -C_[j - 1] * f_[j - 1];
        if (j < m) impulse += B_[j] * f_[j];
        mu_[j] = mu_free_[j] + (dt / weight(j)) * impulse;
        const Vector6 r0 = small::dexp_inv_transpose_apply(dt * eta_[j], M_.cwiseProduct(eta_[j])) - mu_[j];
        if (!solve_velocity(j, dt, r0)) return "diverged in the velocity of node " + std::to_string(j);
      }
    }
    return "did not converge (max |nu - nu*| = " + std::to_string(worst) + ")";
  }

  StepStatus diverged(int j, double t1, double dt) const {
    // (3.42) is a small perturbation of M eta = mu for any step below the stability limit;
    // divergence means the explicit scheme blew up.
    return StepStatus::failed("unstable: variational: Newton on (3.42) diverged at node " +
                              std::to_string(j) + " (t = " + std::to_string(t1) +
                              " s, dt = " + std::to_string(dt) + " s)");
  }

  /// (3.42): dexp^-T_{dt eta} M eta = mu for eta. Newton from the previous velocity eta_old with
  /// the first-order Jacobian J = M - dt/2 B, B d = ad_eta^T M d + ad_d^T M eta (from
  /// dexp^-T_x = I - ad_x^T / 2 + O(x^2)), frozen at eta_old and inverted to the same order,
  /// J^-1 = (I + dt/2 M^-1 B) M^-1 + O(dt^2 |eta|^2), without forming a matrix. The first
  /// residual needs no evaluation: eta_old solved (3.42) with mu_old, so r(eta_old) = mu_old -
  /// mu (to the previous solve's tolerance, which the following exact residuals correct); the
  /// caller passes that first residual r0. The
  /// solve has converged when the step is below tol in the kinetic-energy norm |x|_M^2 = x^T M x.
  bool solve_velocity(int j, double dt, const Vector6& r0) {
    const Vector6& mu = mu_[j];
    const Vector6 eta_old = eta_[j];
    const Vector6 M_eta_old = M_.cwiseProduct(eta_old);
    const double half_dt = 0.5 * dt;
    const Vector6 half_dt_M_inv = half_dt * M_inv_;
    auto J_inv = [&](const Vector6& r) {
      const Vector6 y = r.cwiseProduct(M_inv_);
      const Vector6 By = se3::coad_apply(eta_old, r) + se3::coad_apply(y, M_eta_old);
      return Vector6(y + half_dt_M_inv.cwiseProduct(By));
    };
    Vector6 eta = eta_old - J_inv(r0);
    const double tol2 = opt_.tol * opt_.tol;
    for (int it = 1; it < opt_.max_iterations; ++it) {
      const Vector6 r = small::dexp_inv_transpose_apply(dt * eta, M_.cwiseProduct(eta)) - mu;
      // The zeroth-order step M^-1 r first: when it is already below the tolerance, the
      // first-order correction (dt/2 M^-1 B, relative size ~dt |eta| ~ 1e-3) changes it by less
      // than tol * 1e-3 and is skipped (N = 100: most nodes converge here).
      const Vector6 y = r.cwiseProduct(M_inv_);
      const double y2 = y.dot(r);  // |y|_M^2
      if (y2 <= 0.25 * tol2 * eta.dot(M_.cwiseProduct(eta))) {
        eta_[j] = eta - y;
        return true;
      }
      const Vector6 step = J_inv(r);
      eta -= step;  // a NaN or inf fails the test below: no convergence
      const double step2 = step.dot(M_.cwiseProduct(step));
      if (step2 <= tol2 * eta.dot(M_.cwiseProduct(eta))) {
        eta_[j] = eta;
        return true;
      }
    }
    return false;
  }

  const DynamicProblem& P_;
  VariationalOptions opt_;
  int n_;
  double ds_;
  Vector6 M_, M_inv_;
  std::vector<SE3> g_, G_;
  std::vector<Vector6> xi_, eta_, mu_;
  std::vector<DynamicProblem::EntryNode> entries_;
  Energy ledger_;
  double kinetic_old_ = 0.0;
  // Kirchhoff rods (enforce_constraints)
  using Matrix63 = Eigen::Matrix<double, 6, 3>;
  bool kirchhoff_ = false;
  Vector3 nu_star_;
  std::vector<Vector6> mu_free_;      ///< momenta without the constraint impulses
  std::vector<Vector3> f_, c_;        ///< constraint forces per segment; residuals / steps
  std::vector<Matrix63> B_, C_;       ///< a force's impulse on the inner and outer node
  BlockTridiagonal<3> A_;             ///< the chord matrix dc/df
};

}  // namespace

std::unique_ptr<Stepper> make_variational(const DynamicProblem& problem,
                                          const VariationalOptions& options,
                                          const RestState& initial) {
  return std::make_unique<Variational>(problem, options, initial);
}

}  // namespace rodlab::solvers::dynamics
