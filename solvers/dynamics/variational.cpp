#include "rodlab/solvers/dynamics/variational.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

namespace rodlab::solvers::dynamics {
namespace {

using lie::Matrix3;
using lie::Matrix6;
namespace se3 = lie::se3;

/// bar(w) with ad_d^T w = bar(w) d for a wrench w = [m; f]: [[hat m, hat f], [hat f, 0]].
Matrix6 coad_bar(const Vector6& w) {
  Matrix6 B = Matrix6::Zero();
  const Matrix3 m = lie::so3::hat(w.head<3>()), f = lie::so3::hat(w.tail<3>());
  B.topLeftCorner<3, 3>() = m;
  B.topRightCorner<3, 3>() = f;
  B.bottomLeftCorner<3, 3>() = f;
  return B;
}

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
    if (problem.is_kirchhoff())
      throw std::invalid_argument("variational: rod.model kirchhoff is not supported yet");
    g_.assign(g0.begin(), g0.end());
    G_.resize(n_ - 1);
    xi_.resize(n_ - 1);
    lambda_.resize(n_ - 1);
    for (int j = 0; j + 1 < n_; ++j) {
      G_[j] = g_[j].inverse() * g_[j + 1];
      xi_[j] = G_[j].log() / ds_;
    }
    eta_.assign(n_, Vector6::Zero());
    mu_.assign(n_, Vector6::Zero());
    E_.assign(n_, SE3::identity());
    M_ = problem.model().M_diag();
    entries_ = problem.entry_nodes(n_);
  }

  StepStatus step(double t, double dt) override {
    const double t1 = t + dt;
    const auto& model = P_.model();
    const Vector6& V = model.V_diag();
    // (3.26): the time increment of every node over the step.
    for (int j = 1; j < n_; ++j) E_[j] = SE3::exp(dt * eta_[j]);
    // (3.38)-(3.40): new strains from exact compatibility, poses from the base, stresses.
    double dissipated = 0.0, work = 0.0;
    for (int j = 0; j + 1 < n_; ++j) {
      G_[j] = E_[j].inverse() * G_[j] * E_[j + 1];
      const Vector6 xi = G_[j].log() / ds_;
      const Vector6 xi_dot = (xi - xi_[j]) / dt;
      const double s_mid = (j + 0.5) * ds_;
      xi_[j] = xi;
      g_[j + 1] = g_[j] * G_[j];
      lambda_[j] = se3::dexp_inv_transpose_apply(ds_ * xi, P_.internal_wrench(xi, xi_dot, s_mid, t1));
      dissipated += ds_ * xi_dot.dot(V.cwiseProduct(xi_dot));
      if (P_.has_actuators()) work += ds_ * P_.actuator_power(xi, xi_dot, s_mid, t1);
    }
    // (3.41)-(3.42): momentum balance at every node but the base, then the new velocities.
    kinetic_old_ = 0.0;
    for (int j = 1; j < n_; ++j) {
      const bool tip = j == n_ - 1;
      const double w = tip ? 0.5 * ds_ : ds_;
      const SO3& R = g_[j].rotation();
      const Vector6 inner = tip ? P_.tip_load(R, t1) : lambda_[j];
      const Vector6 outer = G_[j - 1].coAd_apply(lambda_[j - 1]);
      const Vector6 applied = P_.applied_load(R, t1);
      const Vector6 drag = P_.drag_load(eta_[j]);
      const Vector6& eta_old = eta_[j];
      kinetic_old_ += 0.5 * w * eta_old.dot(M_.cwiseProduct(eta_old));
      dissipated -= w * drag.dot(eta_old);
      work += w * applied.dot(eta_old) + (tip ? inner.dot(eta_old) : 0.0);
      Vector6 force = inner - outer + w * (P_.gravity_load(R) + applied + drag);
      for (const auto& e : entries_)
        if (e.node == j) force += P_.entry_load(e.s, xi_[j < n_ - 1 ? j : j - 1], t1);
      mu_[j] = E_[j].coAd_apply(mu_[j]) + (dt / w) * force;
      if (!solve_velocity(j, dt)) {
        // (3.42) is a small perturbation of M eta = mu for any step below the stability limit
        // (Newton converges in 2-3 iterations); divergence means the explicit scheme blew up.
        return StepStatus::failed("unstable: variational: Newton on (3.42) diverged at node " +
                                  std::to_string(j) + " (t = " + std::to_string(t1) +
                                  " s, dt = " + std::to_string(dt) + " s)");
      }
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
    std::vector<result::CenterlineSample> out(n_);
    for (int j = 0; j < n_; ++j) {
      // node strain: the adjacent segments' mean (one segment at the ends)
      const Vector6 xi = j == 0        ? xi_[0]
                         : j == n_ - 1 ? xi_[n_ - 2]
                                       : Vector6(0.5 * (xi_[j - 1] + xi_[j]));
      out[j] = {j * ds_, g_[j], xi};
    }
    return out;
  }

 private:
  /// (3.42): dexp^-T_{dt eta} M eta = mu for eta, chord Newton from the previous velocity with
  /// the Jacobian M - dt/2 (ad_eta^T M + bar(M eta)) of the first-order expansion
  /// dexp^-T_x = I - ad_x^T / 2 + O(x^2); the residual is exact.
  bool solve_velocity(int j, double dt) {
    Vector6 eta = eta_[j];
    const Vector6& mu = mu_[j];
    const Matrix6 J = Matrix6(M_.asDiagonal()) -
                      0.5 * dt * (se3::ad(eta).transpose() * M_.asDiagonal() +
                                  coad_bar(M_.cwiseProduct(eta)));
    const Eigen::PartialPivLU<Matrix6> lu(J);
    // Converged when the step is below tol in the kinetic-energy norm |x|_M^2 = x^T M x.
    for (int it = 0; it < opt_.max_iterations; ++it) {
      const Vector6 r = se3::dexp_inv_transpose_apply(dt * eta, M_.cwiseProduct(eta)) - mu;
      const Vector6 step = lu.solve(r);
      eta -= step;
      if (!eta.allFinite()) return false;
      const double step2 = step.dot(M_.cwiseProduct(step));
      if (step2 <= opt_.tol * opt_.tol * eta.dot(M_.cwiseProduct(eta))) {
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
  Vector6 M_;
  std::vector<SE3> g_, G_, E_;
  std::vector<Vector6> xi_, lambda_, eta_, mu_;
  std::vector<DynamicProblem::EntryNode> entries_;
  Energy ledger_;
  double kinetic_old_ = 0.0;
};

}  // namespace

std::unique_ptr<Stepper> make_variational(const DynamicProblem& problem,
                                          const VariationalOptions& options,
                                          const RestState& initial) {
  return std::make_unique<Variational>(problem, options, initial);
}

}  // namespace rodlab::solvers::dynamics
