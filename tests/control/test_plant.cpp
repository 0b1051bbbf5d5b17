// The plant of the controllers (solvers/control/plant.hpp): snapshots repeat a run bit for bit,
// the held input is the schedule's constant, the tangent coordinates are the strains and
// velocities (closed form: a uniform bend is the constant-curvature arc), bounds are enforced.
#define BOOST_TEST_MODULE control_plant
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "control_support.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/implicit_midpoint_collocation.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

namespace c = rodlab::solvers::control;
namespace d = rodlab::solvers::dynamics;
using rodlab::testing::control::cable_robot;
using rodlab::testing::control::plant_options;

namespace {

struct Case {
  std::string scheme, model, grid;
  double dt = 0.0;  ///< the scheme's step (0: the plant's default)
};

// The schemes the plant supports, Cosserat and Kirchhoff, on their default grids.
const std::vector<Case> kCases = {{"variational", "cosserat", ""},
                                  {"variational", "kirchhoff", ""},
                                  {"implicit-midpoint", "cosserat", ""},
                                  {"implicit-midpoint", "kirchhoff", ""},
                                  {"bdf-alpha", "cosserat", ""},
                                  {"implicit-midpoint-collocation", "cosserat", ""},
                                  {"implicit-midpoint-collocation", "kirchhoff", ""},
                                  // small steps: a solve starts from the kept KLU factors
                                  {"implicit-midpoint-collocation", "cosserat", "", 1e-3}};

c::Plant make(const Case& k, double dt_control = 0.01, int nodes = 10) {
  c::PlantOptions o = plant_options(k.scheme, nodes, dt_control);
  o.solver.dt = k.dt;
  return c::Plant(cable_robot(k.model), o);
}

Eigen::VectorXd input(double a, double b, double c_, double d_) {
  Eigen::VectorXd u(4);
  u << a, b, c_, d_;
  return u;
}

/// Collocation's count of finite-difference Jacobians so far; 0 for the other schemes.
long fresh_jacobians(const c::Plant& p) {
  const auto* collocation =
      dynamic_cast<const d::ImplicitMidpointCollocationStepper*>(&p.stepper());
  return collocation ? collocation->jacobian_evaluations() : 0;
}

Eigen::VectorXd state(const c::Plant& p) {
  Eigen::VectorXd x(p.state_size());
  p.read_state(std::span<double>(x.data(), x.size()));
  return x;
}

}  // namespace

// A rollout from a restored snapshot repeats the original steps exactly (the controllers'
// rollouts depend on it): every member that a step changes is part of the state.
BOOST_AUTO_TEST_CASE(restored_snapshot_repeats_bit_for_bit) {
  for (const Case& k : kCases) {
    BOOST_TEST_CONTEXT(k.scheme << " " << k.model << " dt " << k.dt) {
      c::Plant plant = make(k);
      plant.set_input(input(0.4, 0.1, 0.0, 0.0));
      for (int i = 0; i < 3; ++i) BOOST_REQUIRE(plant.advance().ok);
      c::PlantSnapshot snap = plant.snapshot();
      std::vector<rodlab::lie::Vector3> tips;
      std::vector<Eigen::VectorXd> states;
      for (int i = 0; i < 4; ++i) {
        BOOST_REQUIRE(plant.advance().ok);
        tips.push_back(plant.tip());
        states.push_back(state(plant));
      }
      // another future in between, then the first one again; collocation's goes on until it
      // has a new Jacobian (and KLU new factors: a step may start from the kept ones)
      plant.restore(snap);
      plant.set_input(input(0.0, 0.5, 0.2, 0.0));
      const long jacobians = fresh_jacobians(plant);
      for (int i = 0; i < 2 || (i < 60 && fresh_jacobians(plant) == jacobians); ++i) {
        const auto status = plant.advance();
        BOOST_TEST_REQUIRE(status.ok, status.reason);
      }
      BOOST_TEST(fresh_jacobians(plant) >= jacobians);
      BOOST_TEST((plant.tip() - tips[1]).norm() > 1e-6);  // it did go elsewhere
      c::PlantSnapshot other = plant.snapshot();
      plant.save(other);
      plant.restore(snap);
      BOOST_TEST(plant.input()[0] == 0.4);
      for (int i = 0; i < 4; ++i) {
        BOOST_REQUIRE(plant.advance().ok);
        BOOST_TEST((plant.tip() - tips[i]).norm() == 0.0);  // bit for bit
        BOOST_TEST((state(plant) - states[i]).norm() == 0.0);
      }
    }
  }
}

