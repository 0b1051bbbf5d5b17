#define BOOST_TEST_MODULE dynamics_analytic_jacobian
#include <boost/test/unit_test.hpp>

// The analytic Newton matrix of the semi-discrete rod (semi_discrete_jacobian.cpp;
// docs/dynamics.md "The analytic Jacobian of the semi-discrete rod"; issue #17 item 3),
// J = df/dy (a = 0, b = -1), against central differences of rhs() (step 1e-6 of each
// component's scale; stable to the digits printed under steps 1e-4 .. 1e-7), at bent, moving
// states with unnormalised and sign-flipped quaternions, node rows alone (collocation) and with
// the ledger rows (ida):
//   (1) the whole matrix, per column, |J_c - R_c| / |R_c|: at segment angles of ~0.013 rad
//       (curvature 1 rad/m) the analytic matrix is exact but for the truncated derivative of
//       dexp^-1: measured 5e-7 .. 4e-6 (the finite-difference matrix it replaces: 1e-6 .. 4e-6);
//       tolerance 3e-5. At ~0.07 rad (5 rad/m) the truncation shows: measured 1.2e-5 .. 1.8e-5;
//       tolerance 1e-3, still a Newton matrix;
//   (2) every load alone: the change of J when the load is added (the rod's part cancels)
//       against the change of the reference (step 1e-4), node rows and ledger rows apart, max
//       entry error over max entry: measured 5e-9 .. 1.4e-6, tolerance 1e-4. A missing or wrong
//       load term, which (1) cannot see under the rod's stiffness, is O(1) here.
// The corrected grid (corrected_grid.hpp) in both: the tip's full inertia and its weight at the
// half cell's centre of mass (measured 4.3e-7 .. 6.3e-7 whole, 4.1e-7 .. 7.7e-7 its gravity
// part; the weight left at the node instead: 2.6e-4 and 242).
// Each of nine deliberate mistakes (one load's derivative dropped, DT's second term dropped, the
// dissipation's factor 2 halved, the actuators' dA/dxi or their power's term dropped) fails.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "dynamics_support.hpp"
#include "semi_discrete_states.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"

namespace {

using namespace rodlab;
using namespace rodlab::testing::dynamics;
using solvers::dynamics::DynamicProblem;
using solvers::dynamics::SemiDiscreteRod;
using lie::SE3;
using lie::Vector6;
using Method = SemiDiscreteRod::JacobianMethod;
using Matrix = Eigen::MatrixXd;

constexpr int kNodes = 12;
constexpr double kTime = 0.03;  // inside every ramp below

/// The Table 2.1 rod (viscosity 30 Pa s) with YAML `tip`, `loads` and `actuators` sections.
scene::Scene rod_with(const std::string& tip, const std::string& loads,
                      const std::string& actuators = "") {
  return io::load_scene_from_string(
      "schema: rodlab.scene/1\nname: analytic-jacobian\nrod:\n  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 30}\ntip:\n" + tip +
          "\nloads:\n" + loads + "\n" + (actuators.empty() ? "" : "actuators:\n" + actuators),
      "analytic-jacobian.yaml");
}

const std::string kFreeTip = "  free: {}";
const std::string kNoLoads = "  {}";
const std::string kGravity = "  gravity: [-9.81, 0, 0]";

/// Every load the analytic path covers, at once.
scene::Scene covered_loads() {
  return rod_with(R"(  free:
    wrench:
      force: {ramp: [[0, [0, 0, 0]], [0.05, [0.02, 0.01, 0]]]}
      moment: {ramp: [[0, [0, 0, 0]], [0.05, [0, 0.001, 0]]]}
      frame: body)",
                  R"(  gravity: [-9.81, 0, 0]
  drag: {fluid_density: 1000, laminar: [1e-8, 1e-8, 1e-8, 1e-3, 1e-3, 1e-3],
         turbulent: [0, 0, 0, 0.01, 0.01, 0.01]}
  distributed: {force: {ramp: [[0, [0, 0, 0]], [0.05, [0, 0.5, 0]]]}, moment: [0, 0, 0.001],
                frame: world})",
                  R"(  - cable:
      {offset: [0.003, 0], tension: {ramp: [[0, 0], [0.05, 0.3]]}, span: [0, 0.1]}
  - fluidic: {offset: [0, 0.003, 0], chamber_radius: 0.001, pressure: 2.0e4, span: [0.02, 0.08]})");
}

/// covered_loads() without its actuators (the corrected grid does not take them).
scene::Scene covered_loads_without_actuators() {
  scene::Scene s = covered_loads();
  s.actuators.clear();
  return s;
}


