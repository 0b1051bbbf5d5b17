// The linearisation of a control step (solvers/control/linearisation.hpp): directional
// derivatives agree with the columns of A and B, the implicit-function Jacobians with the
// finite-difference ones, the remainder of the linear model is second order, and the steady
// state of the linearised plant is the closed-form statics of a cable.
#define BOOST_TEST_MODULE control_linearisation
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/LU>

#include "control_support.hpp"
#include "rodlab/solvers/control/linearisation.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"

namespace c = rodlab::solvers::control;
using rodlab::testing::control::cable_robot;
using rodlab::testing::control::plant_options;

namespace {

// N = 6 keeps A small (60 x 60).
c::Plant make(const std::string& scheme, const std::string& model = "cosserat") {
  return c::Plant(cable_robot(model), plant_options(scheme, 6, 0.01));
}

/// The plant moved off rest: three control steps under some tensions.
void drive(c::Plant& plant) {
  Eigen::VectorXd u(4);
  u << 0.3, 0.1, 0.0, 0.05;
  plant.set_input(u);
  for (int i = 0; i < 3; ++i) BOOST_REQUIRE(plant.advance().ok);
}

Eigen::VectorXd state(const c::Plant& p) {
  Eigen::VectorXd x(p.state_size());
  p.read_state(std::span<double>(x.data(), x.size()));
  return x;
}

/// A plant's Jacobians of one control step: the scheme's own linearisation (the default
/// method), or whole-step central differences.
struct Jacobians {
  Eigen::MatrixXd A, B, C, D;
};
Jacobians jacobians(c::Plant& plant, bool differenced) {
  c::LinearisationOptions o;
  if (differenced) o.method = c::JacobianMethod::finite_difference;
  c::Linearisation lin(plant, o);
  Jacobians J;
  BOOST_REQUIRE(lin.jacobians(plant, J.A, J.B, J.C, J.D).ok);
  return J;
}

double rel(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) {
  return (X - Y).norm() / Y.norm();
}

}  // namespace

// One directional derivative against the same combination of A's and B's columns: both are
// central differences of the same step, so they agree to the differences' error: the step's own
// solver error over the difference step (tol 1e-10 / 1e-5 for shooting; measured 1e-6 to 5e-6 of
// the derivative's size, 3e-5 accepted). The plant is left where it was.
BOOST_AUTO_TEST_CASE(directional_derivative_matches_the_columns) {
  for (const std::string scheme :
       {"implicit-midpoint", "variational", "implicit-midpoint-collocation"}) {
    BOOST_TEST_CONTEXT(scheme) {
      c::Plant plant = make(scheme);
      drive(plant);
      const Eigen::VectorXd x0 = state(plant);
      c::Linearisation lin(plant);
      Eigen::MatrixXd A, B, C, D;
      BOOST_REQUIRE(lin.jacobians(plant, A, B, C, D).ok);
      BOOST_TEST((state(plant) - x0).norm() == 0.0);  // restored
      Eigen::VectorXd v = Eigen::VectorXd::Zero(plant.state_size());
      for (int i = 0; i < v.size(); ++i) v[i] = plant.state_scale()[i] * std::sin(1.0 + i);
      Eigen::VectorXd w(4);
      w << 0.2, -0.1, 0.3, 0.0;
      c::StepDerivative d;
      BOOST_REQUIRE(lin.directional(plant, v, w, d).ok);
      const Eigen::VectorXd model = A * v + B * w;
      BOOST_TEST((d.dx - model).norm() < 3e-5 * model.norm());
      BOOST_TEST((d.dtip - (C * v + D * w)).norm() < 3e-5 * d.dtip.norm());
      BOOST_TEST(d.dtip.norm() > 0.0);
    }
  }
}