// Holding u over the control steps is the constant schedule: the plant's tip after 0.04 s equals
// `rodlab dynamic`'s (solve_dynamic) with the tensions as constants and the same step (the same
// code, so to rounding: 1e-14 m).
BOOST_AUTO_TEST_CASE(held_input_is_the_constant_schedule) {
  for (const Case& k : {kCases[0], kCases[2], kCases[5]}) {
    BOOST_TEST_CONTEXT(k.scheme) {
      c::Plant plant = make(k);
      plant.set_input(input(0.3, 0.0, 0.0, 0.2));
      for (int i = 0; i < 4; ++i) BOOST_REQUIRE(plant.advance().ok);
      rodlab::scene::Scene scene = cable_robot(k.model);
      std::get<rodlab::scene::Cable>(scene.actuators[0]).tension = rodlab::scene::ScalarSchedule(0.3);
      std::get<rodlab::scene::Cable>(scene.actuators[3]).tension = rodlab::scene::ScalarSchedule(0.2);
      d::DynamicSolveOptions o;
      o.scheme = k.scheme;
      o.nodes = 10;
      o.dt = plant.substep();
      o.t_end = 0.04;
      const auto run = d::solve_dynamic(scene, o);
      BOOST_REQUIRE(run.converged);
      BOOST_TEST(plant.time() == 0.04, boost::test_tools::tolerance(1e-12));
      BOOST_TEST((plant.tip() - run.tip_position.back()).norm() < 1e-14);
      BOOST_TEST(plant.tip().x() > 1e-4);  // the +x cable bent it towards +x
    }
  }
}

// The tangent coordinates are the segment strains minus xi* and the node velocities: reading
// after a move returns the move, and a uniform bending strain kappa about y puts the tip on the
// constant-curvature arc ((1 - cos kappa L) / kappa, 0, sin kappa L / kappa) (closed form, to
// rounding).
BOOST_AUTO_TEST_CASE(tangent_coordinates_are_strains_and_velocities) {
  const double kappa = 8.0, L = 0.1;
  for (const Case& k : kCases) {
    BOOST_TEST_CONTEXT(k.scheme << " " << k.model) {
      c::Plant plant = make(k);
      const int n = plant.state_size();
      const int strain = k.model == "kirchhoff" ? 3 : 6;
      BOOST_TEST(n == 9 * strain + 9 * 6);
      BOOST_TEST(plant.state_scale().size() == n);
      std::vector<double> x(n), dx(n, 0.0), y(n);
      plant.read_state(x);
      for (double v : x) BOOST_TEST(std::abs(v) < 1e-14);  // at rest, straight (rounding of log)
      for (int j = 0; j < 9; ++j) dx[j * strain + 1] = kappa;
      for (int i = 9 * strain; i < n; ++i) dx[i] = 1e-3 * (i % 7);  // some velocities
      plant.add_state(dx);
      plant.read_state(y);
      // collocation stores poses and reads the strains back as log(g_j^-1 g_(j+1)) / ds (3.38):
      // the rounding of the poses over ds (1.1e-14 measured)
      const bool from_poses = k.scheme == "implicit-midpoint-collocation";
      const double rounding = from_poses ? 8.0 * std::numeric_limits<double>::epsilon() / (L / 9)
                                         : 1e-14;
      for (int i = 0; i < n; ++i) BOOST_TEST(std::abs(y[i] - x[i] - dx[i]) < rounding);
      const rodlab::lie::Vector3 arc((1 - std::cos(kappa * L)) / kappa, 0.0,
                                     std::sin(kappa * L) / kappa);
      BOOST_TEST((plant.tip() - arc).norm() < 1e-15);
      const auto status = plant.advance();  // a moved state steps
      BOOST_TEST_REQUIRE(status.ok, status.reason);
    }
  }
}

