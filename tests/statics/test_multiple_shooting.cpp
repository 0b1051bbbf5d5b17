#define BOOST_TEST_MODULE statics_multiple_shooting
#include <boost/test/unit_test.hpp>

#include <string>
#include <vector>

#include "actuator_support.hpp"
#include "rodlab/solvers/statics/multiple_shooting.hpp"
#include "rodlab/solvers/statics/result_builder.hpp"
#include "rodlab/solvers/statics/shooting.hpp"
#include "statics_support.hpp"

// Multiple shooting, the shooting schemes' corrector for hard problems (multiple_shooting.hpp):
// 1. its intervals march the single march's steps: chained from the single march's nodes they
//    reproduce it bit for bit, across a cable entering at an interval start and breakpoints
//    inside intervals (reference: shoot());
// 2. its interval-by-interval Jacobian is the Jacobian of its residual (reference: forward
//    differences of the whole residual);
// 3. it solves the scheme's own discrete equations: on an actuated rod with two extra unknowns
//    its nodes equal single shooting's to the Newton tolerance (reference: single shooting);
// 4. it solves the constant-twist load with large shear from the reference configuration,
//    where single shooting's Newton finds no descent (tests/statics/test_statics_robustness.cpp;
//    reference: the closed form g(s) = exp(s xi), exact for every RKMK scheme);
// 5. a soft cantilever at a tolerance near the rounding level: its walk is repeated to 1e-9 and
//    polished, and a stop on the rows' rounding floor counts as converged (reference: kinsol).

namespace {

using namespace rodlab;
using namespace rodlab::solvers;
using namespace rodlab::solvers::statics;
using rodlab::testing::actuators::kL;
using rodlab::testing::actuators::straight;
using rodlab::testing::statics::expm_reference;
using rodlab::testing::statics::pose_error;
using rodlab::testing::statics::PoseError;

const RkmkMethod kMethods[] = {RkmkMethod::euler_explicit, RkmkMethod::euler_implicit,
                               RkmkMethod::midpoint_explicit, RkmkMethod::midpoint_implicit,
                               RkmkMethod::rk4};
constexpr int kNodes = 21;

/// The chamber and the muscle of actuator_support.hpp (two extra unknowns, breakpoints at
/// 0.0287 and 0.0613, inside intervals) and a 0.4 N cable entering at node 10, an interval start
/// of 16 intervals on 21 nodes.
StaticProblem actuated_problem() {
  StaticProblem P(rodlab::testing::actuators::table21(), SE3::identity());
  rodlab::testing::actuators::add_chamber_and_muscle(P);
  auto cable = straight(ActuatorKind::cable, -0.003, 0.002, 10 * (kL / (kNodes - 1)), kL);
  cable.input = 0.4;
  P.add_actuator(cable);
  return P;
}

}  // namespace

BOOST_AUTO_TEST_CASE(spans_chained_reproduce_the_single_march) {
  StaticProblem P = actuated_problem();
  BOOST_TEST_REQUIRE(P.has_entry(10 * (kL / (kNodes - 1))));
  BOOST_TEST_REQUIRE(P.tracks_lengths());
  P.set_extra_unknowns(std::vector<double>{0.3, -0.2});  // forces off their rest values
  const Vector6 Lambda0 = (Vector6() << 2e-3, -1e-3, 5e-4, 0.05, -0.02, 0.3).finished();
  for (const RkmkMethod method : kMethods) {
    std::vector<Node> single(kNodes), spans(kNodes);
    const ShootResult whole = shoot(P, method, kNodes, Lambda0, single);
    BOOST_TEST_REQUIRE(whole.ok);
    std::array<double, StaticProblem::kMaxActuators> lengths{};
    for (const auto& [first, last] : {std::pair{0, 3}, std::pair{3, 10}, std::pair{10, 20}}) {
      const auto path = std::span<Node>(spans).subspan(first, last - first + 1);
      const ShootResult part = shoot_span(P, method, kNodes, first, last, single[first], path);
      BOOST_TEST_REQUIRE(part.ok);
      for (std::size_t a = 0; a < lengths.size(); ++a) lengths[a] += part.lengths[a];
    }
    for (int i = 0; i < kNodes; ++i) {
      BOOST_TEST((spans[i].g.matrix() == single[i].g.matrix()), "node " << i);
      BOOST_TEST((spans[i].Lambda == single[i].Lambda), "node " << i);
    }
    for (int a = 0; a < 3; ++a)  // summed in another order: rounding
      BOOST_TEST(lengths[a] == whole.lengths[a], boost::test_tools::tolerance(1e-14));
  }
}

