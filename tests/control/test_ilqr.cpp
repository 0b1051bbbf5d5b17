// iLQR with input limits (solvers/control/ilqr.hpp): on a linear-quadratic problem it lands on
// the finite-horizon LQR optimum (lqr.hpp) in one accepted iteration; on a damped pendulum
// (nonlinear) its true cost falls monotonically and its solution satisfies the first-order
// optimality (KKT) conditions of the bounded problem, checked by central differences of the
// total cost; on the rod an accepted trial rollout serves as the next nominal one.
#define BOOST_TEST_MODULE control_ilqr
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "control_support.hpp"
#include "rodlab/solvers/control/ilqr.hpp"
#include "rodlab/solvers/control/lqr.hpp"
#include "rodlab/solvers/control/plant_ilqr.hpp"

namespace c = rodlab::solvers::control;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

/// x+ = A x + B u; l_k = x^T Q x + u^T R u, plus x_H^T Q_end x_H in the last stage.
class LinearModel final : public c::IlqrModel {
 public:
  LinearModel(MatrixXd A, MatrixXd B, MatrixXd Q, MatrixXd R, MatrixXd Qe, VectorXd x0, int H)
      : A_(std::move(A)), B_(std::move(B)), Q_(std::move(Q)), R_(std::move(R)), Qe_(std::move(Qe)),
        x0_(std::move(x0)), H_(H), lo_(VectorXd::Constant(B_.cols(), -1e6)), hi_(-lo_),
        kept_(H, x0_) {
    x_ = x0_;
  }
  int state_size() const override { return static_cast<int>(A_.rows()); }
  int input_size() const override { return static_cast<int>(B_.cols()); }
  const VectorXd& lower() const override { return lo_; }
  const VectorXd& upper() const override { return hi_; }
  void reset() override { x_ = x0_; }
  void state(VectorXd& x) const override { x = x_; }
  void keep(int k) override { kept_[k] = x_; }
  bool step(int k, const VectorXd& u, double& cost) override {
    cost += x_.dot(Q_ * x_) + u.dot(R_ * u);
    x_ = A_ * x_ + B_ * u;
    if (k == H_ - 1) cost += x_.dot(Qe_ * x_);
    return true;
  }
  bool linearise(int k, const VectorXd& u, MatrixXd& A, MatrixXd& B, VectorXd& lx, VectorXd& lu,
                 MatrixXd& lxx, MatrixXd& luu, MatrixXd& lux) override {
    const VectorXd& x = kept_[k];
    A = A_;
    B = B_;
    lx = 2 * Q_ * x;
    lu = 2 * R_ * u;
    lxx = 2 * Q_;
    luu = 2 * R_;
    lux = MatrixXd::Zero(B_.cols(), A_.rows());
    if (k == H_ - 1) {  // + (A x + B u)^T Qe (A x + B u)
      const VectorXd xn = A_ * x + B_ * u;
      lx += 2 * A_.transpose() * Qe_ * xn;
      lu += 2 * B_.transpose() * Qe_ * xn;
      lxx += 2 * A_.transpose() * Qe_ * A_;
      luu += 2 * B_.transpose() * Qe_ * B_;
      lux += 2 * B_.transpose() * Qe_ * A_;
    }
    return true;
  }

 private:
  MatrixXd A_, B_, Q_, R_, Qe_;
  VectorXd x0_;
  int H_;
  VectorXd lo_, hi_, x_;
  std::vector<VectorXd> kept_;
};

