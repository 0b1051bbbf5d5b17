#pragma once
// Newton on the unknowns of single shooting, shared by the two marches of the shooting steppers
// (shooting_stepper.cpp: explicit Euler RKMK on the nodes, thesis Algorithm 2;
// staggered_shooting_stepper.cpp: the staggered grid of `variational`). Private to
// solvers/dynamics.
//
// A finite-difference Jacobian, Broyden's rank-one updates, reuse across steps (rebuilt when the
// step constant c of the time rule changes or a Newton step does not halve the residual),
// backtracking along a fresh Jacobian's step that does not reduce the residual, and a linear
// predictor from the last two steps' solutions. Multiple shooting (the staggered march below
// single shooting's step bound) supplies its own Jacobian (by intervals, sparse), its own model
// of it (inverse_broyden.hpp: KLU's factors and Broyden's updates of the inverse) and accepts a
// stall on the residual's rounding floor.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/LU>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"


namespace rodlab::solvers::dynamics {

/// Relative finite-difference step of the Jacobian columns (scaled unknowns).
inline constexpr double kShootingFdStep = 1e-7;
/// A Newton step that does not reduce the residual by this factor triggers a fresh Jacobian...
inline constexpr double kShootingSlowRatio = 0.5;
/// ...except far from the solution (residual above this, scaled): there the residual is
/// strongly nonlinear in the unknowns and a fresh Jacobian's step does no better than Broyden's
/// (it halved the residual in the traces of the cantilever at dt = 10 ms), so a Broyden step that
/// reduces the residual at all is kept, up to kShootingSlowSteps in a row (unbounded, a crawl
/// could spend the shot budget). Measured (0.5 s of the cantilever, N = 20, staggered grid, best
/// of 3): implicit-midpoint at dt = 3 ms 21.7 -> 12.1 ms, 5 ms 7.1 -> 5.4 ms, 10 ms 2.75 -> 2.4 ms;
/// bdf-alpha at 3 ms 9.2 -> 7.6 ms; unchanged at dt auto (bench_dynamics).
inline constexpr double kShootingNonlinear = 0.1;
inline constexpr int kShootingSlowSteps = 4;
/// A fresh Jacobian's step that does not reduce the residual is halved up to this many times.
inline constexpr int kShootingHalvings = 10;

/// Shooting unknowns with actuator unknowns: the base wrench and one per muscle or
/// length-controlled actuator (fixed capacity: no allocation in a step).
inline constexpr int kMaxShootingUnknowns = 6 + DynamicProblem::kMaxActuators;
using ShootingVectorU = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxShootingUnknowns, 1>;
using ShootingMatrixU = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0,
                                      kMaxShootingUnknowns, kMaxShootingUnknowns>;

/// Why a shooting solve stopped without converging (empty: it converged).
struct ShootingOutcome {
  std::string failure;
  int shots = 0;  ///< integrations spent, Jacobian columns included
};

/// Newton's model of a small dense Jacobian (single shooting's 6 + m unknowns): the Jacobian
/// itself, LU-factorised for each step, and Broyden's rank-one updates of it.
template <class Vec, class Mat>
class DenseSecant {
 public:
  /// The Jacobian a fresh build fills, then refresh().
  Mat& jacobian() { return J_; }
  bool refresh() { return J_.allFinite(); }
  /// Newton's step -J^-1 r.
  Vec step(const Vec& r) const { return -Eigen::PartialPivLU<Mat>(J_).solve(r); }
  /// Broyden's update for the step s from the residual r to r_new (always taken).
  bool update(const Vec& s, const Vec& r, const Vec& r_new) {
    J_ += ((r_new - r) - J_ * s) * s.transpose() / s.squaredNorm();
    return true;
  }

