#include "rodlab/solvers/dynamics/implicit_midpoint.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/LU>

namespace rodlab::solvers::dynamics {
namespace {

using lie::Matrix6;
namespace se3 = lie::se3;

/// Relative finite-difference step of the Jacobian columns (scaled unknowns).
constexpr double kFdStep = 1e-7;
/// A Newton step that does not reduce the residual by this factor triggers a fresh Jacobian.
constexpr double kSlowRatio = 0.5;

class ImplicitMidpoint final : public Stepper {
 public:
  ImplicitMidpoint(const DynamicProblem& problem, const ImplicitMidpointOptions& options,
                   const RestState& initial)
      : P_(problem), opt_(options), n_(options.nodes), ds_(problem.length() / (n_ - 1)) {
    if (n_ < 3) throw std::invalid_argument("implicit-midpoint: nodes must be >= 3");
    if (static_cast<int>(initial.xi.size()) != n_ || static_cast<int>(initial.g.size()) != n_)
      throw std::invalid_argument("implicit-midpoint: expected " + std::to_string(n_) +
                                  " initial nodes, got " + std::to_string(initial.xi.size()));
    xi_ = initial.xi;
    g_ = initial.g;
    eta_.assign(n_, Vector6::Zero());
    xi_h_.assign(n_, Vector6::Zero());
    xi_ref_.assign(n_, Vector6::Zero());
    eta_h_.assign(n_, Vector6::Zero());
    g_h_.assign(n_, SE3::identity());
    const auto& K = problem.model().K_diag();
    const double EI = std::min(K[0], K[1]), L = problem.length();
    scale_ << EI / L, EI / L, EI / L, EI / (L * L), EI / (L * L), EI / (L * L);
    // first guess: the base wrench of the initial state
    x_prev_ = P_.model().K_diag().cwiseProduct(xi_[0] - P_.model().xi_star()).cwiseQuotient(scale_);
    x_prev2_ = x_prev_;
    entries_ = problem.entry_nodes(n_);
  }

  StepStatus step(double t, double dt) override {
    t_h_ = t + 0.5 * dt;
    dt_ = dt;
    Kt_ = P_.model().K_diag() + (2.0 / dt) * P_.model().V_diag();
    // Lambda_h = K (xi_h - xi*) + (2/dt) V (xi_h - xi_i) + tendons = Kt (xi_h - xi_ref) + tendons
    const Vector6 K_xi_star = P_.model().K_diag().cwiseProduct(P_.model().xi_star());
    for (int j = 0; j < n_; ++j)
      xi_ref_[j] = (K_xi_star + (2.0 / dt) * P_.model().V_diag().cwiseProduct(xi_[j])).cwiseQuotient(Kt_);
    Vector6 x = steps_ >= 2 ? Vector6(2.0 * x_prev_ - x_prev2_) : x_prev_;
    int shots = 0;
    Vector6 r = shoot(x);
    ++shots;
    if (!J_valid_ || dt != J_dt_) {
      if (!finite_difference_jacobian(x, r, shots)) return failure("the Jacobian is not finite", t);
    }
    bool fresh = false;
    while (!(r.lpNorm<Eigen::Infinity>() <= opt_.tol)) {
      if (shots >= opt_.max_iterations || !r.allFinite())
        return failure("single shooting did not converge (tip residual " +
                       std::to_string(r.lpNorm<Eigen::Infinity>()) + ")", t);
      const Eigen::PartialPivLU<Matrix6> lu(J_);
      const Vector6 dx = -lu.solve(r);
      if (!dx.allFinite()) return failure("the shooting Jacobian is singular", t);
      const Vector6 r_new = shoot(x + dx);
      ++shots;
      if (!(r_new.lpNorm<Eigen::Infinity>() <= kSlowRatio * r.lpNorm<Eigen::Infinity>()) && !fresh) {
        // Broyden's secant model went stale: rebuild the Jacobian where we stand.
        if (!finite_difference_jacobian(x, r, shots)) return failure("the Jacobian is not finite", t);
        fresh = true;
        continue;
      }
      // Broyden's rank-one update of the secant model.
      J_ += ((r_new - r) - J_ * dx) * dx.transpose() / dx.squaredNorm();
      x += dx;
      r = r_new;
      fresh = false;
    }
    // the last shot was at x: the half-step profiles are current. (3.53)-(3.54)
    accumulate_ledger(dt);
    for (int j = 0; j < n_; ++j) {
      xi_[j] = 2.0 * xi_h_[j] - xi_[j];
      eta_[j] = 2.0 * eta_h_[j] - eta_[j];
    }
    update_poses();
    x_prev2_ = x_prev_;
    x_prev_ = x;
    ++steps_;
    StepStatus status;
    status.iterations = shots;
    return status;
  }

  Energy energy() const override {
    Energy e = ledger_;
    e.kinetic = kinetic_energy(P_.model(), eta_, ds_);
    e.strain = strain_energy_nodes(P_.model(), xi_, ds_);
    e.gravity = gravity_energy(P_, g_, ds_);
    return e;
  }

  Vector3 tip_position() const override { return g_.back().translation(); }

  double max_det_deviation() const override { return dynamics::max_det_deviation(g_); }