/// A damped pendulum, theta'' = -(g/l) sin theta - c theta' + u, explicit Euler, dt = 0.05, with
/// l = q (theta - theta*)^2 + q_w omega^2 + r u^2, u in [lo, hi]. Exact derivatives.
class Pendulum final : public c::IlqrModel {
 public:
  Pendulum(double lo, double hi, int H)
      : lo_(VectorXd::Constant(1, lo)), hi_(VectorXd::Constant(1, hi)), kept_(H, VectorXd::Zero(2)) {
    x_ = VectorXd::Zero(2);
  }
  int state_size() const override { return 2; }
  int input_size() const override { return 1; }
  const VectorXd& lower() const override { return lo_; }
  const VectorXd& upper() const override { return hi_; }
  void reset() override { x_.setZero(); }
  void state(VectorXd& x) const override { x = x_; }
  void keep(int k) override { kept_[k] = x_; }
  bool step(int, const VectorXd& u, double& cost) override {
    cost += q * std::pow(x_[0] - target, 2) + qw * x_[1] * x_[1] + r * u[0] * u[0];
    const double th = x_[0], w = x_[1];
    x_[0] = th + dt * w;
    x_[1] = w + dt * (-9.81 * std::sin(th) - damping * w + u[0]);
    return true;
  }
  bool linearise(int k, const VectorXd& u, MatrixXd& A, MatrixXd& B, VectorXd& lx, VectorXd& lu,
                 MatrixXd& lxx, MatrixXd& luu, MatrixXd& lux) override {
    const VectorXd& x = kept_[k];
    A.resize(2, 2);
    A << 1, dt, -dt * 9.81 * std::cos(x[0]), 1 - dt * damping;
    B.resize(2, 1);
    B << 0, dt;
    lx.resize(2);
    lx << 2 * q * (x[0] - target), 2 * qw * x[1];
    lu = VectorXd::Constant(1, 2 * r * u[0]);
    lxx = MatrixXd::Zero(2, 2);
    lxx(0, 0) = 2 * q;
    lxx(1, 1) = 2 * qw;
    luu = MatrixXd::Constant(1, 1, 2 * r);
    lux = MatrixXd::Zero(1, 2);
    return true;
  }
  /// The total cost of an input sequence from rest.
  double total(const std::vector<VectorXd>& u) {
    reset();
    double J = 0.0;
    for (std::size_t k = 0; k < u.size(); ++k) step(static_cast<int>(k), u[k], J);
    return J;
  }

  static constexpr double dt = 0.05, damping = 0.5, q = 10.0, qw = 0.1, r = 0.01, target = 1.0;

 private:
  VectorXd lo_, hi_, x_;
  std::vector<VectorXd> kept_;
};

}  // namespace

// Linear dynamics and quadratic cost: the first accepted iteration is the exact optimum, u_k =
// -K_k x_k of the finite-horizon LQR (to 1e-9), and the next changes nothing.
BOOST_AUTO_TEST_CASE(linear_quadratic_problem_is_solved_in_one_iteration) {
  MatrixXd A(2, 2), B(2, 1);
  A << 1.0, 0.1, -0.2, 0.97;
  B << 0.0, 0.1;
  const MatrixXd Q = MatrixXd::Identity(2, 2), R = 0.1 * MatrixXd::Identity(1, 1),
                 Qe = 5 * MatrixXd::Identity(2, 2);
  VectorXd x0(2);
  x0 << 1.0, 0.0;
  const int H = 20;
  LinearModel model(A, B, Q, R, Qe, x0, H);
  const c::IlqrResult r = c::solve_ilqr(model, std::vector<VectorXd>(H, VectorXd::Zero(1)));
  BOOST_TEST_REQUIRE(r.ok, r.reason);
  BOOST_TEST(r.costs.size() >= 2u);
  BOOST_TEST(r.costs[1] <= r.costs.back() * (1 + 1e-12));  // nothing gained after the first
  const c::FiniteHorizonLqr lqr = c::finite_horizon_lqr(A, B, Q, R, Qe, H);
  VectorXd x = x0;
  for (int k = 0; k < H; ++k) {
    const VectorXd u = -lqr.K[k] * x;
    BOOST_TEST(std::abs(r.u[k][0] - u[0]) < 1e-9);
    x = A * x + B * u;
  }
  BOOST_TEST(std::abs(r.costs.back() - x0.dot(lqr.S[0] * x0)) < 1e-9 * r.costs.back());
}