BOOST_AUTO_TEST_CASE(interval_jacobian_is_the_residuals) {
  for (const RkmkMethod method : kMethods) {
    StaticProblem P = actuated_problem();
    const MultipleShooting ms(P, method, kNodes);
    // A state off the solution: the reference configuration, moved in every unknown.
    Eigen::VectorXd x = ms.reference_guess();
    for (int j = 0; j < x.size(); ++j) x[j] += 0.01 * std::sin(1.0 + j);
    Eigen::VectorXd r;
    BOOST_TEST_REQUIRE(ms.residual(x, r));
    Eigen::MatrixXd J, reference(x.size(), x.size());
    BOOST_TEST_REQUIRE(ms.jacobian(x, r, J, 1e-7));
    for (int j = 0; j < x.size(); ++j) {  // central differences of the whole residual
      const double h = 1e-6;
      Eigen::VectorXd xp = x, xm = x, rp, rm;
      xp[j] += h;
      xm[j] -= h;
      BOOST_TEST_REQUIRE(ms.residual(xp, rp));
      BOOST_TEST_REQUIRE(ms.residual(xm, rm));
      reference.col(j) = (rp - rm) / (2 * h);
    }
    const double e =
        (J - reference).lpNorm<Eigen::Infinity>() / reference.lpNorm<Eigen::Infinity>();
    BOOST_TEST_MESSAGE("method " << static_cast<int>(method) << ": " << x.size()
                                 << " unknowns, Jacobian error " << e);
    BOOST_TEST(e <= 1e-5);
  }
}

BOOST_AUTO_TEST_CASE(solves_the_schemes_own_equations) {
  for (const RkmkMethod method : kMethods) {
    StaticProblem P = actuated_problem();
    ShootingOptions single;
    single.nodes = kNodes;
    single.tol = 1e-12;
    const auto reference = solve_shooting(P, method, single);
    BOOST_TEST_REQUIRE(reference.converged, reference.reason);
    NewtonOptions newton;
    newton.tol = 1e-12;
    const MultipleShooting ms(P, method, kNodes);
    const NewtonResult solved = ms.solve(ms.reference_guess(), newton);
    BOOST_TEST_REQUIRE(solved.converged, solved.reason);
    BOOST_TEST(solved.iterations <= 20);
    std::vector<Node> nodes;
    BOOST_TEST_REQUIRE(ms.path(solved.x, nodes));
    // The result shooting would write from these nodes (P holds multiple shooting's unknowns).
    std::vector<double> s(kNodes);
    std::vector<SE3> g(kNodes);
    std::vector<Vector6> Lambda(kNodes);
    for (int i = 0; i < kNodes; ++i) {
      s[i] = kL * i / (kNodes - 1);
      g[i] = nodes[i].g;
      Lambda[i] = nodes[i].Lambda;
    }
    result::StaticResult found;
    fill_static_result(P, s, g, Lambda, found);
    double pose = 0.0, twist = 0.0;
    for (int i = 0; i < kNodes; ++i) {
      const PoseError d = pose_error(found.centerline[i].pose, reference.centerline[i].pose, kL);
      pose = std::max(pose, d.max());
      twist = std::max(twist, kL * (found.centerline[i].twist - reference.centerline[i].twist)
                                       .lpNorm<Eigen::Infinity>());
    }
    const double wrench = (found.base_wrench - reference.base_wrench)
                              .cwiseQuotient(P.wrench_scale())
                              .lpNorm<Eigen::Infinity>();
    BOOST_TEST_MESSAGE("method " << static_cast<int>(method) << ": " << solved.iterations
                                 << " iterations, node pose " << pose << ", twist L " << twist
                                 << ", base wrench " << wrench);
    BOOST_TEST(pose <= 1e-10);
    BOOST_TEST(twist <= 1e-10);
    BOOST_TEST(wrench <= 1e-10);
  }
}