// A controller's model of another scheme takes over the plant's state (set_state_of; the
// model-plant split of control.model_scheme): after three control steps of the plant under a
// 0.4 N / 0.1 N pull, the model's tangent coordinates, tip, time and input are the plant's.
// Reference: the plant's own; tolerance: the rounding of the strains read back from poses
// (collocation, as in tangent_coordinates_are_strains_and_velocities: 8 eps / ds ~ 1.6e-13)
// and of the tip integrated from them (1e-14 m: 45 eps L). Plants of different rod models (Cosserat: 6 strains per
// segment, Kirchhoff: 3) are refused.
BOOST_AUTO_TEST_CASE(a_model_of_another_scheme_takes_over_the_plant_state) {
  const double L = 0.1;
  for (const std::string model : {"cosserat", "kirchhoff"}) {
    for (const std::string plant_scheme : {"variational", "implicit-midpoint"}) {
      c::Plant plant = make({plant_scheme, model, ""});
      plant.set_input(input(0.4, 0.1, 0, 0));
      for (int k = 0; k < 3; ++k) BOOST_TEST_REQUIRE(plant.advance().ok);
      const Eigen::VectorXd x = state(plant);
      BOOST_TEST_REQUIRE(x.cwiseAbs().maxCoeff() > 1.0);  // a bent, moving rod
      for (const std::string_view model_scheme : rodlab::scene::kModelSchemes) {
        BOOST_TEST_CONTEXT(model << ": plant " << plant_scheme << ", model " << model_scheme) {
          c::Plant m = make({std::string(model_scheme), model, ""});
          m.set_state_of(plant);
          const double rounding = 8.0 * std::numeric_limits<double>::epsilon() / (L / 9);
          BOOST_TEST((state(m) - x).cwiseAbs().maxCoeff() < rounding);
          BOOST_TEST((m.tip() - plant.tip()).norm() < 1e-14);  // 2.5e-15 m measured
          BOOST_TEST(m.time() == plant.time());
          BOOST_TEST((m.input() - plant.input()).norm() == 0.0);
          BOOST_TEST_REQUIRE(m.advance().ok);  // and predicts from there
        }
      }
    }
  }
  c::Plant cosserat = make(kCases[2]), kirchhoff = make(kCases[3]);
  BOOST_CHECK_THROW(cosserat.set_state_of(kirchhoff), std::invalid_argument);
}

// Inputs outside their limits are refused (a controller bug, not a clip); a scene without
// limits, a clamped tip or a scheme without control support is refused up front.
BOOST_AUTO_TEST_CASE(bounds_and_unsupported_set_ups_are_refused) {
  c::Plant plant = make(kCases[2]);
  BOOST_TEST(plant.input_count() == 4);
  BOOST_TEST(plant.lower()[2] == 0.0);
  BOOST_TEST(plant.upper()[2] == 0.5);
  BOOST_CHECK_THROW(plant.set_input(input(0.6, 0, 0, 0)), std::invalid_argument);
  BOOST_CHECK_THROW(plant.set_input(input(-0.1, 0, 0, 0)), std::invalid_argument);
  BOOST_CHECK_THROW(plant.set_input(Eigen::VectorXd::Zero(3)), std::invalid_argument);
  BOOST_CHECK_EXCEPTION(
      c::Plant(cable_robot("cosserat", "span: [0, 0.1]"), plant_options("variational", 10, 0.01)),
      std::invalid_argument, [](const std::invalid_argument& e) {
        return std::string(e.what()).find("limits") != std::string::npos;
      });
  BOOST_CHECK_EXCEPTION(c::Plant(cable_robot(), plant_options("ida", 10, 0.01)),
                        std::invalid_argument, [](const std::invalid_argument& e) {
                          return std::string(e.what()).find("control") != std::string::npos;
                        });
  BOOST_CHECK_THROW(c::Plant(cable_robot(), plant_options("variational", 10, 0.0)),
                    std::invalid_argument);
}

// `variational` takes as many equal steps below its stability limit as a control step needs.
BOOST_AUTO_TEST_CASE(variational_substeps_below_its_limit) {
  c::Plant plant = make(kCases[0], 0.01);
  const double limit = d::variational_stable_step(plant.problem(), 10);
  BOOST_TEST(plant.substeps() > 1);
  BOOST_TEST(plant.substep() <= limit);
  BOOST_TEST(plant.substep() * plant.substeps() == 0.01, boost::test_tools::tolerance(1e-14));
}