// The scheme's own linearised step (implicit function theorem on the shooting residual with a
// tangent-linear march, Stepper::step_linearised) against whole-step central differences, every
// column: they agree to 2e-9..4e-7 of each matrix's norm (measured; the differences' error, the
// shooting tolerance over their step), 2e-6 accepted. With gravity the
// rotations enter the balance (the rho columns of the march), bdf-alpha runs past its start-up
// (its own history slope), Kirchhoff drops the linear strains. A rod sagging under gravity also
// has nonzero C.
BOOST_AUTO_TEST_CASE(implicit_function_jacobians_match_finite_differences) {
  for (const auto& [scheme, model, gravity] : std::vector<std::tuple<std::string, std::string, bool>>{
           {"implicit-midpoint", "cosserat", false}, {"implicit-midpoint", "cosserat", true},
           {"implicit-midpoint", "kirchhoff", true}, {"bdf-alpha", "cosserat", true}}) {
    BOOST_TEST_CONTEXT(scheme << " " << model << (gravity ? " gravity" : "")) {
      rodlab::scene::Scene scene = cable_robot(model);
      if (gravity) scene.loads.gravity = Eigen::Vector3d(-9.81, 0.0, 0.0);
      c::Plant plant(scene, plant_options(scheme, 6, 0.01));
      BOOST_REQUIRE(plant.has_step_linearisation());
      drive(plant);
      const Eigen::VectorXd x0 = state(plant);
      const Jacobians exact = jacobians(plant, false);
      BOOST_TEST((state(plant) - x0).norm() == 0.0);  // restored
      const Jacobians fd = jacobians(plant, true);
      BOOST_TEST_MESSAGE("relative differences A " << rel(exact.A, fd.A) << " B "
                         << rel(exact.B, fd.B) << " C " << rel(exact.C, fd.C) << " D "
                         << rel(exact.D, fd.D));
      BOOST_TEST(rel(exact.A, fd.A) < 2e-6);
      BOOST_TEST(rel(exact.B, fd.B) < 2e-6);
      BOOST_TEST(rel(exact.C, fd.C) < 2e-6);
      BOOST_TEST(rel(exact.D, fd.D) < 2e-6);
    }
  }
}

// Under multiple shooting (the staggered march cut into intervals, here forced inside the bound
// so that single shooting solves the same step) the linearised step restarts its tangent chain
// at each interval and closes the joins by the implicit function theorem. Reference: whole-step
// central differences (as above) and single shooting's own linearisation of the same step.
// Measured (2 and 5 intervals): A within 1.1e-9..2.0e-9 of the differences, B 4.0e-8; within
// 3.0e-8 (A) and 1.6e-8 (B) of single shooting's.
BOOST_AUTO_TEST_CASE(multiple_shooting_linearisation_matches) {
  for (const int intervals : {2, 5}) {
    BOOST_TEST_CONTEXT(intervals << " intervals") {
      rodlab::scene::Scene scene = cable_robot("cosserat");
      scene.loads.gravity = Eigen::Vector3d(-9.81, 0.0, 0.0);
      auto o = plant_options("implicit-midpoint", 6, 0.01);
      c::Plant single(scene, o);
      o.solver.shooting_intervals = intervals;
      c::Plant multiple(scene, o);
      BOOST_REQUIRE(multiple.has_step_linearisation());
      drive(single);
      drive(multiple);
      const Jacobians exact = jacobians(multiple, false), fd = jacobians(multiple, true);
      const Jacobians one = jacobians(single, false);
      BOOST_TEST_MESSAGE("against differences: A " << rel(exact.A, fd.A) << " B "
                         << rel(exact.B, fd.B) << "; against single shooting: A "
                         << rel(exact.A, one.A) << " B " << rel(exact.B, one.B));
      BOOST_TEST(rel(exact.A, fd.A) < 2e-6);
      BOOST_TEST(rel(exact.B, fd.B) < 2e-6);
      BOOST_TEST(rel(exact.A, one.A) < 1e-6);
      BOOST_TEST(rel(exact.B, one.B) < 1e-6);
    }
  }
}

// Below single shooting's lower step bound, where the plant refused implicit-midpoint until
// session 33, the steps are multiple shooting's and so is their linearisation. Reference:
// whole-step central differences. Measured at dt = 0.1 ms: A within 1.0e-8, B 1.2e-8.
BOOST_AUTO_TEST_CASE(linearisation_below_the_step_bound) {
  rodlab::scene::Scene scene = cable_robot("cosserat");
  scene.loads.gravity = Eigen::Vector3d(-9.81, 0.0, 0.0);
  const double dt = 1e-4;
  const auto P = rodlab::solvers::dynamics::DynamicProblem::from_scene(scene);
  BOOST_TEST_REQUIRE(rodlab::solvers::dynamics::shooting_intervals(
                         rodlab::solvers::dynamics::single_shooting_exponent(P, dt),
                         rodlab::solvers::dynamics::ShootingGrid::staggered, 1e-10, 5) > 1);
  c::Plant plant(scene, plant_options("implicit-midpoint", 6, dt));
  BOOST_REQUIRE(plant.has_step_linearisation());
  drive(plant);
  const Jacobians exact = jacobians(plant, false), fd = jacobians(plant, true);
  BOOST_TEST_MESSAGE("below the bound, against differences: A " << rel(exact.A, fd.A) << " B "
                                                                << rel(exact.B, fd.B));
  BOOST_TEST(rel(exact.A, fd.A) < 2e-6);
  BOOST_TEST(rel(exact.B, fd.B) < 2e-6);
}

