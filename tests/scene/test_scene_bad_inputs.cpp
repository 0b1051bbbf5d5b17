#define BOOST_TEST_MODULE scene_bad_inputs
#include <boost/test/unit_test.hpp>

// Bad scene input is rejected with a message naming the field, at the right position.
// Data-driven part: one test case per tests/data/scenes/bad/NAME.yaml, called bad_file_NAME,
// registered when the program starts. Each file starts with
//   # expect: <substring of one diagnostic>
//   # expect-at: <line>:<col>        (1-based; 0:0 for problems without a position)
//   # expect-count: <n>              (optional, default 1: no follow-on noise)
// The override cases below use load_scene_from_string with --set lists.

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "rodlab/io/scene_loader.hpp"

namespace fs = std::filesystem;
using rodlab::io::load_scene;
using rodlab::io::load_scene_from_string;
using rodlab::io::Override;
using rodlab::io::parse_override;
using rodlab::io::SceneDiagnostic;
using rodlab::io::SceneError;

namespace bad_inputs {

const fs::path kBadDir = fs::path(RODLAB_TEST_DATA) / "scenes" / "bad";

std::vector<std::string> bad_files() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(kBadDir))
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

struct Expectation {
  std::string message;
  int line = -1, column = -1;
  std::size_t count = 1;
};

Expectation read_expectation(const fs::path& file) {
  Expectation e;
  std::ifstream in(file);
  std::string text;
  const std::regex expect("^# expect: (.*)$"), at("^# expect-at: (\\d+):(\\d+)$"),
      count("^# expect-count: (\\d+)$");
  std::smatch m;
  while (std::getline(in, text) && text.starts_with("#")) {
    if (std::regex_match(text, m, expect))
      e.message = m[1];
    else if (std::regex_match(text, m, at))
      e.line = std::stoi(m[1]), e.column = std::stoi(m[2]);
    else if (std::regex_match(text, m, count))
      e.count = std::stoul(m[1]);
  }
  return e;
}

/// The diagnostics of a load that must fail.
std::vector<SceneDiagnostic> rejection(const std::string& yaml,
                                       const std::vector<Override>& overrides) {
  try {
    load_scene_from_string(yaml, "scene.yaml", overrides);
  } catch (const SceneError& e) {
    return e.diagnostics();
  }
  BOOST_FAIL("the scene was accepted");
  return {};
}

const std::string kGood = R"(schema: rodlab.scene/1
rod:
  length: 0.1
  section: {shape: circle, diameter: 0.01}
  material: {E: 1.0e6, G: 0.33e6, rho: 1000}
tip: {free: {}}
actuators:
  - cable: {offset: [0.004, 0], tension: 0.5}
)";

std::vector<Override> overrides(std::initializer_list<const char*> texts) {
  std::vector<Override> out;
  for (const char* t : texts) out.push_back(parse_override(t));
  return out;
}

/// The test for one bad file: rejected, with the expected message at the expected position.
void check_bad_file(const std::string& file) {
  const fs::path path = kBadDir / file;
  const Expectation expected = read_expectation(path);
  BOOST_TEST_REQUIRE(!expected.message.empty(), file << " has no '# expect:' line");
  BOOST_TEST_REQUIRE(expected.line >= 0, file << " has no '# expect-at:' line");
  std::vector<SceneDiagnostic> diagnostics;
  try {
    load_scene(path.string());
    BOOST_FAIL(file << " was accepted");
  } catch (const SceneError& e) {
    diagnostics = e.diagnostics();
  }
  std::string all;
  for (const auto& d : diagnostics) all += "\n  " + d.to_string();
  BOOST_TEST_CONTEXT(file << " gave:" << all) {
    const auto hit = std::find_if(diagnostics.begin(), diagnostics.end(), [&](const auto& d) {
      return d.to_string().find(expected.message) != std::string::npos;
    });
    BOOST_TEST_REQUIRE((hit != diagnostics.end()),
                       "no diagnostic contains '" << expected.message << "'");
    BOOST_TEST(hit->source == path.string());
    BOOST_TEST(hit->line == expected.line);
    BOOST_TEST(hit->column == expected.column);
    BOOST_TEST(diagnostics.size() == expected.count);
  }
}

/// One test case per bad file, named after it, added to the master suite at start-up.
[[maybe_unused]] const bool registered = [] {
  auto& suite = boost::unit_test::framework::master_test_suite();
  for (const std::string& file : bad_files()) {
    const std::string name = "bad_file_" + fs::path(file).stem().string();
    suite.add(boost::unit_test::make_test_case([file] { check_bad_file(file); }, name, __FILE__,
                                               __LINE__));
  }
  return true;
}();

}  // namespace bad_inputs