// implicit-midpoint-collocation and implicit-midpoint (staggered grid) discretise the same
// semi-discrete rod with the midpoint rule, but collocation applies it to the poses' embedding
// coordinates (p, q) and the shooting march to the strains (docs/dynamics.md "Lower step
// bound"): their plants agree to O(dt^2), not to the solvers' tolerance. Five control steps of
// 10 ms under a 0.4 N / 0.1 N pull from rest, N = 10, two or four substeps (dt = 5, 2.5 ms).
// Measured |tip difference|: Kirchhoff 1.5e-6, 3.8e-7 m (ratio 3.9); Cosserat 2.8e-5, 4.0e-6 m
// (ratio 7: its shear and axial modes, which the pull excites and the midpoint rule does not
// damp, are resolved only at the smaller step). Each scheme's own time error, nearly the same
// for both, is 200 times larger (Kirchhoff: 3.2e-4, 7.0e-5 m against collocation at dt =
// 0.16 ms) and 10-20 times larger (Cosserat: 2.7e-4, 8.6e-5 m). At one substep (dt = 10 ms, the
// plant's default) the difference is 2.2e-4 m (Kirchhoff), 5.6e-4 m (Cosserat), below that
// time error (0.8-1.3e-3 m).
BOOST_AUTO_TEST_CASE(collocation_agrees_with_implicit_midpoint_to_second_order) {
  for (const std::string model : {"kirchhoff", "cosserat"}) {
    BOOST_TEST_CONTEXT(model) {
      std::vector<double> gap;
      for (int substeps : {2, 4}) {
        auto run = [&](const std::string& scheme) {
          c::PlantOptions o = plant_options(scheme, 10, 0.01);
          o.solver.dt = 0.01 / substeps;
          c::Plant plant(cable_robot(model), o);
          BOOST_TEST_REQUIRE(plant.substeps() == substeps);
          plant.set_input(input(0.4, 0.1, 0.0, 0.0));
          for (int i = 0; i < 5; ++i) {
            const auto status = plant.advance();
            BOOST_TEST_REQUIRE(status.ok, status.reason);
          }
          return plant.tip();
        };
        gap.push_back((run("implicit-midpoint-collocation") - run("implicit-midpoint")).norm());
        BOOST_TEST_MESSAGE(model << ", " << substeps << " substeps: |tip difference| "
                                 << gap.back() << " m");
      }
      const bool kirchhoff = model == "kirchhoff";
      BOOST_TEST(gap[0] < (kirchhoff ? 3e-6 : 5e-5));
      BOOST_TEST(gap[1] < (kirchhoff ? 8e-7 : 8e-6));
      BOOST_TEST(gap[0] / gap[1] > 3.5);  // second order at least
      if (kirchhoff) BOOST_TEST(gap[0] / gap[1] < 4.5);
    }
  }
}

// warm_start_from (finite differences of a step, linearisation.hpp): collocation's step from a
// state 1e-5 state_scale away starts from the solution of the unperturbed step, and converges
// in fewer KINSOL iterations to the same step (to the solver's tolerance). Measured at N = 10,
// dt = 10 ms: 11 -> 2 iterations (Cosserat), 10 -> 6 (Kirchhoff); the two perturbed steps'
// states differ by 4e-15 and 4e-13 of the state's norm (1e-10, the solver's tolerance, accepted).
BOOST_AUTO_TEST_CASE(collocation_warm_start_takes_fewer_iterations) {
  for (const Case& k : {kCases[5], kCases[6]}) {
    BOOST_TEST_CONTEXT(k.model) {
      c::Plant plant = make(k);
      plant.set_input(input(0.3, 0.1, 0.0, 0.05));
      for (int i = 0; i < 3; ++i) BOOST_REQUIRE(plant.advance().ok);
      const c::PlantSnapshot start = plant.snapshot();
      BOOST_REQUIRE(plant.advance().ok);
      const c::PlantSnapshot after = plant.snapshot();
      Eigen::VectorXd dx(plant.state_size());
      for (int i = 0; i < dx.size(); ++i)
        dx[i] = 1e-5 * plant.state_scale()[i] * std::sin(1.0 + i);
      std::vector<int> iterations;
      std::vector<Eigen::VectorXd> ends;
      for (bool warm : {false, true}) {
        plant.restore(start);
        plant.add_state(std::span<const double>(dx.data(), dx.size()));
        if (warm) plant.warm_start_from(after);
        const auto status = plant.advance();
        BOOST_TEST_REQUIRE(status.ok, status.reason);
        iterations.push_back(status.iterations);
        ends.push_back(state(plant));
      }
      const double gap = (ends[1] - ends[0]).norm() / ends[0].norm();
      BOOST_TEST_MESSAGE(k.model << ": iterations " << iterations[0] << " cold, "
                                 << iterations[1] << " warm; relative difference " << gap);
      BOOST_TEST(iterations[1] < iterations[0]);
      BOOST_TEST(gap < 1e-10);
    }
  }
}