// The pendulum from rest to theta* = 1 rad over H = 40 steps, with u in [-4, 4] (active: the
// unbounded optimum pushes harder at the start) and without bounds: the true cost never rises;
// at the solution the cost's gradient (central differences, h = 1e-6) is zero on the free
// inputs (to 1e-5 of the initial gradient) and points outward on the clamped ones.
BOOST_AUTO_TEST_CASE(pendulum_cost_falls_and_the_solution_is_stationary) {
  for (const double bound : {4.0, 1e3}) {
    BOOST_TEST_CONTEXT("bound " << bound) {
      const int H = 40;
      Pendulum model(-bound, bound, H);
      const std::vector<VectorXd> u0(H, VectorXd::Zero(1));
      c::IlqrOptions o;
      o.tolerance = 1e-12;
      const c::IlqrResult r = c::solve_ilqr(model, u0, o);
      BOOST_TEST_REQUIRE(r.ok, r.reason);
      for (std::size_t i = 1; i < r.costs.size(); ++i) BOOST_TEST(r.costs[i] <= r.costs[i - 1]);
      BOOST_TEST_MESSAGE("iterations " << r.iterations << ", cost " << r.costs.front() << " -> "
                                       << r.costs.back());
      auto gradient = [&](const std::vector<VectorXd>& u, int k) {
        std::vector<VectorXd> up = u, down = u;
        up[k][0] += 1e-6;
        down[k][0] -= 1e-6;
        return (model.total(up) - model.total(down)) / 2e-6;
      };
      double g0 = 0.0;
      for (int k = 0; k < H; ++k) g0 = std::max(g0, std::abs(gradient(u0, k)));
      int clamped = 0;
      for (int k = 0; k < H; ++k) {
        const double g = gradient(r.u, k);
        const double v = r.u[k][0];
        BOOST_TEST(std::abs(v) <= bound);
        if (v <= -bound + 1e-12) {
          BOOST_TEST(g >= -1e-5 * g0);
          ++clamped;
        } else if (v >= bound - 1e-12) {
          BOOST_TEST(g <= 1e-5 * g0);
          ++clamped;
        } else {
          BOOST_TEST(std::abs(g) <= 1e-5 * g0);
        }
      }
      if (bound < 10) BOOST_TEST(clamped > 0);  // the bound was active
    }
  }
}

namespace {

/// The rod's model without trial states: solve_ilqr runs every accepted trial's rollout again.
class Rerunning final : public c::IlqrModel {
 public:
  explicit Rerunning(c::PlantIlqrModel& m) : m_(m) {}
  int state_size() const override { return m_.state_size(); }
  int input_size() const override { return m_.input_size(); }
  const VectorXd& lower() const override { return m_.lower(); }
  const VectorXd& upper() const override { return m_.upper(); }
  void reset() override { m_.reset(); }
  void state(VectorXd& x) const override { m_.state(x); }
  bool step(int k, const VectorXd& u, double& cost) override { return m_.step(k, u, cost); }
  void keep(int k) override { m_.keep(k); }
  bool linearise(int k, const VectorXd& u, MatrixXd& A, MatrixXd& B, VectorXd& l_x, VectorXd& l_u,
                 MatrixXd& l_xx, MatrixXd& l_uu, MatrixXd& l_ux) override {
    return m_.linearise(k, u, A, B, l_x, l_u, l_xx, l_uu, l_ux);
  }

 private:
  c::PlantIlqrModel& m_;
};

}  // namespace

// On the rod (PlantIlqrModel, N = 6, H = 3, dt_c = 0.05 s, towards a point 5 mm off the axis):
// an accepted trial rollout becomes the nominal one (accept_trial) instead of being run again;
// the iterations must then be those of the model that runs it again, bit for bit.
BOOST_AUTO_TEST_CASE(rod_accepted_trial_is_the_nominal_rollout) {
  c::Plant plant(rodlab::testing::control::cable_robot(),
                 rodlab::testing::control::plant_options("implicit-midpoint", 6, 0.05));
  const int H = 3;
  c::PlantIlqrModel model(plant, H, 0.0, 1.0);
  const std::vector<Eigen::Vector3d> targets(H, Eigen::Vector3d(0.005, 0.0, 0.0998));
  c::IlqrOptions o;
  o.max_iterations = 3;
  const std::vector<VectorXd> u0(H, plant.input());
  model.start(targets);
  const c::IlqrResult kept = c::solve_ilqr(model, u0, o);
  model.reset();
  Rerunning rerunning(model);
  const c::IlqrResult rerun = c::solve_ilqr(rerunning, u0, o);
  BOOST_REQUIRE(kept.ok);
  BOOST_REQUIRE(rerun.ok);
  BOOST_TEST(kept.iterations == rerun.iterations);
  BOOST_TEST(kept.costs == rerun.costs);
  for (int k = 0; k < H; ++k) BOOST_TEST((kept.u[k] - rerun.u[k]).norm() == 0.0);
  BOOST_TEST(kept.costs.back() < 0.5 * kept.costs.front());  // it did move towards the target
}