using namespace bad_inputs;

BOOST_AUTO_TEST_CASE(there_is_a_bad_file_for_every_kind_of_problem) {
  BOOST_TEST(bad_files().size() >= 40u);
}

BOOST_AUTO_TEST_CASE(message_format_is_file_line_column_field_message) {
  const fs::path path = kBadDir / "negative-E.yaml";
  try {
    load_scene(path.string());
    BOOST_FAIL("accepted");
  } catch (const SceneError& e) {
    BOOST_TEST(std::string(e.what()) ==
               path.string() + ":7:17: rod.material.E: must be > 0 (got -1)");
  }
}

BOOST_AUTO_TEST_CASE(all_problems_are_listed_in_what_one_per_line) {
  try {
    load_scene((kBadDir / "several-problems.yaml").string());
    BOOST_FAIL("accepted");
  } catch (const SceneError& e) {
    const std::string what = e.what();
    BOOST_TEST(std::count(what.begin(), what.end(), '\n') == 2);
    BOOST_TEST(what.find("rod.material.E") < what.find("loads.gravity"));
    BOOST_TEST(what.find("loads.gravity") < what.find("solver.nodes"));
  }
}

BOOST_AUTO_TEST_CASE(missing_file_is_named) {
  const std::string path = (kBadDir / "no-such-scene.yaml").string();
  try {
    load_scene(path);
    BOOST_FAIL("accepted");
  } catch (const SceneError& e) {
    BOOST_TEST_REQUIRE(e.diagnostics().size() == 1u);
    BOOST_TEST(e.diagnostics()[0].source == path);
    BOOST_TEST(e.diagnostics()[0].line == 0);
    BOOST_TEST(std::string(e.what()).find("cannot open the scene file") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(directory_is_not_a_scene) {
  BOOST_CHECK_THROW(load_scene(kBadDir.string()), SceneError);
}

// ---- overrides

BOOST_AUTO_TEST_CASE(parse_override_needs_key_equals_value) {
  BOOST_CHECK_THROW(parse_override("rod.material.E"), SceneError);
  BOOST_CHECK_THROW(parse_override("=3"), SceneError);
  BOOST_CHECK_THROW(parse_override(" =3"), SceneError);
  try {
    parse_override("rod.length");
  } catch (const SceneError& e) {
    BOOST_TEST(e.diagnostics()[0].source == "--set");
    BOOST_TEST(std::string(e.what()).find("expected KEY=VALUE") != std::string::npos);
  }
  const Override o = parse_override("loads.gravity=[0, 0, -9.81]");
  BOOST_TEST(o.path == "loads.gravity");
  BOOST_TEST(o.value == "[0, 0, -9.81]");
  BOOST_TEST(o.text == "loads.gravity=[0, 0, -9.81]");
  BOOST_TEST(parse_override("name=a=b").value == "a=b");
}

BOOST_AUTO_TEST_CASE(bad_overridden_value_is_reported_against_the_override) {
  const auto d = rejection(kGood, overrides({"rod.material.E=-1"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() == "--set rod.material.E=-1: rod.material.E: must be > 0 (got -1)");
  BOOST_TEST(d[0].line == 0);
  BOOST_TEST(d[0].column == 0);
}

BOOST_AUTO_TEST_CASE(override_to_unknown_key_is_an_unknown_key) {
  const auto d = rejection(kGood, overrides({"rod.materal.E=2e6"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].source == "--set rod.materal.E=2e6");
  BOOST_TEST(d[0].field == "rod.materal");
  BOOST_TEST(d[0].message.find("unknown key (did you mean material?)") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(override_index_out_of_range_names_the_override) {
  const auto d = rejection(kGood, overrides({"actuators.3.cable.tension=0.3"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() ==
             "--set actuators.3.cable.tension=0.3: actuators.3: no such element: actuators has 1 "
             "entries (got index 3)");
}

BOOST_AUTO_TEST_CASE(override_index_into_a_map_or_an_absent_list_is_an_error) {
  auto d = rejection(kGood, overrides({"rod.0=1"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].message.find("rod is not a list, so it has no element 0") != std::string::npos);
  d = rejection(kGood, overrides({"loads.gravity.1=0"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].source == "--set loads.gravity.1=0");
  BOOST_TEST(d[0].message.find("loads.gravity is not a list") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(override_inside_a_scalar_is_an_error) {
  const auto d = rejection(kGood, overrides({"rod.length.x=1"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() ==
             "--set rod.length.x=1: rod.length.x: rod.length is a single value, "
             "so it has no field x (got 0.1)");
}

BOOST_AUTO_TEST_CASE(override_key_into_a_list_is_an_error) {
  const auto d = rejection(kGood, overrides({"actuators.cable.tension=1"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].message.find("actuators is a list, indexed by number") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(override_value_that_is_not_yaml) {
  const auto d = rejection(kGood, overrides({"loads.gravity=[0, 0"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].source == "--set loads.gravity=[0, 0");
  BOOST_TEST(d[0].message.find("the value is not valid YAML") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(override_path_with_an_empty_segment) {
  const auto d = rejection(kGood, overrides({"rod..E=1"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].message.find("KEY must be a dotted path") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(override_with_a_wrong_type_or_length) {
  auto d = rejection(kGood, overrides({"loads.gravity=[0, -9.81]"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() ==
             "--set loads.gravity=[0, -9.81]: loads.gravity: must be a list of 3 "
             "numbers (got [0, -9.81])");
  d = rejection(kGood, overrides({"solver.nodes=2.5"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() ==
             "--set solver.nodes=2.5: solver.nodes: must be an integer (got 2.5)");
}

BOOST_AUTO_TEST_CASE(problems_in_maps_an_override_created_are_the_overrides) {
  // loads and loads.drag do not exist in the file: the missing coefficients are the override's.
  const auto d = rejection(kGood, overrides({"loads.drag.fluid_density=-1"}));
  BOOST_TEST_REQUIRE(d.size() == 2u);
  for (const auto& x : d) BOOST_TEST(x.source == "--set loads.drag.fluid_density=-1");
  BOOST_TEST(d[0].field + d[1].field == "loads.drag.fluid_densityloads.drag");
}

BOOST_AUTO_TEST_CASE(override_replacing_a_map_owns_what_is_missing_in_it) {
  const auto d = rejection(kGood, overrides({"rod.material={E: 2e6, rho: 1000}"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() ==
             "--set rod.material={E: 2e6, rho: 1000}: rod.material: one of G, "
             "poisson is required");
}

BOOST_AUTO_TEST_CASE(override_adding_a_second_choice_is_reported_at_the_override) {
  const auto d = rejection(kGood, overrides({"rod.material.poisson=0.3"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() ==
             "--set rod.material.poisson=0.3: rod.material.poisson: give only one "
             "of G, poisson (got G and poisson)");
}

BOOST_AUTO_TEST_CASE(file_problems_come_first_then_override_problems_in_order) {
  std::string yaml = kGood;
  yaml.replace(yaml.find("rho: 1000"), 9, "rho: -5");
  const auto d = rejection(yaml, overrides({"solver.tol=0", "rod.length=-1"}));
  BOOST_TEST_REQUIRE(d.size() == 3u);
  BOOST_TEST(d[0].to_string() == "scene.yaml:5:40: rod.material.rho: must be > 0 (got -5)");
  BOOST_TEST(d[1].source == "--set solver.tol=0");
  BOOST_TEST(d[2].source == "--set rod.length=-1");
}

BOOST_AUTO_TEST_CASE(the_latest_override_of_a_field_is_blamed) {
  const auto d = rejection(kGood, overrides({"rod.length=0.2", "rod.length=0"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].source == "--set rod.length=0");
}

BOOST_AUTO_TEST_CASE(duplicate_key_in_an_overridden_value) {
  const auto d = rejection(kGood, overrides({"rod.material={E: 1, G: 1, rho: 1, G: 2}"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].to_string() ==
             "--set rod.material={E: 1, G: 1, rho: 1, G: 2}: rod.material.G: duplicate key");
}

BOOST_AUTO_TEST_CASE(bad_control_override_is_reported_against_the_override) {
  // kGood's cable has no limits: control needs them, and says so at the cable in the file
  auto d = rejection(kGood, overrides({"control.horizon=0"}));
  BOOST_TEST_REQUIRE(d.size() == 2u);
  BOOST_TEST(d[0].to_string() ==
             "scene.yaml:8:12: actuators.0.cable.limits: is required by control (the bounds of "
             "the input the controller sets)");
  BOOST_TEST(d[1].to_string() ==
             "--set control.horizon=0: control.horizon: must be >= 1 (got 0)");

  d = rejection(kGood, overrides({"actuators.0.cable.limits=[0, 1]",
                                  "control={task: track, targets: [[0, 0, 0.1]]}"}));
  BOOST_TEST_REQUIRE(d.size() == 1u);
  BOOST_TEST(d[0].source == "--set control={task: track, targets: [[0, 0, 0.1]]}");
  BOOST_TEST(d[0].field == "control.targets");
  BOOST_TEST(d[0].message.find("task track follows a trajectory") != std::string::npos);
}
