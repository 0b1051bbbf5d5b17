// NLSQ-MPC (solvers/control/nlsq_mpc.hpp): its Jacobian from propagated directional derivatives
// against central differences of whole rollouts, and a reach of a static target (the forward
// statics of known tensions) within the thesis' success threshold with inputs inside limits.
#define BOOST_TEST_MODULE control_nlsq_mpc
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "control_support.hpp"
#include "rodlab/solvers/control/nlsq_mpc.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace c = rodlab::solvers::control;
using rodlab::lie::Vector3;
using rodlab::testing::control::cable_robot;
using rodlab::testing::control::plant_options;

namespace {

/// The static tip under tensions u (rkmk-rk4, N = 101): a target in the static workspace.
Vector3 static_tip(const Eigen::VectorXd& u) {
  rodlab::scene::Scene scene = cable_robot();
  for (int k = 0; k < 4; ++k)
    std::get<rodlab::scene::Cable>(scene.actuators[k]).tension = rodlab::scene::ScalarSchedule(u[k]);
  rodlab::solvers::statics::StaticSolveOptions o;
  o.nodes = 101;
  const auto r = rodlab::solvers::statics::solve_static(scene, o);
  BOOST_REQUIRE(r.converged);
  return r.centerline.back().pose.translation();
}

}  // namespace

// The tip trajectory's Jacobian against central differences of whole rollouts in each input
// (step 1e-4 of the range), built from the steps' own linearisations (implicit midpoint) or from
// directional derivatives propagated along the rollout (forward differences; variational, and
// implicit midpoint on request): agreement to 1e-3 of the largest entry (the forward
// differences' O(h) error and the shooting tolerance over the step; measured 9e-5 and 6e-7),
// and to 1e-7 for the linearised steps (measured 1.2e-9: the rollouts' differences' own error).
BOOST_AUTO_TEST_CASE(tip_jacobian_matches_rollout_differences) {
  for (const auto& [scheme, method] : std::vector<std::pair<std::string, c::JacobianMethod>>{
           {"implicit-midpoint", c::JacobianMethod::implicit_function},
           {"implicit-midpoint", c::JacobianMethod::finite_difference},
           {"variational", c::JacobianMethod::implicit_function}}) {  // (variational: differences)
    BOOST_TEST_CONTEXT(scheme << (method == c::JacobianMethod::finite_difference ? " differenced" : "")) {
      c::Plant plant(cable_robot(), plant_options(scheme, 8, 0.02));
      c::MpcOptions o;
      o.horizon = 4;
      o.jacobian = method;
      c::NlsqMpc mpc(plant, o);
      const std::vector<Vector3> targets(4, Vector3(0.01, 0.0, 0.099));
      // inside the limits, so that central differences stay feasible
      Eigen::VectorXd U(16);
      U << 0.2, 0.01, 0.02, 0.1, 0.3, 0.05, 0.01, 0.1, 0.25, 0.1, 0.02, 0.01, 0.1, 0.2, 0.05, 0.01;
      Eigen::VectorXd r, rp, rm;
      Eigen::MatrixXd J;
      std::string why;
      BOOST_REQUIRE(mpc.evaluate(plant, targets, U, r, &J, why));
      BOOST_TEST(J.rows() == 12 + 16);
      double worst = 0.0, largest = 0.0;
      for (int col = 0; col < 16; ++col) {
        const double h = 1e-4 * 0.5;
        Eigen::VectorXd up = U, down = U;
        up[col] += h;
        down[col] -= h;
        BOOST_REQUIRE(mpc.evaluate(plant, targets, up, rp, nullptr, why));
        BOOST_REQUIRE(mpc.evaluate(plant, targets, down, rm, nullptr, why));
        const Eigen::VectorXd fd = (rp - rm) / (2 * h);
        worst = std::max(worst, (fd - J.col(col)).cwiseAbs().maxCoeff());
        largest = std::max(largest, fd.cwiseAbs().maxCoeff());
      }
      BOOST_TEST_MESSAGE(scheme << ": max |J - FD| " << worst << " of max |J| " << largest);
      const bool linearised = scheme == "implicit-midpoint" &&
                              method == c::JacobianMethod::implicit_function;
      BOOST_TEST(worst < (linearised ? 1e-7 : 1e-3) * largest);
      // causality: p_1 does not depend on u_1..u_3
      BOOST_TEST(J.block(0, 4, 3, 12).cwiseAbs().maxCoeff() == 0.0);
    }
  }
}

// Reach and hold a static target (the statics of tensions (0.3, 0, 0, 0.1) N) from rest on the
// implicit midpoint at dt_c = 0.05 s, H = 5: the tip gets within the thesis' success threshold
// (5 % of L) and ends within 1 mm; every applied tension lies in [0, 0.5] N.
BOOST_AUTO_TEST_CASE(reaches_a_static_target) {
  c::Plant plant(cable_robot(), plant_options("implicit-midpoint", 10, 0.05));
  c::MpcOptions o;
  o.horizon = 5;
  c::NlsqMpc mpc(plant, o);
  Eigen::VectorXd u_star(4);
  u_star << 0.3, 0.0, 0.0, 0.1;
  const Vector3 target = static_tip(u_star);
  const std::vector<Vector3> targets(5, target);
  double first_success = -1.0, error = 0.0;
  for (int step = 0; step < 40; ++step) {
    const auto t0 = std::chrono::steady_clock::now();
    const c::MpcPlan plan = mpc.plan(plant, targets);
    BOOST_TEST_MESSAGE("plan " << step << ": " << plan.iterations << " iterations, "
                       << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()
                       << " s, cost " << plan.cost);
    BOOST_REQUIRE_MESSAGE(plan.ok, plan.reason);
    BOOST_TEST((plan.u.array() >= 0.0).all());
    BOOST_TEST((plan.u.array() <= 0.5).all());
    plant.set_input(plan.u);
    BOOST_REQUIRE(plant.advance().ok);
    error = (plant.tip() - target).norm();
    if (first_success < 0 && error < 0.05 * 0.1) first_success = plant.time();
  }
  BOOST_TEST_MESSAGE("reached 5 % of L at t = " << first_success << " s; final error " << error
                                                 << " m");
  BOOST_TEST(first_success > 0.0);
  BOOST_TEST(error < 1e-3);
}

