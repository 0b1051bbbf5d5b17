#define BOOST_TEST_MODULE dynamics_extreme_materials
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/schemes.hpp"

// Issue #4: a very stiff rod (steel, E = 200 GPa, a 1 mm wire) and a very soft one (E = 10 kPa):
// every available dynamics scheme either runs, stops with its reason, or is refused before it
// starts naming the scheme to use (exit 2 on the command line); none reports success with a
// non-finite number. From the straight rod released under gravity (which excites every
// mode, the stiff axial ones included), undamped.

namespace {

using namespace rodlab;

scene::Scene material_scene(const std::string& name, double E, double rho, double D, double L) {
  const std::string yaml =
      "schema: rodlab.scene/1\nname: " + name + "\nrod:\n  length: " + std::to_string(L) +
      "\n  section: {shape: circle, diameter: " + std::to_string(D) + "}\n"
      "  material: {E: " + std::to_string(E) + ", poisson: 0.3, rho: " + std::to_string(rho) +
      "}\ntip:\n  free: {}\nloads:\n  gravity: [-9.81, 0, 0]\n";
  return io::load_scene_from_string(yaml, name + ".yaml");
}

bool all_finite(const result::DynamicResult& r) {
  auto finite = [](const std::vector<double>& v) {
    for (double x : v)
      if (!std::isfinite(x)) return false;
    return true;
  };
  for (const auto& p : r.tip_position)
    if (!p.allFinite()) return false;
  return finite(r.t) && finite(r.energy.kinetic) && finite(r.energy.strain) &&
         finite(r.energy.gravity) && finite(r.energy.total) && finite(r.max_det_deviation);
}

/// Every available scheme over the same simulated time T = 200 steps of `variational` at its
/// `dt: auto`, each at its own `dt: auto` but with at least 5 steps in T.
void run_every_scheme(const scene::Scene& s) {
  const auto problem = solvers::dynamics::DynamicProblem::from_scene(s);
  constexpr int kNodes = 12;
  const double T = 200 * solvers::dynamics::auto_time_step(problem, "variational", kNodes);
  for (const auto& info : solvers::all_schemes()) {
    if (info.problem != solvers::Problem::dynamics) continue;
    const std::string scheme(info.name);
    solvers::dynamics::DynamicSolveOptions o;
    o.scheme = scheme;
    o.nodes = kNodes;
    o.dt = std::min(solvers::dynamics::auto_time_step(problem, scheme, kNodes), T / 5);
    o.t_end = T;
    result::DynamicResult r;
    try {
      r = solvers::dynamics::solve_dynamic(s, o);
    } catch (const std::invalid_argument& e) {
      // refused before it starts (single shooting's lower step bound, step_bound.hpp): the
      // message names the schemes to use instead
      const std::string why = e.what();
      BOOST_TEST_MESSAGE(s.name << " " << scheme << ": refused: " << why);
      BOOST_TEST_CONTEXT(s.name << " / " << scheme) {
        BOOST_TEST((scheme == "implicit-midpoint" || scheme == "bdf-alpha"));
        BOOST_TEST(why.find("lower step bound") != std::string::npos, why);
        BOOST_TEST(why.find("implicit-midpoint-collocation") != std::string::npos, why);
      }
      continue;
    }
    BOOST_TEST_MESSAGE(s.name << " " << scheme << ": dt = " << r.dt << " s, t_end = " << T
                              << " s, converged " << r.converged << ", steps " << r.steps
                              << ", tip " << r.tip_position.back().transpose() << ", wall "
                              << r.wall_time_s << " s " << r.reason);
    BOOST_TEST_CONTEXT(s.name << " / " << scheme) {
      if (r.converged) {
        BOOST_TEST(all_finite(r));
        BOOST_TEST(r.reason.empty());
        BOOST_TEST(r.t.back() == T, boost::test_tools::tolerance(1e-12));
      } else {
        BOOST_TEST(!r.reason.empty());
      }
    }
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(steel_wire) {
  // E = 200 GPa, rho = 7850 kg/m^3, D = 1 mm, L = 0.1 m: axial wave speed 5 km/s.
  run_every_scheme(material_scene("steel-wire", 200e9, 7850, 0.001, 0.1));
}

BOOST_AUTO_TEST_CASE(very_soft_rod) {
  // E = 10 kPa, rho = 1000 kg/m^3, D = 1 cm, L = 0.1 m: gravity alone bends it past 90 degrees
  // (rho g A L^3 / EI = 157).
  run_every_scheme(material_scene("very-soft", 1e4, 1000, 0.01, 0.1));
}
