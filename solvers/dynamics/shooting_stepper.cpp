#include "rodlab/solvers/dynamics/shooting_stepper.hpp"

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

class ShootingStepper final : public Stepper {
 public:
  ShootingStepper(const DynamicProblem& problem, const ShootingOptions& options,
                  const RestState& initial, std::unique_ptr<TimeRule> rule)
      : P_(problem), opt_(options), rule_(std::move(rule)), n_(options.nodes),
        ds_(problem.length() / (n_ - 1)) {
    const std::string name(rule_->name());
    if (n_ < 3) throw std::invalid_argument(name + ": nodes must be >= 3");
    if (static_cast<int>(initial.xi.size()) != n_ || static_cast<int>(initial.g.size()) != n_)
      throw std::invalid_argument(name + ": expected " + std::to_string(n_) +
                                  " initial nodes, got " + std::to_string(initial.xi.size()));
    xi_ = initial.xi;
    g_ = initial.g;
    eta_.assign(n_, Vector6::Zero());
    xi_u_.assign(n_, Vector6::Zero());
    eta_u_.assign(n_, Vector6::Zero());
    xi_hist_.assign(n_, Vector6::Zero());
    eta_hist_.assign(n_, Vector6::Zero());
    xi_ref_.assign(n_, Vector6::Zero());
    g_u_.assign(n_, SE3::identity());
    const auto& K = problem.model().K_diag();
    const double EI = std::min(K[0], K[1]), L = problem.length();
    scale_ << EI / L, EI / L, EI / L, EI / (L * L), EI / (L * L), EI / (L * L);
    // first guess: the base wrench of the initial state
    x_prev_ = P_.model().K_diag().cwiseProduct(xi_[0] - P_.model().xi_star()).cwiseQuotient(scale_);
    x_prev2_ = x_prev_;
    entries_ = problem.entry_nodes(n_);
  }

