#define BOOST_TEST_MODULE scheme_registry
#include <boost/test/unit_test.hpp>

// The scheme catalogue (rodlab/scene/schemes.hpp) is the one list of schemes: the loader accepts
// exactly its names, where each belongs, and the registry (rodlab/solvers/registry.hpp) runs
// every one of them by name. References: the catalogue itself; the registry's statics entries
// against the scheme functions they wrap (bit-identical results), its dynamics entries against
// a run that must start at rest and stay finite.

#include <cmath>
#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/registry.hpp"
#include "rodlab/solvers/statics/chebyshev.hpp"
#include "rodlab/solvers/statics/kinsol_collocation.hpp"
#include "rodlab/solvers/statics/shooting.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace {

using namespace rodlab;

const std::string kBase = R"(schema: rodlab.scene/1
rod: {length: 0.1, section: {shape: circle, diameter: 0.01}, material: {E: 1.0e6, G: 0.33e6, rho: 1000}}
tip: {free: {}}
)";

const std::string kCantilever = kBase + "loads: {gravity: [-9.81, 0, 0]}\n";

/// The statics result of a scheme function called directly, as the registry should call it.
result::StaticResult direct(const solvers::statics::StaticProblem& P, solvers::SchemeId id,
                            int nodes) {
  using solvers::SchemeId;
  using solvers::statics::RkmkMethod;
  const solvers::statics::ShootingOptions shooting{nodes, 1e-10, 50, {}};
  switch (id) {
    case SchemeId::rkmk_euler_explicit:
      return solve_shooting(P, RkmkMethod::euler_explicit, shooting);
    case SchemeId::rkmk_euler_implicit:
      return solve_shooting(P, RkmkMethod::euler_implicit, shooting);
    case SchemeId::rkmk_midpoint_explicit:
      return solve_shooting(P, RkmkMethod::midpoint_explicit, shooting);
    case SchemeId::rkmk_midpoint_implicit:
      return solve_shooting(P, RkmkMethod::midpoint_implicit, shooting);
    case SchemeId::rkmk_rk4: return solve_shooting(P, RkmkMethod::rk4, shooting);
    case SchemeId::chebyshev: {
      solvers::statics::ChebyshevOptions o;
      o.nodes = nodes;
      return solve_chebyshev(P, o);
    }
    case SchemeId::kinsol: {
      solvers::statics::KinsolCollocationOptions o;
      o.nodes = nodes;
      return solve_kinsol_collocation(P, o);
    }
    default: throw std::logic_error("not a statics scheme");
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(catalogue_is_indexed_by_id_and_names_are_unique) {
  const auto all = solvers::all_schemes();
  BOOST_TEST(all.size() == static_cast<std::size_t>(scene::kSchemeCount));
  for (std::size_t i = 0; i < all.size(); ++i) {
    BOOST_TEST(static_cast<std::size_t>(all[i].id) == i);
    BOOST_TEST((solvers::find_scheme(all[i].name)->id == all[i].id));
    for (std::size_t j = 0; j < i; ++j) BOOST_TEST(all[i].name != all[j].name);
  }
  BOOST_TEST(!solvers::find_scheme("rk4").has_value());
}

BOOST_AUTO_TEST_CASE(every_scheme_name_is_accepted_where_it_belongs) {
  for (const auto& s : solvers::all_schemes()) {
    const std::string name(s.name);
    BOOST_TEST_CONTEXT(name) {
      const auto scene =
          io::load_scene_from_string(kBase + "solver: {scheme: " + name + "}\n", "s.yaml");
      BOOST_TEST(scene.solver.scheme == name);
      const std::string dyn = kBase + "dynamics: {t_end: 1, scheme: " + name + "}\n";
      if (s.problem == solvers::Problem::dynamics) {
        BOOST_TEST(*io::load_scene_from_string(dyn, "s.yaml").dynamics->scheme == name);
      } else {
        BOOST_CHECK_THROW(io::load_scene_from_string(dyn, "s.yaml"), io::SceneError);
      }
    }
  }
  BOOST_CHECK_THROW(io::load_scene_from_string(kBase + "solver: {scheme: rk4}\n", "s.yaml"),
                    io::SceneError);
}

// Each statics entry runs its own scheme: solve_static by name gives the scheme function's
// result to the last bit (the gravity cantilever, N = 11).
BOOST_AUTO_TEST_CASE(statics_entries_run_their_own_scheme) {
  const auto scene = io::load_scene_from_string(kCantilever, "cantilever.yaml");
  const auto P = solvers::statics::StaticProblem::from_scene(scene, 0.0);
  for (const auto& s : solvers::all_schemes()) {
    if (s.problem != solvers::Problem::statics) continue;
    BOOST_TEST_CONTEXT(s.name) {
      BOOST_CHECK_THROW(solvers::stepper_factory(s.id), std::invalid_argument);
      solvers::statics::StaticSolveOptions o;
      o.scheme = std::string(s.name);
      o.nodes = 11;
      const auto r = solvers::statics::solve_static(P, o);
      const auto d = direct(P, s.id, 11);
      BOOST_TEST(r.converged);
      BOOST_TEST(r.scheme == std::string(s.name));
      BOOST_TEST(r.iterations == d.iterations);
      BOOST_TEST((r.centerline.back().pose.translation() - d.centerline.back().pose.translation())
                     .norm() == 0.0);
    }
  }
}

// Each dynamics entry makes a stepper that runs: 10 steps of the scheme's dt: auto from rest,
// tip moved by at most the free fall g t^2 / 2 (the rod's stiffness only holds it back).
BOOST_AUTO_TEST_CASE(dynamics_entries_make_steppers_that_run) {
  const auto scene = io::load_scene_from_string(kCantilever, "cantilever.yaml");
  const auto problem = solvers::dynamics::DynamicProblem::from_scene(scene);
  for (const auto& s : solvers::all_schemes()) {
    if (s.problem != solvers::Problem::dynamics) continue;
    BOOST_TEST_CONTEXT(s.name) {
      BOOST_CHECK_THROW(solvers::static_solver(s.id), std::invalid_argument);
      solvers::dynamics::DynamicSolveOptions o;
      o.scheme = std::string(s.name);
      o.nodes = 6;
      o.dt = solvers::dynamics::auto_time_step(problem, s.name, o.nodes);
      o.t_end = 10 * o.dt;
      const auto r = solvers::dynamics::solve_dynamic(scene, o);
      BOOST_TEST(r.converged, r.reason);
      BOOST_TEST(r.scheme == std::string(s.name));
      BOOST_TEST(r.steps == 10);
      const double fall = 0.5 * 9.81 * o.t_end * o.t_end;
      BOOST_TEST((r.tip_position.back() - r.tip_position.front()).norm() <= fall * (1 + 1e-9));
    }
  }
}

// A name of the wrong problem class, or none, is rejected with the valid names.
BOOST_AUTO_TEST_CASE(scheme_for_names_the_valid_schemes) {
  BOOST_TEST((solvers::scheme_for("ida", solvers::Problem::dynamics).id == solvers::SchemeId::ida));
  try {
    solvers::scheme_for("ida", solvers::Problem::statics);
    BOOST_FAIL("expected std::invalid_argument");
  } catch (const std::invalid_argument& e) {
    BOOST_TEST(std::string(e.what()).find("rkmk-rk4") != std::string::npos, e.what());
  }
}