// The linear model's remainder x+(x + e v, u + e w) - x+(x, u) - e (A v + B w) is O(e^2): halving
// e divides it by 4 (3 to 5 accepted), which checks A and B are the step's derivative and not
// merely a fit.
BOOST_AUTO_TEST_CASE(linear_model_remainder_is_second_order) {
  c::Plant plant = make("implicit-midpoint");
  drive(plant);
  c::Linearisation lin(plant);
  Eigen::MatrixXd A, B, C, D;
  BOOST_REQUIRE(lin.jacobians(plant, A, B, C, D).ok);
  const c::PlantSnapshot start = plant.snapshot();
  const Eigen::VectorXd u0 = plant.input();
  BOOST_REQUIRE(plant.advance().ok);
  const Eigen::VectorXd x1 = state(plant);
  Eigen::VectorXd v(plant.state_size());
  for (int i = 0; i < v.size(); ++i) v[i] = plant.state_scale()[i] * std::cos(2.0 + i);
  Eigen::VectorXd w(4);
  w << 0.5, 0.2, 0.1, 0.3;
  std::vector<double> remainder;
  for (double e : {0.02, 0.01}) {
    plant.restore(start);
    const Eigen::VectorXd dx = e * v;
    plant.add_state(std::span<const double>(dx.data(), dx.size()));
    plant.set_input(u0 + e * w);
    BOOST_REQUIRE(plant.advance().ok);
    remainder.push_back((state(plant) - x1 - e * (A * v + B * w)).norm());
  }
  BOOST_TEST_MESSAGE("remainders " << remainder[0] << " " << remainder[1]);
  BOOST_TEST(remainder[0] / remainder[1] > 3.0);
  BOOST_TEST(remainder[0] / remainder[1] < 5.0);
}

// At rest, straight, the steady state of the linearised plant under a tension dF on the +x cable,
// x_ss = (I - A)^-1 B dF, has the tip d p = C x_ss + D dF of the linear statics (closed form): a
// uniform curvature kappa = F r / (E I) and axial strain -F / (E A), so dp_x/dF = r L^2 / (2 E I)
// and dp_z/dF = -L / (E A) (Kirchhoff: 0). Every grid represents a uniform strain exactly, so
// only the differences' error remains (1e-5).
BOOST_AUTO_TEST_CASE(steady_state_of_the_linearisation_is_the_cable_statics) {
  const double L = 0.1, r = 0.004, E = 1e6, d = 0.01;
  const double I = std::numbers::pi * std::pow(d, 4) / 64.0, A_s = std::numbers::pi * d * d / 4.0;
  for (const auto& [scheme, model] : std::vector<std::pair<std::string, std::string>>{
           {"implicit-midpoint", "cosserat"}, {"variational", "cosserat"},
           {"variational", "kirchhoff"}, {"bdf-alpha", "cosserat"},
           {"implicit-midpoint-collocation", "cosserat"},
           {"implicit-midpoint-collocation", "kirchhoff"}}) {
    BOOST_TEST_CONTEXT(scheme << " " << model) {
      c::Plant plant = make(scheme, model);
      c::Linearisation lin(plant);
      Eigen::MatrixXd A, B, C, D;
      BOOST_REQUIRE(lin.jacobians(plant, A, B, C, D).ok);
      const int n = plant.state_size();
      const Eigen::VectorXd x_ss =
          (Eigen::MatrixXd::Identity(n, n) - A).partialPivLu().solve(B.col(0));
      const Eigen::Vector3d dp = C * x_ss + D.col(0);
      const double dpx = r * L * L / (2.0 * E * I);
      const double dpz = model == "kirchhoff" ? 0.0 : -L / (E * A_s);
      BOOST_TEST_MESSAGE("dp/dF = " << dp.transpose() << " closed form " << dpx << " 0 " << dpz
                                    << " (dp_x relative error " << (dp.x() - dpx) / dpx << ")");
      BOOST_TEST(std::abs(dp.x() - dpx) < 1e-5 * dpx);
      BOOST_TEST(std::abs(dp.y()) < 1e-8 * dpx);
      BOOST_TEST(std::abs(dp.z() - dpz) < 1e-5 * dpx);
    }
  }
}