  StepStatus step(double t, double dt) override {
    t_u_ = t + rule_->theta() * dt;
    dt_ = dt;
    c_ = rule_->coefficient(dt);
    rule_->history(RuleField::strain, dt, xi_, xi_hist_);
    rule_->history(RuleField::velocity, dt, eta_, eta_hist_);
    const Vector6& V = P_.model().V_diag();
    Kt_ = P_.model().K_diag() + c_ * V;
    // Lambda = K (xi - xi*) + V (c xi + h) + tendons = Kt (xi - xi_ref) + tendons   (3.10)
    const Vector6 K_xi_star = P_.model().K_diag().cwiseProduct(P_.model().xi_star());
    for (int j = 0; j < n_; ++j)
      xi_ref_[j] = (K_xi_star - V.cwiseProduct(xi_hist_[j])).cwiseQuotient(Kt_);
    Vector6 x = steps_ >= 2 ? Vector6(2.0 * x_prev_ - x_prev2_) : x_prev_;
    int shots = 0;
    Vector6 r = shoot(x);
    ++shots;
    if (!J_valid_ || c_ != J_c_) {
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
    // the last shot was at x: the profiles at t_u are current.
    accumulate_ledger(dt);
    rule_->advance(RuleField::strain, dt, xi_u_, xi_hist_, xi_);
    rule_->advance(RuleField::velocity, dt, eta_u_, eta_hist_, eta_);
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
    return StepStatus::failed(std::string(rule_->name()) + ": " + what + " in the step from t = " +
                              std::to_string(t) + " s (dt = " + std::to_string(dt_) + " s)");
  }

  /// Integrates the BVP at t_u from the base with Lambda(0) = x * scale (explicit Euler RKMK,
  /// (3.51)-(3.52)) and returns the scaled tip residual.
  Vector6 shoot(const Vector6& x) {
    const Vector6& M = P_.model().M_diag();
    Vector6 Lambda = x.cwiseProduct(scale_);
    Vector6 eta = Vector6::Zero();
    SE3 g = P_.base();
    for (int j = 0;; ++j) {
      const double s = j * ds_;
      const Vector6 xi = P_.solve_strain(Kt_, xi_ref_[j], Lambda, s, t_u_);
      xi_u_[j] = xi;
      eta_u_[j] = eta;
      g_u_[j] = g;
      if (j == n_ - 1) break;
      const SO3& R = g.rotation();
      const Vector6 Meta = M.cwiseProduct(eta);
      const Vector6 load = P_.gravity_load(R) + P_.applied_load(R, t_u_) + P_.drag_load(eta);
      Vector6 dLambda = M.cwiseProduct(c_ * eta + eta_hist_[j]) - se3::coad_apply(eta, Meta) +
                        se3::coad_apply(xi, Lambda) - load;                            // (3.51)
      const Vector6 deta = (c_ * xi + xi_hist_[j]) - se3::ad_apply(xi, eta);             // (3.52)
      g = g * SE3::exp(ds_ * xi);
      Lambda += ds_ * dLambda;
      eta += ds_ * deta;
      for (const auto& e : entries_)
        if (e.node == j + 1) Lambda -= P_.entry_load(e.s, xi, t_u_);
    }
    const Vector6 W = P_.tip_load(g.rotation(), t_u_);
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
    shoot(x);  // restore the profiles of x
    ++shots;
    J_valid_ = J_.allFinite();
    J_c_ = c_;  // the Jacobian depends on the step through c
    return J_valid_;
  }

  /// Dissipation and input work of the step: the power at t_u (trapezoid in s) weighted with
  /// the power at the start of the step as the rule says (midpoint rule or trapezoid in time).
  void accumulate_ledger(double dt) {
    const auto& V = P_.model().V_diag();
    double dissipated = 0.0, work = 0.0;
    for (int j = 0; j < n_; ++j) {
      const double w = (j == 0 || j == n_ - 1) ? 0.5 * ds_ : ds_;
      const Vector6 xi_dot = c_ * xi_u_[j] + xi_hist_[j];
      const SO3& R = g_u_[j].rotation();
      dissipated += w * (xi_dot.dot(V.cwiseProduct(xi_dot)) - P_.drag_load(eta_u_[j]).dot(eta_u_[j]));
      work += w * P_.applied_load(R, t_u_).dot(eta_u_[j]);
      if (P_.has_actuators()) work += w * P_.actuator_power(xi_u_[j], xi_dot, j * ds_, t_u_);
    }
    work += P_.tip_load(g_u_.back().rotation(), t_u_).dot(eta_u_.back());
    const double w0 = rule_->ledger_start_weight(), w1 = 1.0 - w0;
    ledger_.dissipated += dt * (w0 * dissipated_start_ + w1 * dissipated);
    ledger_.work_in += dt * (w0 * work_start_ + w1 * work);
    dissipated_start_ = dissipated;  // the start of the next step (the state at rest: 0)
    work_start_ = work;
  }

  /// Poses from the strains by the same explicit Euler RKMK as the shooting.
  void update_poses() {
    g_[0] = P_.base();
    for (int j = 0; j + 1 < n_; ++j) g_[j + 1] = g_[j] * SE3::exp(ds_ * xi_[j]);
  }

  const DynamicProblem& P_;
  ShootingOptions opt_;
  std::unique_ptr<TimeRule> rule_;
  int n_;
  double ds_;
  Vector6 scale_, Kt_;
  double t_u_ = 0.0, dt_ = 0.0, c_ = 0.0, J_c_ = 0.0;
  double dissipated_start_ = 0.0, work_start_ = 0.0;
  std::vector<Vector6> xi_, eta_, xi_u_, eta_u_, xi_hist_, eta_hist_, xi_ref_;
  std::vector<SE3> g_, g_u_;
  std::vector<DynamicProblem::EntryNode> entries_;
  Matrix6 J_ = Matrix6::Identity();
  bool J_valid_ = false;
  Vector6 x_prev_, x_prev2_;
  long steps_ = 0;
  Energy ledger_;
};

}  // namespace

std::unique_ptr<Stepper> make_shooting_stepper(const DynamicProblem& problem,
                                               const ShootingOptions& options,
                                               const RestState& initial,
                                               std::unique_ptr<TimeRule> rule) {
  if (!rule) throw std::invalid_argument("shooting stepper: no time rule");
  return std::make_unique<ShootingStepper>(problem, options, initial, std::move(rule));
}

}  // namespace rodlab::solvers::dynamics
