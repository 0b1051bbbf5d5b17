// The learning environment (solvers/learning/rod_environment.hpp, issue #15 item 1): the reward
// (4.40) at its cases, the random paths' boundary conditions (closed form), the action map, and
// episodes on the control robot (tests/control/control_support.hpp: the Table 2.1 rod, four
// cables in [0, 0.5] N, alpha = 300 Pa s), implicit-midpoint N = 10, dt_c = 0.05 s.
#define BOOST_TEST_MODULE learning_rod_environment
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "../control/control_support.hpp"
#include "rodlab/solvers/control/inverse_statics.hpp"
#include "rodlab/solvers/learning/rod_environment.hpp"
#include "rodlab/solvers/learning/goal_pool.hpp"
#include "rodlab/solvers/learning/polynomial_path.hpp"
#include "rodlab/solvers/learning/reward.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace l = rodlab::solvers::learning;
using rodlab::lie::Vector3;
using rodlab::testing::control::cable_robot;
using rodlab::testing::control::plant_options;

namespace {

constexpr double L = 0.1;

l::EnvironmentOptions options(l::LearningTask task, int state_nodes = 0) {
  l::EnvironmentOptions o;
  o.plant = plant_options("implicit-midpoint", 10, 0.05);
  o.task = task;
  o.state_nodes = state_nodes;
  return o;
}

/// A pool of points 3 cm off the axis on the side of cables 1-3 (for episodes that only step:
/// the tests pull cable 0, towards +x, so none of them is reached early).
l::GoalPool pool() {
  return {{Vector3(0, 0.03, 0.09), Vector3(0, -0.03, 0.09), Vector3(-0.03, 0, 0.09),
           Vector3(-0.02, 0.02, 0.09), Vector3(-0.02, -0.02, 0.09)}};
}

/// A quasi-static tip and the actions that hold it: the tip of u = (0.3, 0, 0, 0) N, by inverse
/// statics (N = 10) for a target next to it, which it then reports exactly.
struct StaticTip {
  Vector3 tip;
  std::vector<double> actions;
};
StaticTip static_tip() {
  rodlab::solvers::control::InverseStaticsOptions is;
  is.statics.nodes = 10;
  const auto scene = cable_robot();
  rodlab::solvers::control::InverseStatics statics(scene, is);
  const auto r = statics.solve(Vector3(0.02, 0.0, 0.097));
  BOOST_TEST_REQUIRE(r.converged);
  StaticTip s{r.tip, std::vector<double>(4)};
  for (int k = 0; k < 4; ++k) s.actions[k] = 2.0 * r.u[k] / 0.5 - 1.0;
  return s;
}

}  // namespace