 private:
  Mat J_;
};

/// Newton's state across steps for one kind of unknown vector; Mat is the Jacobian's type and
/// Secant Newton's model of it (DenseSecant, or InverseBroyden for multiple shooting).
template <class Vec, class Mat, class Secant = DenseSecant<Vec, Mat>>
class ShootingNewton {
 public:
  /// The next solve starts from `other`'s last solution with its Jacobian, predictor off (a
  /// perturbed repeat of the step `other` has just solved: control's finite differences).
  void warm_from(const ShootingNewton& other) {
    model_ = other.model_;
    valid_ = other.valid_;
    c_ = other.c_;
    prev_ = prev2_ = other.prev_;
  }

  /// Multiple shooting: where no step along a fresh Jacobian's direction reduces the residual,
  /// accept x if each row is within tol of what moving every unknown in its last bits
  /// (kRoundingUlps units of rounding, either way) changes it by: the residual cannot be resolved
  /// further in double precision (the interior joins amplify like the march, e^(kappa / M)).
  void accept_rounding_floor(bool on) { accept_rounding_floor_ = on; }

  /// What the failure messages call the solve ("single shooting"; multiple shooting names its
  /// intervals).
  void name(std::string what) { name_ = std::move(what); }

  /// The first guess of the first step (also the predictor's history).
  void start(const Vec& x0) {
    prev_ = prev2_ = x0;
    valid_ = false;
  }

  /// Solves shoot(x) = 0 to |r|_inf <= tol within max_iterations Newton steps (solver.
  /// max_iterations; a step's backtracking and the Jacobians' columns are not counted: a
  /// Jacobian costs n + 1 integrations, so a budget of integrations ran out after a handful of
  /// Jacobians with actuator unknowns, e.g. the muscle switched on in scenes/muscle-dynamics.yaml
  /// at dt = 2 ms). `shoot` maps the unknowns to the residual and leaves the profiles of its
  /// argument behind, so on success the last call was at the solution. `c` keys the Jacobian's
  /// reuse; `extrapolate` turns the linear predictor on (from the third step: two previous
  /// solutions exist).
  template <class Shoot>
  ShootingOutcome solve(Shoot&& shoot, double c, bool extrapolate, double tol,
                        int max_iterations) {
    auto by_columns = [&shoot](const Vec& x, const Vec& r, Mat& J, int& shots) {
      finite_difference_columns(shoot, x, r, J, shots);
    };
    return solve(shoot, by_columns, c, extrapolate, tol, max_iterations);
  }

