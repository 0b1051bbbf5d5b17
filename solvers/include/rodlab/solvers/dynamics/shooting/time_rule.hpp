#pragma once
// The time-difference rule of the shooting steppers (`implicit-midpoint`, `bdf-alpha`;
// shooting_stepper.hpp). A step from t to t + dt solves for unknown profiles x (strains xi and
// velocities eta at the nodes) that sit at t_u = t + theta dt; every time derivative at t_u is
// written
//
//   x_dot(t_u) = c x + h,
//
// c a scalar of the step, h a history term per node computed once per step from stored values.
// The viscous strain rate (3.10), M eta_dot in the balance (3.51) and xi_dot in the
// compatibility (3.52) all follow from (c, h). docs/dynamics.md.
//
// implicit midpoint (thesis (3.50)-(3.54)): theta = 1/2, c = 2/dt, h = -c x_i,
//   x_(i+1) = 2 x - x_i.
// BDF-alpha (Till, Aloi & Rucker 2019): theta = 1, c = c0, x_(i+1) = x,
//   h = c1 x_i + c2 x_(i-1) + d1 x_dot_i,  x_dot_(i+1) = c0 x + h (stored for the next step),
//   c0 = (1.5 + alpha) / (dt (1 + alpha)), c1 = -2/dt, c2 = (0.5 + alpha) / (dt (1 + alpha)),
//   d1 = alpha / (1 + alpha),  alpha in [-0.5, 0]   (0: BDF2; -0.5: trapezoidal rule).
// Start-up: the first two steps are implicit midpoint steps, then x_dot_2 = (3 x_2 - 4 x_1 + x_0)
// / (2 dt) (time_rule.cpp says why: a consistent x_dot_0 is not known for a released rod).
#include <memory>
#include <span>
#include <string_view>

#include "rodlab/lie/se3.hpp"

namespace rodlab::solvers::dynamics {

/// The coefficients of BDF-alpha for a step dt (see above).
struct BdfAlphaCoefficients {
  double c0 = 0.0, c1 = 0.0, c2 = 0.0, d1 = 0.0;
};
/// Throws std::invalid_argument unless -0.5 <= alpha <= 0 and dt > 0.
BdfAlphaCoefficients bdf_alpha_coefficients(double alpha, double dt);

/// The two time-differentiated fields of a shooting step.
enum class RuleField { strain = 0, velocity = 1 };

class TimeRule {
 public:
  virtual ~TimeRule() = default;
  /// The scheme's name, for messages.
  virtual std::string_view name() const = 0;
  /// The unknowns of the coming step sit at t + theta dt (loads are evaluated there).
  virtual double theta() const = 0;
  /// c of x_dot = c x + h for the coming step dt.
  virtual double coefficient(double dt) const = 0;
  /// The history term h of every node for a step dt from the state x at t.
  virtual void history(RuleField f, double dt, std::span<const lie::Vector6> x,
                       std::span<lie::Vector6> h) = 0;
  /// dh/dx_i of history(): the history's slope in the state at t (control's linearisation of a
  /// step; the older history of BDF-alpha is held). Midpoint: -2/dt; BDF-alpha: c1 = -2/dt.
  virtual double history_slope(double dt) const = 0;
  /// Completes the step: the state x (at t on entry, at t + dt on exit) from the converged
  /// unknowns u and the h of the step.
  virtual void advance(RuleField f, double dt, std::span<const lie::Vector6> u,
                       std::span<const lie::Vector6> h, std::span<lie::Vector6> x) = 0;
  /// a of x_(i+1) = a u + (1 - a) x_i for the coming step (midpoint: 2; BDF-alpha: 1): the end
  /// state, for constraints imposed at the end of the step (length control).
  virtual double end_coefficient() const = 0;
  /// Weight of the power at the start of the coming step in its dissipation and work; the power
  /// at the unknowns gets 1 minus it (midpoint: 0, the midpoint rule; BDF-alpha: 1/2, the
  /// trapezoid).
  virtual double ledger_start_weight() const = 0;
  /// A copy with its history (a control snapshot, stepper.hpp; allocates).
  virtual std::unique_ptr<TimeRule> clone() const = 0;
  /// Takes the history of `other`, a clone of this rule, without allocating.
  virtual void assign(const TimeRule& other) = 0;
};

/// Implicit midpoint (thesis Algorithm 2).
std::unique_ptr<TimeRule> make_midpoint_rule();
/// BDF-alpha for `nodes` nodes (its history is allocated once). Throws std::invalid_argument for
/// alpha outside [-0.5, 0].
std::unique_ptr<TimeRule> make_bdf_alpha_rule(double alpha, int nodes);

}  // namespace rodlab::solvers::dynamics
