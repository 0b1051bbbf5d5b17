#define BOOST_TEST_MODULE dynamics_semi_discrete_packed
#include <boost/test/unit_test.hpp>

// The semi-discrete rod's f with the plain rod's segments in pairs (SemiDiscreteRod::
// segment_pair, packed_pair.hpp's two-lane kernels; docs/dynamics.md "The packed segments of
// the semi-discrete rod") against the same f segment by segment (set_packed(false)), the
// reference: the same formulas in another rounding order.
//   (1) rhs at bent, moving states (segment angles ~0.013 and ~0.07 rad, unnormalised and
//       sign-flipped quaternions), N = 12 and 13 (an odd segment count leaves the last one
//       alone), with and without gravity, drag and a tip wrench: each node's position,
//       quaternion, angular and linear rates and the ledger rows within 1e-12 of their norm
//       (measured 2.2e-13: the accelerations are differences of stresses over ds, so f's own
//       rounding level is ~2 eps (omega_max / omega_1)^2, ~3e-11 here, docs/dynamics.md);
//   (2) segments above the small-angle kernels' bound (a rest arc of 0.3 rad per segment):
//       the pairs fall back to the scalar segments, so f is equal bit for bit.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dynamics_support.hpp"
#include "semi_discrete_states.hpp"
#include "rodlab/solvers/dynamics/semi_discrete/semi_discrete_rod.hpp"

namespace {

using rodlab::solvers::dynamics::DynamicProblem;
using rodlab::solvers::dynamics::SemiDiscreteRod;

/// max over rows of |f_packed - f_scalar| / |f_scalar| of the row's block (positions,
/// quaternions, angular and linear accelerations of a node; the ledger rows apart).
double worst_relative_difference(const SemiDiscreteRod::Vector& a,
                                 const SemiDiscreteRod::Vector& b, int node_size) {
  double worst = 0.0;
  const int blocks[] = {3, 4, 3, 3};
  for (int node = 0; node * SemiDiscreteRod::kBlock < node_size; ++node) {
    int start = node * SemiDiscreteRod::kBlock;
    for (int size : blocks) {
      const double norm = b.segment(start, size).norm();
      if (norm > 0.0)
        worst = std::max(worst, (a.segment(start, size) - b.segment(start, size)).norm() / norm);
      start += size;
    }
  }
  for (int i = node_size; i < a.size(); ++i)
    worst = std::max(worst, std::abs(a[i] - b[i]) / std::max(std::abs(b[i]), 1e-300));
  return worst;
}

}  // namespace

BOOST_AUTO_TEST_CASE(packed_f_equals_the_scalar_f_to_rounding) {
  using rodlab::testing::dynamics::rod_scene;
  const rodlab::scene::Scene scenes[] = {
      rod_scene("{}", "{}", 30.0),
      rod_scene("{gravity: [-9.81, 0, 0], drag: {fluid_density: 1000, laminar: [1e-8, 1e-8, "
                "1e-8, 1e-3, 1e-3, 1e-3], turbulent: [0, 0, 0, 0.01, 0.01, 0.01]}}",
                "{wrench: {force: [0.02, 0.01, 0], moment: [0, 0.001, 0], frame: body}}", 30.0)};
  double worst = 0.0;
  int cases = 0;
  for (const auto& s : scenes)
    for (int nodes : {12, 13}) {
      const auto P = DynamicProblem::from_scene(s);
      SemiDiscreteRod rod(P, nodes, "test", false, false);
      for (double curvature : {1.0, 5.0})
        for (unsigned seed = 1; seed <= 3; ++seed) {
          const auto y = rodlab::testing::dynamics::bent_moving_state(rod, curvature, seed);
          SemiDiscreteRod::Vector f_packed(rod.size()), f_scalar(rod.size());
          rod.set_packed(true);
          rod.rhs(0.01, y, f_packed);
          rod.set_packed(false);
          rod.rhs(0.01, y, f_scalar);
          worst = std::max(worst, worst_relative_difference(f_packed, f_scalar, rod.node_size()));
          ++cases;
        }
    }
  BOOST_TEST_MESSAGE("packed f against the scalar f over " << cases << " states: worst "
                                                           << worst << " relative");
  BOOST_TEST(worst <= 1e-12);
}

BOOST_AUTO_TEST_CASE(segments_above_the_small_angle_bound_fall_back_bit_for_bit) {
  // a rest arc of 0.3 rad per segment at N = 12 (3 rad over the rod): every segment's log is
  // above the packed kernels' bound
  const auto s = rodlab::io::load_scene_from_string(
      "schema: rodlab.scene/1\nname: arc\nrod:\n  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 30}\n"
      "  rest_strain: {arc: {angle: 3.3}}\ntip:\n  free: {}\nloads: {gravity: [-9.81, 0, 0]}\n",
      "arc.yaml");
  const auto P = DynamicProblem::from_scene(s);
  SemiDiscreteRod rod(P, 12, "test", false, false);
  using rodlab::lie::SE3;
  using rodlab::lie::Vector6;
  std::vector<SE3> g(rod.nodes(), P.base());
  std::vector<Vector6> eta(rod.nodes(), Vector6::Zero());
  Vector6 xi;
  xi << 0.0, 3.3 / 0.1, 0.0, 0.0, 0.0, 1.0;
  for (int j = 1; j < rod.nodes(); ++j) {
    g[j] = g[j - 1] * SE3::exp(rod.ds() * xi);
    eta[j] << 0.1 * j, -0.2, 0.05, 0.001, 0.002 * j, -0.001;
  }
  SemiDiscreteRod::Vector y = SemiDiscreteRod::Vector::Zero(rod.size());
  rod.pack_nodes(g, eta, y);
  SemiDiscreteRod::Vector f_packed(rod.size()), f_scalar(rod.size());
  rod.set_packed(true);
  rod.rhs(0.01, y, f_packed);
  rod.set_packed(false);
  rod.rhs(0.01, y, f_scalar);
  BOOST_TEST((f_packed - f_scalar).cwiseAbs().maxCoeff() == 0.0);
}