BOOST_AUTO_TEST_CASE(solves_where_single_shooting_cannot) {
  const Vector6 xi = (Vector6() << 3.0, -2.0, 5.0, 0.04, -0.03, 1.02).finished();
  StaticProblem P = rodlab::testing::statics::constant_twist_problem(
      rod::ModelKind::cosserat, xi, rodlab::testing::statics::constant_twist_wrench(xi));
  for (const int nodes : {5, 11}) {
    // Single shooting's Newton from the rigid guess finds no descent here (the march blows up
    // for nearby base wrenches), and its continuation stalls (test_statics_robustness.cpp).
    const NewtonResult direct = [&] {
      const Residual F = [&](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
        const auto end = shoot(P, RkmkMethod::euler_explicit, nodes,
                               x.head<6>().cwiseProduct(P.wrench_scale()));
        r = P.tip_residual(end.tip.g, end.tip.Lambda);
        return end.ok && r.allFinite();
      };
      NewtonOptions o;
      o.tol = 1e-12;
      return solve_newton(F, rigid_base_wrench(P, nodes - 1).cwiseQuotient(P.wrench_scale()), o);
    }();
    BOOST_TEST(!direct.converged, "single shooting now converges at N = " << nodes);
    NewtonOptions newton;
    newton.tol = 1e-12;
    const MultipleShooting ms(P, RkmkMethod::euler_explicit, nodes);
    const NewtonResult solved = ms.solve(ms.reference_guess(), newton);
    BOOST_TEST_REQUIRE(solved.converged, solved.reason);
    std::vector<Node> path;
    BOOST_TEST_REQUIRE(ms.path(solved.x, path));
    double e = 0.0;
    for (int i = 0; i < nodes; ++i) {
      const double s = kL * i / (nodes - 1);
      e = std::max(e, pose_error(path[i].g, expm_reference(s * xi)).max());
    }
    BOOST_TEST_MESSAGE("N = " << nodes << ": " << solved.iterations << " iterations, node error "
                              << e);
    BOOST_TEST(e <= 1e-9);
    // The whole shooting scheme: direct, continuation, then multiple shooting.
    const auto r = rodlab::testing::statics::solve(P, "rkmk-euler-explicit", nodes);
    BOOST_TEST(r.converged, r.reason);
  }
}

BOOST_AUTO_TEST_CASE(soft_cantilever_at_a_tight_tolerance) {
  // E = 1000 Pa (G = 0.33 E, the Table 2.1 geometry) under gravity: rho g A L^3 / E I = 1570,
  // N = 100, tol 1e-12. The direct solve's march is not finite, and the walk held to 1e-12
  // stalled at load factor 0.86 (its correctors' line searches cut steps in the rounding noise,
  // which the walk takes for leaving the branch); the polish at the full load then stops on the
  // rounding floor, 1.6e-12 with |x| ~ 1.6e3 (shooting.cpp, multiple_shooting.cpp). Reference:
  // kinsol at N = 100, fourth order like rk4: the tips differ by the two discretisations, measured
  // 9.0e-8 m.
  StaticProblem P(rod::RodModel(kL, rod::Circle{0.01}, rod::Material{1000.0, 330.0, 1000.0, 0.0},
                                rod::ModelKind::cosserat),
                  SE3::identity());
  P.set_gravity(loads::Gravity(P.model(), Vector3(-9.81, 0.0, 0.0)));
  const auto r = rodlab::testing::statics::solve(P, "rkmk-rk4", 100, 1e-12);
  const auto reference = rodlab::testing::statics::solve(P, "kinsol", 100, 1e-12);
  BOOST_TEST_REQUIRE(r.converged, r.reason);
  BOOST_TEST_REQUIRE(reference.converged, reference.reason);
  const double d = (r.centerline.back().pose.translation() -
                    reference.centerline.back().pose.translation()).norm();
  BOOST_TEST_MESSAGE("soft cantilever, rkmk-rk4 N = 100: residual " << r.residual_norm
                     << ", |tip - kinsol| " << d << " m, " << r.iterations << " iterations");
  BOOST_TEST(r.residual_norm <= 1e-10);
  BOOST_TEST(d <= 1e-6);
}