  std::vector<result::CenterlineSample> centerline() const override {
    std::vector<result::CenterlineSample> out(n_);
    for (int j = 0; j < n_; ++j) out[j] = {j * ds_, g_[j], xi_[j]};
    return out;
  }

 private:
  StepStatus failure(const std::string& what, double t) const {
    return StepStatus::failed("implicit-midpoint: " + what + " in the step from t = " +
                              std::to_string(t) + " s (dt = " + std::to_string(dt_) + " s)");
  }

  /// Integrates the half-step BVP from the base with Lambda_h(0) = x * scale (explicit Euler
  /// RKMK, (3.51)-(3.52)) and returns the scaled tip residual.
  Vector6 shoot(const Vector6& x) {
    const Vector6& M = P_.model().M_diag();
    const double c = 2.0 / dt_;
    Vector6 Lambda = x.cwiseProduct(scale_);
    Vector6 eta = Vector6::Zero();
    SE3 g = P_.base();
    for (int j = 0;; ++j) {
      const double s = j * ds_;
      const Vector6 xi = P_.solve_strain(Kt_, xi_ref_[j], Lambda, s, t_h_);
      xi_h_[j] = xi;
      eta_h_[j] = eta;
      g_h_[j] = g;
      if (j == n_ - 1) break;
      const SO3& R = g.rotation();
      const Vector6 Meta = M.cwiseProduct(eta);
      const Vector6 load = P_.gravity_load(R) + P_.applied_load(R, t_h_) + P_.drag_load(eta);
      Vector6 dLambda = c * M.cwiseProduct(eta - eta_[j]) - se3::coad_apply(eta, Meta) +
                        se3::coad_apply(xi, Lambda) - load;                            // (3.51)
      const Vector6 deta = c * (xi - xi_[j]) - se3::ad_apply(xi, eta);                   // (3.52)
      g = g * SE3::exp(ds_ * xi);
      Lambda += ds_ * dLambda;
      eta += ds_ * deta;
      for (const auto& e : entries_)
        if (e.node == j + 1) Lambda -= P_.entry_load(e.s, xi, t_h_);
    }
    const Vector6 W = P_.tip_load(g.rotation(), t_h_);
    return (Lambda - W).cwiseQuotient(scale_);
  }

  bool finite_difference_jacobian(const Vector6& x, const Vector6& r, int& shots) {
    for (int k = 0; k < 6; ++k) {
      const double h = kFdStep * std::max(1.0, std::abs(x[k]));
      Vector6 xp = x;
      xp[k] += h;
      J_.col(k) = (shoot(xp) - r) / h;
      ++shots;
    }
    shoot(x);  // restore the half-step profiles of x
    ++shots;
    J_valid_ = J_.allFinite();
    J_dt_ = dt_;
    return J_valid_;
  }

  /// Dissipation and input work of the step, trapezoid in s at the half step.
  void accumulate_ledger(double dt) {
    const auto& V = P_.model().V_diag();
    double dissipated = 0.0, work = 0.0;
    for (int j = 0; j < n_; ++j) {
      const double w = (j == 0 || j == n_ - 1) ? 0.5 * ds_ : ds_;
      const Vector6 xi_dot = 2.0 * (xi_h_[j] - xi_[j]) / dt;
      const SO3& R = g_h_[j].rotation();
      dissipated += w * (xi_dot.dot(V.cwiseProduct(xi_dot)) - P_.drag_load(eta_h_[j]).dot(eta_h_[j]));
      work += w * P_.applied_load(R, t_h_).dot(eta_h_[j]);
      if (P_.has_actuators()) work += w * P_.actuator_power(xi_h_[j], xi_dot, j * ds_, t_h_);
    }
    work += P_.tip_load(g_h_.back().rotation(), t_h_).dot(eta_h_.back());
    ledger_.dissipated += dt * dissipated;
    ledger_.work_in += dt * work;
  }

  /// Poses from the strains by the same explicit Euler RKMK as the shooting.
  void update_poses() {
    g_[0] = P_.base();
    for (int j = 0; j + 1 < n_; ++j) g_[j + 1] = g_[j] * SE3::exp(ds_ * xi_[j]);
  }

  const DynamicProblem& P_;
  ImplicitMidpointOptions opt_;
  int n_;
  double ds_;
  Vector6 scale_, Kt_;
  double t_h_ = 0.0, dt_ = 0.0, J_dt_ = 0.0;
  std::vector<Vector6> xi_, eta_, xi_h_, eta_h_, xi_ref_;
  std::vector<SE3> g_, g_h_;
  std::vector<DynamicProblem::EntryNode> entries_;
  Matrix6 J_ = Matrix6::Identity();
  bool J_valid_ = false;
  Vector6 x_prev_, x_prev2_;
  long steps_ = 0;
  Energy ledger_;
};

}  // namespace

std::unique_ptr<Stepper> make_implicit_midpoint(const DynamicProblem& problem,
                                                const ImplicitMidpointOptions& options,
                                                const RestState& initial) {
  return std::make_unique<ImplicitMidpoint>(problem, options, initial);
}

}  // namespace rodlab::solvers::dynamics