// (4.40) with beta = 0.3, L = 0.1 m: 0 on the target, -e / (beta L) inside beta L = 3 cm, -1
// outside; continuous at the edge. Closed form.
BOOST_AUTO_TEST_CASE(reward_4_40_at_its_cases) {
  const double b = l::kThesisBeta;
  BOOST_TEST(l::reward(0.0, b, L) == 0.0);
  BOOST_TEST(l::reward(0.015, b, L) == -0.5, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(l::reward(0.03, b, L) == -1.0, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(l::reward(0.03 * (1 - 1e-12), b, L) > -1.0);
  BOOST_TEST(l::reward(0.06, b, L) == -1.0);
  BOOST_TEST(l::reward(1e3, b, L) == -1.0);
}

// The quartic's five conditions (closed form, polynomial_path.hpp), evaluated on the polynomial
// itself just inside [0, T] (at the ends the path returns its end points): p -> p0 and p' -> v0
// at 0+, p'' (0) = 0 (the difference quotient of p' falls linearly with h: 3 c3 h), p -> p1 and
// p' = v1 at T; p' is p's derivative inside (central differences, 1e-9); it waits outside.
BOOST_AUTO_TEST_CASE(random_path_meets_its_end_conditions) {
  const Vector3 p0(0.01, -0.02, 0.09), v0(0.003, -0.001, 0.002), p1(-0.015, 0.01, 0.095),
      v1(-0.002, 0.004, 0.0);
  const double T = 4.0, eps = 1e-12;
  const l::PolynomialPath path(p0, v0, p1, v1, T);
  BOOST_TEST((path.position(eps) - p0).norm() < 1e-14);
  BOOST_TEST((path.velocity(eps) - v0).norm() < 1e-14);
  BOOST_TEST((path.position(T - eps) - p1).norm() < 1e-14);
  BOOST_TEST((path.velocity(T) - v1).norm() < 1e-15);
  const double a3 = (path.velocity(1e-3) - v0).norm() / 1e-3;  // 3 |c3| 1e-3 + O(1e-6)
  const double a4 = (path.velocity(1e-4) - v0).norm() / 1e-4;
  BOOST_TEST(a4 < 0.11 * a3);  // -> 0: p''(0) = 0
  for (const double t : {0.7, 2.0, 3.3}) {
    const Vector3 fd = (path.position(t + 1e-5) - path.position(t - 1e-5)) / 2e-5;
    BOOST_TEST((fd - path.velocity(t)).norm() < 1e-9);
  }
  BOOST_TEST((path.position(-1) - p0).norm() == 0.0);
  BOOST_TEST((path.position(T + 1) - p1).norm() == 0.0);
  BOOST_TEST(path.velocity(T + 1).norm() == 0.0);
  BOOST_CHECK_THROW(l::PolynomialPath(p0, v0, p1, v1, 0.0), std::invalid_argument);
}

// Actions in [-1, 1] map onto each cable's [0, 0.5] N linearly; beyond the box they are clipped.
BOOST_AUTO_TEST_CASE(actions_map_onto_the_limits) {
  l::RodEnvironment env(cable_robot(), options(l::LearningTask::reach_any), pool());
  BOOST_TEST(env.action_size() == 4);
  BOOST_TEST(env.observation_size() == 9);
  Eigen::VectorXd u;
  const std::vector<double> a{-1.0, 0.0, 1.0, 3.0};
  env.action_to_input(a, u);
  BOOST_TEST(u[0] == 0.0);
  BOOST_TEST(u[1] == 0.25);
  BOOST_TEST(u[2] == 0.5);
  BOOST_TEST(u[3] == 0.5);  // clipped
  const std::vector<double> three{0.0, 0.0, 0.0};
  BOOST_CHECK_THROW(env.action_to_input(three, u), std::invalid_argument);
}

// The same seed gives the same goal and, under the same actions, the same observations and
// rewards bit for bit; the reward is (4.40) of the reported error; the observation holds the
// tip / L, its mean velocity over the step and the goal / L.
BOOST_AUTO_TEST_CASE(episodes_repeat_with_their_seed) {
  l::RodEnvironment env(cable_robot(), options(l::LearningTask::reach_any), pool());
  std::vector<double> o1(9), o2(9);
  const std::vector<double> a{0.4, -1.0, -0.8, -1.0};
  std::vector<double> first, second;
  for (auto* trace : {&first, &second}) {
    env.reset(7, o1);
    trace->insert(trace->end(), o1.begin(), o1.end());
    for (int k = 0; k < 4; ++k) {
      const Vector3 before = env.tip();
      const l::Transition tr = env.step(a, o2);
      BOOST_TEST_REQUIRE(!tr.failed, tr.reason);
      BOOST_TEST(tr.reward == l::reward(tr.error, 0.3, L));
      BOOST_TEST(tr.error == (env.tip() - env.goal().position(env.time())).norm());
      for (int i = 0; i < 3; ++i) {
        BOOST_TEST(o2[i] == env.tip()[i] / L);
        BOOST_TEST(o2[6 + i] == env.goal().position(env.time() + 0.05)[i] / L);
      }
      const Vector3 v = (env.tip() - before) / 0.05;
      BOOST_TEST(v.norm() > 0.0);  // the rod moves
      for (int i = 0; i < 3; ++i) BOOST_TEST(o2[3 + i] == v[i] * env.period() / L);
      trace->insert(trace->end(), o2.begin(), o2.end());
      trace->push_back(tr.reward);
    }
  }
  BOOST_TEST(first == second, boost::test_tools::per_element());
  // other seeds draw other goals: 20 seeds reach at least 4 of the pool's 5 points
  std::vector<Vector3> seen;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    env.reset(seed, o1);
    const Vector3 g = *env.goal().point;
    if (std::none_of(seen.begin(), seen.end(), [&](const Vector3& s) { return s == g; }))
      seen.push_back(g);
  }
  BOOST_TEST(seen.size() >= 4u);
}

// Reaching: the goal is the static tip under 0.3 N on cable 0 (forward statics, chebyshev);
// holding the action of that input, the damped rod settles there and the episode ends in
// success within 5 % of L before max_steps; a step after the end is refused.
BOOST_AUTO_TEST_CASE(holding_the_right_input_reaches_its_static_tip) {
  const StaticTip r = static_tip();
  l::Goal goal;
  goal.point = r.tip;
  l::RodEnvironment env(cable_robot(), options(l::LearningTask::reach_one), {{r.tip}});
  std::vector<double> o(9), a = r.actions;
  env.reset(goal, o);
  l::Transition tr;
  while (!tr.done) tr = env.step(a, o);
  BOOST_TEST(tr.success);
  BOOST_TEST(!tr.failed);
  BOOST_TEST(tr.error < 0.05 * L);
  BOOST_TEST(env.steps() < 100);
  BOOST_TEST(tr.reward > -0.05 / 0.3);
  BOOST_CHECK_THROW(env.step(a, o), std::invalid_argument);
}

// Tracking: a random quartic between two pool points; the episode lasts the path's duration in
// control steps (4 s / 0.05 s = 80), its observation adds the goal's velocity; the state of K
// nodes adds K (6 + 6) coordinates divided by their characteristic sizes.
BOOST_AUTO_TEST_CASE(track_episodes_last_the_path) {
  l::RodEnvironment env(cable_robot(), options(l::LearningTask::track, 3), pool());
  BOOST_TEST(env.observation_size() == 12 + 3 * 12);
  std::vector<double> o(static_cast<std::size_t>(env.observation_size()));
  env.reset(3, o);
  BOOST_TEST_REQUIRE(env.goal().path.has_value());
  const std::vector<double> a{-1.0, -1.0, -1.0, -1.0};
  int steps = 0;
  for (l::Transition tr; !tr.done; ++steps) tr = env.step(a, o);
  BOOST_TEST(steps == 80);
  // at rest and slack the state is zero: the observed strains and velocities too
  for (std::size_t i = 12; i < o.size(); ++i) BOOST_TEST(std::abs(o[i]) < 1e-12);
  // a reach goal for a track environment is refused
  l::Goal point;
  point.point = Vector3(0, 0, 0.1);
  BOOST_CHECK_THROW(env.reset(point, o), std::invalid_argument);
}

// reach-one's goal lies in the dynamic workspace but outside the static one: its closest
// quasi-static tip (inverse statics) is farther than the success threshold.
BOOST_AUTO_TEST_CASE(reach_one_goal_cannot_be_held) {
  auto scene = cable_robot();
  const auto o = options(l::LearningTask::reach_one);
  l::GoalPoolOptions po;
  po.dynamic_holds = 10;
  const l::GoalPool p = l::make_goal_pool(scene, o, po);
  BOOST_TEST_REQUIRE(p.points.size() == 1u);
  rodlab::solvers::control::InverseStaticsOptions is;
  is.statics.nodes = 10;
  rodlab::solvers::control::InverseStatics statics(scene, is);
  const auto r = statics.solve(p.points.front());
  BOOST_TEST(r.error > 0.05 * L);
  BOOST_TEST((p.points.front() - Vector3(0, 0, L)).norm() > 0.05 * L);
}

// A failed plant step (single shooting allowed one Newton iteration: it cannot converge after a
// 0.5 N jump) ends the episode as terminal and failed, with the reason, reward -1, and the
// observation and error of before the step (finite: the state where the scheme stopped is not
// observed, so nothing non-finite reaches a replay buffer).
BOOST_AUTO_TEST_CASE(a_failed_step_is_reported_and_observes_nothing_new) {
  auto o = options(l::LearningTask::reach_any);
  o.plant.solver.max_iterations = 1;
  l::RodEnvironment env(cable_robot(), o, pool());
  std::vector<double> before(9), after(9);
  env.reset(1, before);
  const std::vector<double> a{1.0, -1.0, -1.0, -1.0};
  const l::Transition tr = env.step(a, after);
  BOOST_TEST_REQUIRE(tr.failed);
  BOOST_TEST(tr.done);
  BOOST_TEST(tr.terminal);
  BOOST_TEST(!tr.success);
  BOOST_TEST(tr.reward == -1.0);
  BOOST_TEST(!tr.reason.empty());
  BOOST_TEST(after == before, boost::test_tools::per_element());
  BOOST_TEST(tr.error == (Vector3(0, 0, L) - env.goal().position(0.0)).norm(),
             boost::test_tools::tolerance(1e-12));
}

// GPS's cost (tip_cost.hpp) and its expansion: value, gradient and Hessian against central
// differences (h = 1e-6 and 1e-4) at a point where every term is active (an action beyond the
// box, a velocity error), before and at the last step (running and final weights differ).
BOOST_AUTO_TEST_CASE(gps_cost_derivatives_match_finite_differences) {
  l::TipCost cost;
  cost.velocity = 0.7;
  cost.running = 0.8;
  cost.final = 5.0;
  const Eigen::Vector3d goal(0.2, -0.1, 0.9), goal_velocity(0.05, 0.0, -0.02);
  Eigen::VectorXd x(8), a(3);
  x << 0.25, -0.02, 0.93, 0.1, -0.05, 0.02, 0.3, -0.4;
  a << 1.3, -0.2, -1.6;
  for (const bool last : {false, true}) {
    l::CostExpansion e;
    const double value = cost(x, a, goal, goal_velocity, last, &e);
    BOOST_TEST(value == cost(x, a, goal, goal_velocity, last, nullptr));
    const auto l_of = [&](const Eigen::VectorXd& xx, const Eigen::VectorXd& aa) {
      return cost(xx, aa, goal, goal_velocity, last, nullptr);
    };
    const auto grad_of = [&](const Eigen::VectorXd& xx, const Eigen::VectorXd& aa) {
      l::CostExpansion g;
      cost(xx, aa, goal, goal_velocity, last, &g);
      Eigen::VectorXd out(11);
      out << g.lx, g.la;
      return out;
    };
    Eigen::VectorXd z(11);
    z << x, a;
    Eigen::VectorXd g(11);
    g << e.lx, e.la;
    Eigen::MatrixXd H(11, 11);
    H << e.lxx, e.lax.transpose(), e.lax, e.laa;
    for (int i = 0; i < 11; ++i) {
      Eigen::VectorXd zp = z, zm = z;
      zp[i] += 1e-6;
      zm[i] -= 1e-6;
      const double fd = (l_of(zp.head(8), zp.tail(3)) - l_of(zm.head(8), zm.tail(3))) / 2e-6;
      BOOST_TEST(g[i] == fd, boost::test_tools::tolerance(1e-6));
      zp[i] += 1e-4 - 1e-6;
      zm[i] -= 1e-4 - 1e-6;
      const Eigen::VectorXd hd =
          (grad_of(zp.head(8), zp.tail(3)) - grad_of(zm.head(8), zm.tail(3))) / 2e-4;
      BOOST_TEST((hd - H.col(i)).norm() < 1e-5 * std::max(1.0, H.col(i).norm()));
    }
  }
}

// The GPS interface of the rod's environment: the state is the observation without the goal,
// o = J x + goal (J a 0/1 selection), with track's goal velocity and K = 2 nodes; in fixed-length
// episodes a success does not end the episode (holding a quasi-static tip's input, which ends
// a normal episode early, runs all 30 steps).
BOOST_AUTO_TEST_CASE(gps_state_and_fixed_length_episodes) {
  l::RodEnvironment env(cable_robot(), options(l::LearningTask::track, 2), pool());
  const int n = env.state_size(), no = env.observation_size();
  BOOST_TEST(n == 6 + 2 * 12);
  BOOST_TEST(no == n + 6);
  std::vector<double> o(static_cast<std::size_t>(no)), x(static_cast<std::size_t>(n));
  env.reset(5, o);
  const std::vector<double> a{0.6, -1.0, -0.2, -1.0};
  for (int k = 0; k < 5; ++k) env.step(a, o);
  env.state(x);
  const Eigen::VectorXd ox = env.observation_jacobian() * Eigen::Map<Eigen::VectorXd>(x.data(), n);
  for (int i = 0; i < no; ++i) {
    const bool goal_entry = i >= 6 && i < 12;
    if (!goal_entry) BOOST_TEST(ox[i] == o[static_cast<std::size_t>(i)]);
    if (goal_entry) BOOST_TEST(ox[i] == 0.0);
  }
  // the cost at the state: (4.40)'s |d| / beta term grows with the distance to the goal
  const Eigen::VectorXd xv = Eigen::Map<Eigen::VectorXd>(x.data(), n);
  const Eigen::VectorXd av = Eigen::Map<const Eigen::VectorXd>(a.data(), 4);
  BOOST_TEST(std::isfinite(env.cost(xv, av, 5, nullptr)));

  const StaticTip r = static_tip();
  l::RodEnvironment reach(cable_robot(), options(l::LearningTask::reach_one), {{r.tip}});
  reach.set_fixed_length(30);
  std::vector<double> o9(9), u = r.actions;
  reach.reset(1, o9);
  int steps = 0, successes = 0;
  for (l::Transition tr; !tr.done; ++steps) {
    tr = reach.step(u, o9);
    successes += tr.success ? 1 : 0;
    BOOST_TEST(!tr.terminal);
  }
  BOOST_TEST(steps == 30);
  BOOST_TEST(successes > 0);
}