/// df/dy by central differences of rhs() with steps `step` times each component's scale, node
/// rows and, with `ledger`, the ledger rows.
Matrix central_differences(const SemiDiscreteRod& rod, const SemiDiscreteRod::Vector& y,
                           bool ledger, double step = 1e-6) {
  const int n = ledger ? rod.size() : rod.node_size();
  Matrix J(n, n);
  SemiDiscreteRod::Vector yp = y.head(n), ym = y.head(n), fp(n), fm(n);
  for (int c = 0; c < n; ++c) {
    const double h = step * rod.scale()[c];
    yp[c] = y[c] + h;
    ym[c] = y[c] - h;
    rod.rhs(kTime, yp, fp);
    rod.rhs(kTime, ym, fm);
    J.col(c) = (fp - fm) / (yp[c] - ym[c]);
    yp[c] = ym[c] = y[c];
  }
  return J;
}

/// J = df/dy by `method`, dense.
Matrix newton_matrix(const SemiDiscreteRod& rod, const SemiDiscreteRod::Vector& y, bool ledger,
                     Method method) {
  auto J = rod.pattern(ledger);
  rod.newton_matrix(kTime, ledger ? y : SemiDiscreteRod::Vector(y.head(rod.node_size())), 0.0,
                    -1.0, J, method);
  return Matrix(J);
}

/// max over columns of |J_c - R_c| / |R_c| (R's zero columns, D and W: J's must be zero too).
double worst_column_error(const Matrix& J, const Matrix& R) {
  double worst = 0.0;
  for (int c = 0; c < R.cols(); ++c) {
    const double norm = R.col(c).norm();
    worst = std::max(worst, norm == 0.0 ? J.col(c).norm() : (J.col(c) - R.col(c)).norm() / norm);
  }
  return worst;
}

/// The problem of scene s on the staggered grid, or on the corrected grid (its model with the
/// residual bending flexibility; the rod then takes the tip's half cell as a rigid body).
DynamicProblem problem_of(const scene::Scene& s, bool corrected) {
  const auto P = DynamicProblem::from_scene(s);
  return corrected ? solvers::dynamics::corrected_grid_problem(P, kNodes) : P;
}

/// (1): the whole matrix of scene s at `curvature`, three states, with and without the ledger.
void check_whole_matrix(const scene::Scene& s, const std::string& what, double curvature,
                        double tol, bool corrected = false) {
  const auto P = problem_of(s, corrected);
  const SemiDiscreteRod rod(P, kNodes, "test", false, corrected);
  BOOST_REQUIRE(rod.analytic_jacobian());
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const auto y = bent_moving_state(rod, curvature, seed);
    for (bool ledger : {false, true}) {
      const Matrix R = central_differences(rod, y, ledger);
      const double e = worst_column_error(newton_matrix(rod, y, ledger, Method::automatic), R);
      const double e_fd =
          worst_column_error(newton_matrix(rod, y, ledger, Method::finite_differences), R);
      BOOST_TEST_MESSAGE(what << ", " << curvature << " rad/m, seed " << seed
                              << (ledger ? ", ledger" : "") << ": worst column error " << e
                              << " (finite differences " << e_fd << ")");
      BOOST_TEST(e < tol);
    }
  }
}

/// The largest entry error of dJ against dR over the largest entry of dR (0 when both vanish).
double relative_entry_error(const Matrix& dJ, const Matrix& dR) {
  const double scale = dR.cwiseAbs().maxCoeff(), error = (dJ - dR).cwiseAbs().maxCoeff();
  return scale > 0.0 ? error / scale : error;
}

