#pragma once
// What Guided Policy Search (gps.hpp) needs of an environment beyond LearningEnvironment's
// episodes: the state x its local controllers and dynamics live in, a smooth cost l(x, a) with
// its derivatives for trajectory optimisation, and how the policy's observation depends on x.
// The rod's environment (rod_environment.hpp) is one; the tests' linear plants are others.
//
// The observation is affine in the state for a fixed goal, o = J x + g(t) (observer.hpp: the
// tip, its velocity and the node states are entries of x, the goal is not): GPS linearises its
// policy through J (gps.hpp, "policy linearisation").
#include <span>

#include <Eigen/Core>

#include "rodlab/solvers/learning/learning_environment.hpp"

namespace rodlab::solvers::learning {

/// l and its first and second derivatives at (x, a); l_ax = d2l / da dx.
struct CostExpansion {
  double value = 0.0;
  Eigen::VectorXd lx, la;
  Eigen::MatrixXd lxx, laa, lax;
};

class TrajectoryEnvironment : public LearningEnvironment {
 public:
  virtual int state_size() const = 0;
  /// x now (after reset or step); x.size() == state_size().
  virtual void state(std::span<double> x) const = 0;
  /// l(x, a) of the current episode's goal at control step t (a unclipped: the cost may keep
  /// actions inside [-1, 1]); the expansion if e is given (resized as needed).
  virtual double cost(const Eigen::Ref<const Eigen::VectorXd>& x,
                      const Eigen::Ref<const Eigen::VectorXd>& a, int t,
                      CostExpansion* e) const = 0;
  /// J = d observation / d state (observation_size x state_size), constant.
  virtual const Eigen::MatrixXd& observation_jacobian() const = 0;
  /// Episodes of exactly `steps` control steps: success no longer ends them (GPS samples
  /// trajectories of a fixed length T; success is still reported in each transition).
  virtual void set_fixed_length(int steps) = 0;
};

}  // namespace rodlab::solvers::learning
