#define BOOST_TEST_MODULE scheme_names
#include <boost/test/unit_test.hpp>

// The loader (rodlab::io, which does not link rodlab::solvers) keeps its own list of scheme
// names for solver.scheme / dynamics.scheme; it must equal the solvers' catalogue.

#include <string>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/schemes.hpp"

BOOST_AUTO_TEST_CASE(loader_scheme_names_equal_the_solver_catalogue) {
  const auto loader = rodlab::io::scene_scheme_names();
  const auto catalogue = rodlab::solvers::all_schemes();
  BOOST_TEST_REQUIRE(loader.size() == catalogue.size());
  for (std::size_t i = 0; i < loader.size(); ++i) {
    BOOST_TEST_CONTEXT("scheme " << i) {
      BOOST_TEST(std::string(loader[i].name) == std::string(catalogue[i].name));
      BOOST_TEST(loader[i].dynamics ==
                 (catalogue[i].problem == rodlab::solvers::Problem::dynamics));
    }
  }
}

BOOST_AUTO_TEST_CASE(every_scheme_name_is_accepted_where_it_belongs) {
  const std::string base = R"(schema: rodlab.scene/1
rod: {length: 0.1, section: {shape: circle, diameter: 0.01}, material: {E: 1.0e6, G: 0.33e6, rho: 1000}}
tip: {free: {}}
)";
  for (const auto& s : rodlab::solvers::all_schemes()) {
    const std::string name(s.name);
    BOOST_TEST_CONTEXT(name) {
      const auto scene =
          rodlab::io::load_scene_from_string(base + "solver: {scheme: " + name + "}\n", "s.yaml");
      BOOST_TEST(scene.solver.scheme == name);
      const std::string dyn = base + "dynamics: {t_end: 1, scheme: " + name + "}\n";
      if (s.problem == rodlab::solvers::Problem::dynamics) {
        BOOST_TEST(*rodlab::io::load_scene_from_string(dyn, "s.yaml").dynamics->scheme == name);
      } else {
        BOOST_CHECK_THROW(rodlab::io::load_scene_from_string(dyn, "s.yaml"),
                          rodlab::io::SceneError);
      }
    }
  }
}
