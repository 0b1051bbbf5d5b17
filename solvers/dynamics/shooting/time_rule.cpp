#include "rodlab/solvers/dynamics/shooting/time_rule.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "rodlab/check.hpp"

namespace rodlab::solvers::dynamics {
namespace {

using lie::Vector6;

class MidpointRule final : public TimeRule {
 public:
  std::string_view name() const override { return "implicit-midpoint"; }
  double theta() const override { return 0.5; }
  double coefficient(double dt) const override { return 2.0 / dt; }
  // x_dot_h = (x_(i+1) - x_i) / dt = (2/dt) (x_h - x_i)   (3.50)
  void history(RuleField, double dt, std::span<const Vector6> x, std::span<Vector6> h) override {
    const double c = coefficient(dt);
    for (std::size_t j = 0; j < x.size(); ++j) h[j] = -c * x[j];
  }
  double history_slope(double dt) const override { return -coefficient(dt); }
  // x_(i+1) = 2 x_h - x_i   (3.53)-(3.54)
  void advance(RuleField, double, std::span<const Vector6> u, std::span<const Vector6>,
               std::span<Vector6> x) override {
    for (std::size_t j = 0; j < x.size(); ++j) x[j] = 2.0 * u[j] - x[j];
  }
  double end_coefficient() const override { return 2.0; }
  double ledger_start_weight() const override { return 0.0; }
  std::unique_ptr<TimeRule> clone() const override { return std::make_unique<MidpointRule>(); }
  void assign(const TimeRule&) override {}  // no history
};

class BdfAlphaRule final : public TimeRule {
 public:
  BdfAlphaRule(double alpha, int nodes) : alpha_(alpha) {
    bdf_alpha_coefficients(alpha, 1.0);  // checks alpha
    for (int f = 0; f < 2; ++f) {
      previous_[f].assign(nodes, Vector6::Zero());
      rate_[f].assign(nodes, Vector6::Zero());
    }
  }
  std::string_view name() const override { return "bdf-alpha"; }
  // Start-up: the first kStartSteps steps are implicit midpoint steps. BDF-alpha needs x_(i-1)
  // and x_dot_i; at rest x_dot_0 = 0 is exact for the strains, but not for the velocities of a
  // rod released out of equilibrium (x_dot_0 is then the acceleration, and for Kirchhoff rods it
  // contains the unknown constraint forces). Guessing x_(-1) = x_0, x_dot_0 = 0 makes the first
  // step's velocity error O(dt) (first order overall); an implicit Euler start costs a one-time
  // O(dt^2) energy loss (9 % on the oscillator at 20 steps per period). Two midpoint steps and the
  // second-order x_dot_2 = (3 x_2 - 4 x_1 + x_0) / (2 dt) leave a one-time O(dt^3) error (0.34 %).
  double theta() const override { return steps_ < kStartSteps ? 0.5 : 1.0; }
  double coefficient(double dt) const override {
    return steps_ < kStartSteps ? 2.0 / dt : bdf_alpha_coefficients(alpha_, dt).c0;
  }
  // h = c1 x_i + c2 x_(i-1) + d1 x_dot_i   (midpoint start: h = -(2/dt) x_i)
  void history(RuleField f, double dt, std::span<const Vector6> x, std::span<Vector6> h) override {
    if (steps_ < kStartSteps) {
      const double c = 2.0 / dt;
      for (std::size_t j = 0; j < x.size(); ++j) h[j] = -c * x[j];
      return;
    }
    const int k = static_cast<int>(f);
    const auto b = bdf_alpha_coefficients(alpha_, dt);
    const auto& prev = previous_[k];
    const auto& rate = rate_[k];
    for (std::size_t j = 0; j < x.size(); ++j) h[j] = b.c1 * x[j] + b.c2 * prev[j] + b.d1 * rate[j];
  }
  double history_slope(double dt) const override {
    return steps_ < kStartSteps ? -2.0 / dt : bdf_alpha_coefficients(alpha_, dt).c1;
  }
  // x_(i+1) = u; x_dot_(i+1) = c0 u + h kept for the next step's history.
  void advance(RuleField f, double dt, std::span<const Vector6> u, std::span<const Vector6> h,
               std::span<Vector6> x) override {
    const int k = static_cast<int>(f);
    auto& prev = previous_[k];
    auto& rate = rate_[k];
    if (steps_ == 0) {  // midpoint; keep x_0 (in rate) for the start-up rate
      for (std::size_t j = 0; j < x.size(); ++j) {
        rate[j] = x[j];
        x[j] = 2.0 * u[j] - x[j];
      }
    } else if (steps_ == 1) {  // midpoint; x_dot_2 = (3 x_2 - 4 x_1 + x_0) / (2 dt)
      for (std::size_t j = 0; j < x.size(); ++j) {
        prev[j] = x[j];
        x[j] = 2.0 * u[j] - x[j];
        rate[j] = (3.0 * x[j] - 4.0 * prev[j] + rate[j]) / (2.0 * dt);
      }
    } else {
      const double c0 = coefficient(dt);
      for (std::size_t j = 0; j < x.size(); ++j) {
        rate[j] = c0 * u[j] + h[j];
        prev[j] = x[j];
        x[j] = u[j];
      }
    }
    advanced_[k] = true;
    if (advanced_[0] && advanced_[1]) {
      ++steps_;
      advanced_ = {false, false};
    }
  }
  double end_coefficient() const override { return steps_ < kStartSteps ? 2.0 : 1.0; }
  // trapezoid once the power at the start of the step is BDF-alpha's own (at t, not t - dt/2)
  double ledger_start_weight() const override { return steps_ > kStartSteps ? 0.5 : 0.0; }
  std::unique_ptr<TimeRule> clone() const override { return std::make_unique<BdfAlphaRule>(*this); }
  void assign(const TimeRule& other) override {
    *this = dynamic_cast<const BdfAlphaRule&>(other);  // equal sizes: the vectors keep their storage
  }

 private:
  static constexpr int kStartSteps = 2;
  double alpha_;
  std::array<std::vector<Vector6>, 2> previous_, rate_;  // x_(i-1), x_dot_i per field
  std::array<bool, 2> advanced_{false, false};
  long steps_ = 0;  // completed steps
};

}  // namespace

BdfAlphaCoefficients bdf_alpha_coefficients(double alpha, double dt) {
  RODLAB_THROW_UNLESS(alpha >= -0.5 && alpha <= 0.0,
                      "bdf-alpha: alpha must lie in [-0.5, 0] (got {:g})", alpha);
  if (!(dt > 0.0)) throw std::invalid_argument("bdf-alpha: dt must be > 0");
  BdfAlphaCoefficients b;
  b.c0 = (1.5 + alpha) / (dt * (1.0 + alpha));
  b.c1 = -2.0 / dt;
  b.c2 = (0.5 + alpha) / (dt * (1.0 + alpha));
  b.d1 = alpha / (1.0 + alpha);
  return b;
}

std::unique_ptr<TimeRule> make_midpoint_rule() { return std::make_unique<MidpointRule>(); }

std::unique_ptr<TimeRule> make_bdf_alpha_rule(double alpha, int nodes) {
  return std::make_unique<BdfAlphaRule>(alpha, nodes);
}

}  // namespace rodlab::solvers::dynamics
