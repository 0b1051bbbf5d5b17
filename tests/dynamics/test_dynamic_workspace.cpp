#define BOOST_TEST_MODULE dynamics_dynamic_workspace
#include <boost/test/unit_test.hpp>

#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/dynamics/dynamic_workspace.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/statics/workspace.hpp"

// The dynamic workspace (thesis 3.4.1, Fig. 3.8): holding random cable tensions in turn, the
// rod overshoots its equilibria and reaches beyond the static workspace. scenes/cable-steps.yaml
// (four cables at 4 mm, tensions in [0, 0.5] N, alpha = 300 Pa s). The same seed draws the same
// input vectors for both (statics: one per sample; dynamics: one per hold), so the dynamic run
// visits the static samples' inputs and must bend further than any of their equilibria:
// measured omega_bound (see the message) for the static and the dynamic workspace.

using namespace rodlab;

BOOST_AUTO_TEST_CASE(the_dynamic_workspace_reaches_beyond_the_static_one) {
  const auto scene = io::load_scene(std::string(RODLAB_SOURCE_DIR) + "/scenes/cable-steps.yaml");
  constexpr int kSamples = 8;
  solvers::statics::StaticSolveOptions so;
  so.scheme = "rkmk-rk4";
  so.nodes = 30;
  const auto stat = solvers::statics::sample_workspace(scene, so, kSamples);
  BOOST_REQUIRE(stat.failed == 0);

  solvers::dynamics::DynamicWorkspaceOptions dw;
  dw.solve.scheme = "variational";
  dw.solve.nodes = 10;
  dw.solve.dt = solvers::dynamics::auto_time_step(
      solvers::dynamics::DynamicProblem::from_scene(scene), "variational", 10);
  dw.holds = kSamples;
  dw.hold_time = 0.3;  // ~1.3 first bending periods (4.4 Hz)
  const auto dyn = solvers::dynamics::sample_dynamic_workspace(scene, dw);
  BOOST_TEST_MESSAGE("static omega_bound " << stat.bounds.omega_bound << " rad/m, eps ["
                     << stat.bounds.eps_low << ", " << stat.bounds.eps_high << "]; dynamic "
                     << dyn.bounds.omega_bound << " rad/m, eps [" << dyn.bounds.eps_low << ", "
                     << dyn.bounds.eps_high << "], " << dyn.samples.size() << " tips, wall "
                     << dyn.wall_time_s << " s");
  BOOST_TEST(dyn.failed == 0);
  BOOST_TEST(dyn.samples.size() >= static_cast<std::size_t>(kSamples * 50));
  for (std::size_t k = 0; k < stat.samples[0].inputs.size(); ++k)
    BOOST_TEST(dyn.samples.back().inputs[k] == stat.samples[kSamples - 1].inputs[k]);
  BOOST_TEST(dyn.bounds.omega_bound > 1.1 * stat.bounds.omega_bound);
  // every static equilibrium lies in the dynamic workspace (the run passes near it)
  for (const auto& s : stat.samples)
    BOOST_TEST(solvers::statics::workspace_contains(dyn.bounds, s.tip, scene.rod.length, 0.05));
}