/// (2): the change of J when the scene `with` adds one load to `without`, node rows and ledger
/// rows apart (each relative to its own largest entry: the ledger's are far smaller). A
/// body-frame load (`pose_free`) does not depend on the pose: its only terms are its power's,
/// and the node rows' reference there is the rounding of the rod's stiff part, so only the
/// ledger rows are compared.
void check_load(const scene::Scene& without, const scene::Scene& with, const std::string& what,
                bool pose_free = false, bool corrected = false) {
  const auto P0 = problem_of(without, corrected), P1 = problem_of(with, corrected);
  const SemiDiscreteRod rod0(P0, kNodes, "test", false, corrected),
      rod1(P1, kNodes, "test", false, corrected);
  BOOST_REQUIRE(rod1.analytic_jacobian());
  const int nodes = rod1.node_size();
  for (unsigned seed = 1; seed <= 2; ++seed) {
    const auto y = bent_moving_state(rod1, 2.0, seed);
    // The rod's part of the differences cancels to rounding, so the step can be large.
    const Matrix dR =
        central_differences(rod1, y, true, 1e-4) - central_differences(rod0, y, true, 1e-4);
    const Matrix dJ = newton_matrix(rod1, y, true, Method::automatic) -
                      newton_matrix(rod0, y, true, Method::automatic);
    const double node_rows = relative_entry_error(dJ.topRows(nodes), dR.topRows(nodes));
    const double ledger_rows = relative_entry_error(dJ.bottomRows(2), dR.bottomRows(2));
    BOOST_TEST_MESSAGE(what << ", seed " << seed << ": the load's part of J, relative error "
                            << (pose_free ? "(not compared) " : "") << node_rows
                            << " in the node rows (largest entry "
                            << dR.topRows(nodes).cwiseAbs().maxCoeff() << "), " << ledger_rows
                            << " in the ledger rows (largest entry "
                            << dR.bottomRows(2).cwiseAbs().maxCoeff() << ")");
    if (!pose_free) BOOST_TEST(node_rows < 1e-4);
    BOOST_TEST(ledger_rows < 1e-4);
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(whole_matrix_at_small_segment_angles) {
  check_whole_matrix(rod_with(kFreeTip, kGravity), "viscous cantilever", 1.0, 3e-5);
  check_whole_matrix(covered_loads(), "every covered load", 1.0, 3e-5);
  check_whole_matrix(rod_with("  clamped: {position: [0.005, 0, 0.099]}", kGravity),
                     "clamped tip", 1.0, 3e-5);
  check_whole_matrix(covered_loads_without_actuators(), "the corrected grid, every load", 1.0,
                     3e-5, true);
}

BOOST_AUTO_TEST_CASE(whole_matrix_at_large_segment_angles) {
  check_whole_matrix(rod_with(kFreeTip, kGravity), "viscous cantilever", 5.0, 1e-3);
  check_whole_matrix(covered_loads(), "every covered load", 5.0, 1e-3);
}

BOOST_AUTO_TEST_CASE(every_load_alone) {
  const auto bare = rod_with(kFreeTip, kNoLoads);
  check_load(bare, rod_with(kFreeTip, kGravity), "gravity");
  // the corrected grid's tip: its full inertia, its weight at the half cell's centre of mass
  check_load(bare, rod_with(kFreeTip, kGravity), "gravity, corrected grid", false, true);
  check_load(bare, rod_with(kFreeTip, "  gravity: [0, 0, -9.81]\n  buoyancy: {fluid_density: 800}"),
             "gravity and buoyancy");
  check_load(bare,
             rod_with(kFreeTip,
                      "  drag: {fluid_density: 1000, laminar: [1e-8, 2e-8, 3e-8, 1e-3, 2e-3, 3e-3],"
                      " turbulent: [0, 0, 0, 0.01, 0.02, 0.005]}"),
             "drag");
  check_load(bare,
             rod_with(kFreeTip,
                      "  distributed: {force: [0, 0.5, 0.2], moment: [0.001, 0, 0], frame: world}"),
             "distributed, world");
  check_load(bare,
             rod_with(kFreeTip,
                      "  distributed: {force: [0, 0.5, 0.2], moment: [0.001, 0, 0], frame: body}"),
             "distributed, body", true);
  for (const std::string frame : {"world", "body"})
    check_load(bare,
               rod_with("  free:\n    wrench: {force: [0.02, 0.01, 0.005], moment: [0, 0.001, "
                        "0.0005], frame: " + frame + "}",
                        kNoLoads),
               "tip wrench, " + frame, frame == "body");
  check_load(bare,
             rod_with(kFreeTip, kNoLoads,
                      "  - cable: {offset: [0.003, 0.001], tension: 0.3, span: [0, 0.1]}"),
             "cable");
  check_load(bare,
             rod_with(kFreeTip, kNoLoads,
                      "  - fluidic: {offset: [0, 0.003, 0], chamber_radius: 0.001, pressure: "
                      "2.0e4, span: [0.02, 0.08]}"),
             "chamber");
}

BOOST_AUTO_TEST_CASE(scenes_outside_the_derivation_keep_finite_differences) {
  // Muscles and cables pulled from outside (entry loads) are differenced.
  const auto muscles = DynamicProblem::from_scene(
      io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/muscle-dynamics.yaml"));
  BOOST_TEST(!SemiDiscreteRod(muscles, kNodes, "test").analytic_jacobian());
  const auto entry = DynamicProblem::from_scene(rod_with(
      kFreeTip, kNoLoads, "  - cable: {offset: [0.003, 0], tension: 0.3, span: [0.03, 0.1]}"));
  BOOST_TEST(!SemiDiscreteRod(entry, kNodes, "test").analytic_jacobian());
}