  /// The same with the Jacobian from `jacobian(x, r, J, shots)`, which fills J at x (r = shoot
  /// (x)), adds the integrations it spent to shots and leaves the profiles of x behind (multiple
  /// shooting: finite differences interval by interval, each column re-marching one interval).
  template <class Shoot, class Jacobian>
  ShootingOutcome solve(Shoot&& shoot, Jacobian&& jacobian, double c, bool extrapolate,
                        double tol, int max_iterations) {
    ShootingOutcome out;
    Vec x = extrapolate ? Vec(2.0 * prev_ - prev2_) : prev_;
    Vec r = shoot(x);
    ++out.shots;
    auto rebuild = [&] {  // a fresh Jacobian at x
      if (fresh_jacobian(jacobian, x, r, c, out.shots)) return true;
      out.failure = "the Jacobian is not finite";
      return false;
    };
    if ((!valid_ || c != c_) && !rebuild()) return out;
    bool fresh = false;
    int slow_steps = 0;  // slow Broyden steps kept in a row (far from the solution)
    int iterations = 0;  // Newton steps taken
    auto norm = [](const Vec& v) { return v.template lpNorm<Eigen::Infinity>(); };
    while (!(norm(r) <= tol)) {
      check_deadline();  // the run's wall-time guard (common/deadline.hpp)
      if (iterations >= max_iterations || !r.allFinite()) {
        out.failure =
            rodlab::format("{} did not converge (tip residual {:g})", name_, norm(r));
        return out;
      }
      if (!valid_) {  // the model keeps no more updates: a fresh Jacobian here
        if (!rebuild()) return out;
        fresh = true;
      }
      const Vec dx = model_.step(r);
      if (!dx.allFinite()) {
        out.failure = "the shooting Jacobian is singular";
        return out;
      }
      Vec r_new = shoot(Vec(x + dx));
      ++out.shots;
      const bool slow = !(norm(r_new) <= kShootingSlowRatio * norm(r));
      const bool keep_slow = norm(r) >= kShootingNonlinear && norm(r_new) < norm(r) &&
                             slow_steps < kShootingSlowSteps;
      slow_steps = slow && keep_slow ? slow_steps + 1 : 0;
      if (slow && !keep_slow && !fresh) {
        // Broyden's secant model went stale: rebuild the Jacobian where we stand.
        if (!rebuild()) return out;
        fresh = true;
        continue;
      }
      // Even a fresh Jacobian's step may overshoot where the march amplifies (small dt):
      // backtrack along it until the residual falls.
      Vec step = dx;
      for (int k = 0; k < kShootingHalvings && !(norm(r_new) < norm(r)); ++k) {
        step *= 0.5;
        r_new = shoot(Vec(x + step));
        ++out.shots;
      }
      if (!(norm(r_new) < norm(r))) {
        if (accept_rounding_floor_ && at_rounding_floor(shoot, x, r, tol, out.shots)) {
          shoot(x);  // the profiles of the solution
          ++out.shots;
          break;
        }
        shoot(x);  // leave the profiles of the best iterate
        out.failure = rodlab::format(
            "{} did not converge (no step along Newton's direction reduces the tip "
            "residual {:g})",
            name_, norm(r));
        return out;
      }
      ++iterations;
      // Broyden's rank-one update of the secant model; a model that can keep no more asks for a
      // fresh Jacobian at the next iterate
      valid_ = model_.update(step, r, r_new);
      x += step;
      r = r_new;
      fresh = false;
    }
    prev2_ = prev_;
    prev_ = x;
    return out;
  }

 private:
  template <class Jacobian>
  bool fresh_jacobian(Jacobian& jacobian, const Vec& x, const Vec& r, double c, int& shots) {
    jacobian(x, r, model_.jacobian(), shots);
    valid_ = model_.refresh();
    c_ = c;  // the Jacobian depends on the step through c
    return valid_;
  }

  static constexpr double kRoundingUlps = 16.0;

  template <class Shoot>
  static bool at_rounding_floor(Shoot& shoot, const Vec& x, const Vec& r, double tol, int& shots) {
    Vec floor = Vec::Zero(r.size());
    for (const double sign : {1.0, -1.0, 0.0}) {  // 0: x again, from other warm starts
      const double move = sign * kRoundingUlps * std::numeric_limits<double>::epsilon();
      const Vec moved = x + move * x.cwiseAbs();
      floor = floor.cwiseMax((shoot(moved) - r).cwiseAbs());
      ++shots;
    }
    return (r.cwiseAbs().array() <= tol + floor.array()).all();
  }

  /// Forward differences column by column, a whole shot each (single shooting).
  template <class Shoot>
  static void finite_difference_columns(Shoot& shoot, const Vec& x, const Vec& r, Mat& J,
                                        int& shots) {
    J.resize(x.size(), x.size());
    for (Eigen::Index k = 0; k < x.size(); ++k) {
      const double h = kShootingFdStep * std::max(1.0, std::abs(x[k]));
      Vec xp = x;
      xp[k] += h;
      J.col(k) = (shoot(xp) - r) / h;
      ++shots;
    }
    shoot(x);  // restore the profiles of x
    ++shots;
  }

  Secant model_;
  bool valid_ = false;
  bool accept_rounding_floor_ = false;
  std::string name_ = "single shooting";
  double c_ = 0.0;
  Vec prev_, prev2_;
};

}  // namespace rodlab::solvers::dynamics
