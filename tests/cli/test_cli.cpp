#define BOOST_TEST_MODULE cli
#include <boost/test/unit_test.hpp>

// The rodlab command line (interface spec section 2), run as a user would: the binary in a
// fresh temporary working directory, checking the exit status, what it printed, and that a
// run with exit status 2 wrote nothing. Numbers are checked against closed forms computed
// here from the scene's raw values (A = pi D^2/4, I = pi D^4/64, c = sqrt(E/rho), ...).

#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/solvers/schemes.hpp"

#include "cli_support.hpp"

namespace fs = std::filesystem;
using Json = nlohmann::json;
constexpr double pi = std::numbers::pi;

using namespace rodlab::testing::cli;

namespace {

const std::string kScene = RODLAB_SOURCE_DIR "/scenes/cantilever-gravity.yaml";

/// Runs of spaces collapsed to one, so that aligned columns compare as plain text.
std::string collapse(const std::string& text) {
  return std::regex_replace(text, std::regex(" +"), " ");
}

std::string g6(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

}  // namespace

// --- usage ----------------------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(help_lists_every_subcommand) {
  Sandbox box;
  for (const std::string args : {"--help", "-h", "help"}) {
    const Run r = box.run(args);
    BOOST_TEST(r.status == 0);
    for (const char* name :
         {"check", "static", "dynamic", "schemes", "study", "validate", "workspace", "plot"})
      BOOST_TEST(contains(r.out, std::string("  ") + name + " "), args << " lists " << name);
  }
  const Run r = box.run("static --help");
  BOOST_TEST(r.status == 0);
  for (const char* option : {"--scheme", "--nodes", "--tol", "--out", "--set"})
    BOOST_TEST(contains(r.out, option));
  BOOST_TEST(box.run("help dynamic").status == 0);
  BOOST_TEST(contains(box.run("dynamic -h").out, "--dt"));
}

BOOST_AUTO_TEST_CASE(version) {
  Sandbox box;
  const Run r = box.run("--version");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(contains(r.out, "rodlab "));
}

BOOST_AUTO_TEST_CASE(no_arguments_is_a_usage_error) {
  Sandbox box;
  const Run r = box.run("");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(contains(r.err, "Usage: rodlab"));
  BOOST_TEST(r.out.empty());
}

BOOST_AUTO_TEST_CASE(unknown_subcommand_lists_the_valid_ones) {
  Sandbox box;
  expect_bad_input(box, "frobnicate",
                   {"frobnicate", "check, static, dynamic, control, schemes, study, train, validate, workspace, plot"});
  expect_bad_input(box, "help frobnicate", {"frobnicate", "check, static"});
  expect_bad_input(box, quote(kScene), {"unknown subcommand", "check, static"});  // forgot `check`
  expect_bad_input(box, "--nodes 3", {"unknown option '--nodes'"});
}

// --- check ----------------------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(check_prints_closed_form_quantities) {
  Sandbox box;
  const auto scene = rodlab::io::load_scene(kScene);
  BOOST_REQUIRE(std::holds_alternative<rodlab::rod::Circle>(scene.rod.section));
  const double D = std::get<rodlab::rod::Circle>(scene.rod.section).diameter;
  const auto& m = scene.rod.material;

  const Run check = box.run("check " + quote(kScene));
  BOOST_TEST_CONTEXT(check.err) { BOOST_TEST(check.status == 0); }
  const std::string out = collapse(check.out);
  BOOST_TEST(contains(out, "A = " + g6(pi * D * D / 4) + " m^2"), out);
  BOOST_TEST(contains(out, "Ix = " + g6(pi * std::pow(D, 4) / 64) + " m^4"));
  BOOST_TEST(contains(out, "Jt = " + g6(pi * std::pow(D, 4) / 32) + " m^4"));
  BOOST_TEST(contains(out, "K[0] = E Ix = " + g6(m.E * pi * std::pow(D, 4) / 64) + " N m^2"));
  BOOST_TEST(contains(out, "M[3] = rho A = " + g6(m.rho * pi * D * D / 4) + " kg/m"));
  BOOST_TEST(contains(out, "sqrt(E/rho) = " + g6(std::sqrt(m.E / m.rho)) + " m/s"));
  BOOST_TEST(contains(out, "sqrt(G/rho) = " + g6(std::sqrt(m.G / m.rho)) + " m/s"));
  BOOST_TEST(contains(out, scene.name));
  BOOST_TEST(contains(out, "verdict"));
  if (D == 0.01 && m.E == 1e6 && m.rho == 1000) {  // the thesis' test rod (spec example)
    BOOST_TEST(contains(out, "A = 7.85398e-05 m^2"));
    BOOST_TEST(contains(out, "sqrt(E/rho) = 31.6228 m/s"));
  }
  BOOST_TEST(box.files().empty());
}

BOOST_AUTO_TEST_CASE(check_json_matches_closed_forms) {
  Sandbox box;
  const auto scene = rodlab::io::load_scene(kScene);
  BOOST_REQUIRE(std::holds_alternative<rodlab::rod::Circle>(scene.rod.section));
  const double D = std::get<rodlab::rod::Circle>(scene.rod.section).diameter;
  const auto& m = scene.rod.material;
  const double L = scene.rod.length;

  const Run r = box.run("check " + quote(kScene) + " --json --nodes 11");
  BOOST_REQUIRE_EQUAL(r.status, 0);
  const Json j = Json::parse(r.out);
  const auto tol = boost::test_tools::tolerance(1e-12);
  BOOST_TEST(j["schema"] == "rodlab.check/1");
  BOOST_TEST(j["scene"]["name"] == scene.name);
  BOOST_TEST(j["section"]["A"].get<double>() == pi * D * D / 4, tol);
  BOOST_TEST(j["section"]["Ix"].get<double>() == pi * std::pow(D, 4) / 64, tol);
  BOOST_TEST(j["section"]["Iy"].get<double>() == pi * std::pow(D, 4) / 64, tol);
  BOOST_TEST(j["section"]["J"].get<double>() == pi * std::pow(D, 4) / 32, tol);
  BOOST_TEST(j["section"]["Jt"].get<double>() == pi * std::pow(D, 4) / 32, tol);
  const Json& K = j["matrices"]["K_diag"];
  BOOST_REQUIRE_EQUAL(K.size(), 6u);
  BOOST_TEST(K[0].get<double>() == m.E * pi * std::pow(D, 4) / 64, tol);
  BOOST_TEST(K[2].get<double>() == m.G * pi * std::pow(D, 4) / 32, tol);
  BOOST_TEST(K[3].get<double>() == m.G * pi * D * D / 4, tol);
  BOOST_TEST(K[5].get<double>() == m.E * pi * D * D / 4, tol);
  BOOST_TEST(j["matrices"]["M_diag"][3].get<double>() == m.rho * pi * D * D / 4, tol);
  BOOST_TEST(!j["matrices"].contains("V_diag"));  // elastic rod
  const Json& t = j["time_scales"];
  BOOST_TEST(t["axial_wave_speed"].get<double>() == std::sqrt(m.E / m.rho), tol);
  BOOST_TEST(t["shear_wave_speed"].get<double>() == std::sqrt(m.G / m.rho), tol);
  BOOST_TEST(t["nodes"].get<int>() == 11);
  BOOST_TEST(t["ds"].get<double>() == L / 10, tol);
  const double k = scene.rod.model == rodlab::rod::ModelKind::kirchhoff ? 0.9 : 0.1;  // thesis
  BOOST_TEST(t["dt_thesis"].get<double>() == k * L / 10 * std::sqrt(m.rho / m.E), tol);
  // 3 E I / (G A L^2) with I = pi D^4/64, A = pi D^2/4: 3 E D^2 / (16 G L^2).
  BOOST_TEST(j["model_choice"]["kirchhoff_error_estimate"].get<double>() ==
                 3 * m.E * D * D / (16 * m.G * L * L),
             tol);
  BOOST_TEST(j["model_choice"]["kirchhoff_safe"].is_boolean());
  BOOST_TEST(j["units"]["section.A"] == "m^2");
}

BOOST_AUTO_TEST_CASE(check_reports_viscosity_and_actuators_when_present) {
  Sandbox box;
  box.write("v.yaml",
            "schema: rodlab.scene/1\n"
            "name: viscous\n"
            "rod:\n"
            "  model: kirchhoff\n"
            "  length: 0.2\n"
            "  section: {shape: rectangle, width: 0.01, height: 0.002}\n"
            "  material: {E: 2.0e6, G: 0.7e6, rho: 1100, viscosity: 5}\n"
            "tip:\n"
            "  free: {}\n"
            "actuators:\n"
            "  - cable: {offset: [0.004, 0, 0], tension: {ramp: [[0, 0], [1, 0.5]]}}\n");
  const Run r = box.run("check v.yaml --json");
  BOOST_REQUIRE_EQUAL(r.status, 0);
  const Json j = Json::parse(r.out);
  const auto tol = boost::test_tools::tolerance(1e-12);
  const double w = 0.01, h = 0.002, A = w * h, Ix = w * h * h * h / 12;
  BOOST_TEST(j["section"]["A"].get<double>() == A, tol);
  BOOST_TEST(j["section"]["Ix"].get<double>() == Ix, tol);
  BOOST_TEST(j["matrices"]["V_diag"][0].get<double>() == 3 * 5 * Ix, tol);  // (3.10)
  BOOST_TEST(j["matrices"]["V_diag"][3].get<double>() == 5 * A, tol);
  BOOST_TEST(j["scene"]["model"] == "kirchhoff");
  BOOST_TEST(j["time_scales"]["thesis_safety_factor"].get<double>() == 0.9);
  BOOST_REQUIRE_EQUAL(j["loads"]["actuators"].size(), 1u);
  BOOST_TEST(contains(j["loads"]["actuators"][0].get<std::string>(), "cable"));
  BOOST_TEST(contains(collapse(box.run("check v.yaml").out), "V[0] = 3 alpha Ix"));
}

// `rodlab check` reports the steps `dt: auto` takes, and they are the steps `rodlab dynamic`
// takes: on the viscous control robot (alpha = 300 Pa s, Kirchhoff, N = 20) the variational
// scheme's stable step is set by the viscous relaxation, 1.36e-5 s, ten times below the
// thesis' (3.44) 0.9 ds sqrt(rho/E) = 1.5e-4 s, which ignores viscosity; the implicit schemes
// take a tenth of the first bending period.
BOOST_AUTO_TEST_CASE(check_reports_the_steps_dynamic_takes) {
  Sandbox box;
  const std::string scene = quote(std::string(RODLAB_SOURCE_DIR) + "/scenes/control-cable.yaml");
  const std::string rod = " --nodes 20 --set rod.model=kirchhoff";
  const Run r = box.run("check " + scene + rod + " --json");
  BOOST_REQUIRE_EQUAL(r.status, 0);
  const Json t = Json::parse(r.out)["time_scales"];
  const double variational = t["dt_auto_variational"], implicit = t["dt_auto_implicit"];
  BOOST_TEST(variational < 0.1 * t["dt_thesis"].get<double>());
  const double f_b = Json::parse(r.out)["frequencies"]["first_bending_hz"];
  BOOST_TEST(implicit == 0.1 / f_b, boost::test_tools::tolerance(1e-12));
  for (const auto& [scheme, dt] : {std::pair{"variational", variational},
                                   std::pair{"implicit-midpoint", implicit}}) {
    const Run d = box.run("dynamic " + scene + rod + " --scheme " + scheme +
                          " --t-end 0.05 --out d.json");
    BOOST_REQUIRE_EQUAL(d.status, 0);
    const Json result = Json::parse(read(box.work / "d.json"));
    // the run fits a whole number of equal steps into t_end: within one step of auto's
    const double taken = result["dt"], steps = result["steps"];
    BOOST_TEST_CONTEXT(scheme) {
      BOOST_TEST(taken <= dt * (1 + 1e-12));
      BOOST_TEST(taken * (steps + 1) >= 0.05);
    }
  }
}

// --- option checking ------------------------------------------------------------------------

// One rule for the node count (lib/include/rodlab/scene/schemes.hpp, min_nodes): statics from
// 2, dynamics from 3, in the option check and for the scene's solver.nodes alike (exit 2 up
// front, not a solver's "nodes must be >= 3").
BOOST_AUTO_TEST_CASE(node_minimum_is_one_rule_per_problem) {
  Sandbox box;
  const std::string scene = quote(kScene);
  expect_bad_input(box, "dynamic " + scene + " --nodes 2 --t-end 0.01",
                   {"--nodes", "integer >= 3", "got 2"});
  expect_bad_input(box, "dynamic " + scene + " --set solver.nodes=2 --t-end 0.01",
                   {"solver.nodes", "N >= 3", "got 2"});
  const Run ok = box.run("static " + scene + " --nodes 2 --scheme rkmk-rk4");
  BOOST_TEST(ok.status != 2, ok.err);
}


BOOST_AUTO_TEST_CASE(bad_option_values_name_the_option) {
  Sandbox box;
  const std::string scene = quote(kScene);
  expect_bad_input(box, "check " + scene + " --nodes 1", {"--nodes", "integer >= 2", "got 1"});
  expect_bad_input(box, "static " + scene + " --nodes abc", {"--nodes", "abc"});
  expect_bad_input(box, "static " + scene + " --nodes 2.5", {"--nodes", "2.5"});
  expect_bad_input(box, "static " + scene + " --tol 0", {"--tol", "> 0"});
  expect_bad_input(box, "static " + scene + " --tol -1e-3", {"--tol", "-1e-3"});
  expect_bad_input(box, "dynamic " + scene + " --dt -1", {"--dt", "-1"});
  expect_bad_input(box, "dynamic " + scene + " --dt 0 --t-end 1", {"--dt", "auto"});
  expect_bad_input(box, "dynamic " + scene + " --t-end 0", {"--t-end"});
  expect_bad_input(box, "dynamic " + scene + " --output-every 0", {"--output-every", "got 0"});
  expect_bad_input(box, "static " + scene + " --out r.txt", {"--out", ".json or .csv", "r.txt"});
  expect_bad_input(box, "static " + scene + " --out missing/r.json", {"--out", "missing"});
  expect_bad_input(box, "static " + scene + " --nodes 3 --nodes 4", {"--nodes", "more than once"});
  expect_bad_input(box, "static " + scene + " --frobnicate", {"--frobnicate", "--scheme"});
  expect_bad_input(box, "static " + scene + " --nodes", {"--nodes", "missing value"});
  expect_bad_input(box, "static " + scene + " --out --nodes 3", {"--out", "missing value"});
  expect_bad_input(box, "static", {"missing SCENE"});
  expect_bad_input(box, "static " + scene + " extra", {"unexpected argument 'extra'"});
  expect_bad_input(box, "check " + scene + " --json=yes", {"--json", "takes no value"});
  expect_bad_input(box, "schemes --nodes 3", {"--nodes", "takes no options"});
}

BOOST_AUTO_TEST_CASE(every_problem_is_reported_at_once) {
  Sandbox box;
  const Run r = box.run("dynamic " + quote(kScene) + " --nodes 1 --tol -1 --dt x");
  BOOST_TEST(r.status == 2);
  BOOST_TEST(contains(r.err, "--nodes"));
  BOOST_TEST(contains(r.err, "--tol"));
  BOOST_TEST(contains(r.err, "--dt"));
}

BOOST_AUTO_TEST_CASE(dt_auto_is_accepted) {
  Sandbox box;
  const Run r = box.run("dynamic " + quote(kScene) + " --dt auto --t-end 1e-4 --nodes 5");
  BOOST_TEST(!contains(r.err, "--dt"), r.err);
  // Either it ran (0 or 1), or the dynamics schemes are not there yet (2, saying so).
  BOOST_TEST((r.status != 2 || contains(r.err, "not available yet")), r.err);
  BOOST_TEST(box.files().empty());
}

// rodlab dynamic: a short run writes the result (spec section 4) and exits 0; a run above the
// explicit scheme's stability limit exits 1 and still writes the result, with the reason; a scene
// feature a scheme does not support is bad input (2, nothing written).
BOOST_AUTO_TEST_CASE(dynamic_writes_results_and_reports_instability) {
  Sandbox box;
  const std::string scene = quote(kScene);
  const Run ok = box.run("dynamic " + scene + " --t-end 2e-3 --nodes 6 --out r.json");
  BOOST_TEST(ok.status == 0, ok.err);
  BOOST_TEST(contains(ok.out, "real-time ratio"));
  const std::string json = read(box.work / "r.json");
  BOOST_TEST(contains(json, "\"schema\": \"rodlab.dynamic-result/1\""));
  BOOST_TEST(contains(json, "\"converged\": true"));
  BOOST_TEST(contains(json, "\"work_in\""));
  const Run blown = box.run("dynamic " + scene + " --t-end 0.05 --nodes 20 --dt 1e-3 --out b.json");
  BOOST_TEST(blown.status == 1, blown.err);
  const std::string bad = read(box.work / "b.json");
  BOOST_TEST(contains(bad, "\"converged\": false"));
  BOOST_TEST(contains(bad, "unstable"));
  // ida runs Kirchhoff rods (the stabilised index-2 form, docs/dynamics.md)
  const Run kirchhoff = box.run("dynamic " + scene +
                                " --scheme ida --t-end 1e-3 --set rod.model=kirchhoff --out k.json");
  BOOST_TEST(kirchhoff.status == 0, kirchhoff.err);
  BOOST_TEST(contains(read(box.work / "k.json"), "\"converged\": true"));
}

// Muscles run with every dynamics scheme (scenes/muscle-dynamics.yaml), and so does length
// control (ida: the stabilised index-2 form; docs/dynamics.md "Muscles and length control").
BOOST_AUTO_TEST_CASE(dynamic_muscles_and_length_control) {
  Sandbox box;
  const std::string muscle = quote(RODLAB_SOURCE_DIR "/scenes/muscle-dynamics.yaml");
  for (const char* scheme :
       {"variational", "implicit-midpoint", "implicit-midpoint-collocation", "bdf-alpha", "ida"}) {
    const Run r = box.run("dynamic " + muscle + " --scheme " + scheme + " --t-end 0.3 --out m.json");
    BOOST_TEST(r.status == 0, scheme << ": " << r.err);
    BOOST_TEST(contains(read(box.work / "m.json"), "\"converged\": true"), scheme);
  }
  box.write("pulled.yaml",
            "schema: rodlab.scene/1\nname: pulled\nrod:\n  length: 0.1\n"
            "  section: {shape: circle, diameter: 0.01}\n"
            "  material: {E: 1.0e6, G: 0.33e6, rho: 1000, viscosity: 300}\n"
            "tip:\n  free: {}\nactuators:\n"
            "  - cable: {offset: [0.004, 0], displacement: {ramp: [[0, 0], [0.5, 0.002]]}}\n");
  const Run pulled = box.run("dynamic pulled.yaml --scheme implicit-midpoint-collocation "
                             "--t-end 0.05 --dt 1e-2 --out p.json");
  BOOST_TEST(pulled.status == 0, pulled.err);
  const Run ida = box.run("dynamic pulled.yaml --scheme ida --t-end 0.05 --dt 1e-2 --out i.json");
  BOOST_TEST(ida.status == 0, ida.err);
  BOOST_TEST(contains(read(box.work / "i.json"), "\"converged\": true"));
}

// --time: the scene's schedules are evaluated at that time (scenes/cable-steps.yaml: cable 0
// pulls 0 N before t = 0.5 s and 0.5 N from then on, bending the tip towards +x by 2 cm).
BOOST_AUTO_TEST_CASE(static_time_option_evaluates_the_schedules) {
  Sandbox box;
  const std::string scene = quote(std::string(RODLAB_SOURCE_DIR) + "/scenes/cable-steps.yaml");
  const auto tip_x = [&](const std::string& time) {
    const Run r = box.run("static " + scene + " --scheme rkmk-rk4 --nodes 30 --time " + time +
                          " --out s" + time + ".json");
    BOOST_TEST(r.status == 0, r.err);
    return Json::parse(read(box.work / ("s" + time + ".json")))["tip"]["position"][0].get<double>();
  };
  BOOST_TEST(std::abs(tip_x("0")) < 1e-12);
  BOOST_TEST(tip_x("0.7") > 0.015);  // measured 0.0200 m (rkmk-rk4, N = 30)
  expect_bad_input(box, "static " + scene + " --time -1", {"--time", "got -1"});
}

// --alpha, bdf-alpha's parameter: outside [-0.5, 0] or not a number it is bad input (2, nothing
// written); inside it runs and the result names the scheme.
BOOST_AUTO_TEST_CASE(dynamic_alpha_option) {
  Sandbox box;
  const std::string scene = quote(kScene);
  expect_bad_input(box, "dynamic " + scene + " --scheme bdf-alpha --alpha 0.1 --t-end 0.1 --out a.json",
                   {"--alpha", "[-0.5, 0]", "got 0.1"});
  expect_bad_input(box, "dynamic " + scene + " --scheme bdf-alpha --alpha -0.6 --t-end 0.1",
                   {"--alpha", "got -0.6"});
  expect_bad_input(box, "dynamic " + scene + " --alpha x --t-end 0.1", {"--alpha", "got x"});
  const Run ok = box.run("dynamic " + scene +
                         " --scheme bdf-alpha --alpha -0.5 --t-end 0.1 --nodes 10 --out a.json");
  BOOST_TEST(ok.status == 0, ok.err);
  BOOST_TEST(contains(read(box.work / "a.json"), "\"scheme\": \"bdf-alpha\""));
}

// --grid, the shooting schemes' spatial grid: anything but euler / staggered is bad input (2,
// nothing written); staggered runs and lands elsewhere than euler at N = 10 (first against
// second order in s: the tips differ by the Euler grid's spatial error, ~1e-3 m here).
BOOST_AUTO_TEST_CASE(dynamic_grid_option) {
  Sandbox box;
  const std::string scene = quote(kScene);
  expect_bad_input(box, "dynamic " + scene + " --scheme implicit-midpoint --grid chebyshev --t-end 0.1 --out a.json",
                   {"--grid", "euler, staggered or corrected", "got chebyshev"});
  double tip[2] = {0, 0};
  int k = 0;
  for (const char* grid : {"euler", "staggered"}) {
    const Run ok = box.run("dynamic " + scene + " --scheme implicit-midpoint --grid " + grid +
                           " --dt 0.01 --t-end 0.1 --nodes 10 --out g.json");
    BOOST_TEST(ok.status == 0, ok.err);
    const auto j = Json::parse(read(box.work / "g.json"));
    tip[k++] = j["series"]["tip_position"].back()[0].get<double>();
  }
  BOOST_TEST_MESSAGE("tip x: euler " << tip[0] << ", staggered " << tip[1]);
  BOOST_TEST(std::abs(tip[0] - tip[1]) > 1e-5);
}

// --grid corrected, variational's corrected grid (docs/dynamics.md "The corrected grid"): runs,
// with a longer automatic step than the staggered grid's at N = 6 (its softer shear lowers the
// rotation-shear frequency that bounds coarse grids: 0.41 against 0.25 ms measured) and another
// tip; any other scheme, a Kirchhoff rod or a scene with actuators is bad input naming
// solver.grid (2, nothing written).
BOOST_AUTO_TEST_CASE(dynamic_corrected_grid_option) {
  Sandbox box;
  const std::string scene = quote(kScene);
  double dt[2] = {0, 0}, tip[2] = {0, 0};
  int k = 0;
  for (const char* grid : {"staggered", "corrected"}) {
    const Run ok = box.run("dynamic " + scene + " --scheme variational --grid " + grid +
                           " --t-end 0.05 --nodes 6 --out g.json");
    BOOST_TEST(ok.status == 0, ok.err);
    const auto j = Json::parse(read(box.work / "g.json"));
    dt[k] = j["dt"].get<double>();
    tip[k++] = j["series"]["tip_position"].back()[0].get<double>();
  }
  BOOST_TEST_MESSAGE("dt: staggered " << dt[0] << ", corrected " << dt[1] << "; tip x "
                                      << tip[0] << ", " << tip[1]);
  BOOST_TEST(dt[1] > 1.4 * dt[0]);
  BOOST_TEST(std::abs(tip[0] - tip[1]) > 1e-5);
  // `rodlab check` reports the step of the scene's grid: within one step of the run's
  const Run c = box.run("check " + scene + " --nodes 6 --set solver.grid=corrected --json");
  BOOST_REQUIRE_EQUAL(c.status, 0);
  const double reported = Json::parse(c.out)["time_scales"]["dt_auto_variational"];
  // (the run takes t_end / ceil(t_end / auto): auto in [dt, dt / (1 - dt / t_end)))
  BOOST_TEST(dt[1] <= reported * (1 + 1e-12));
  BOOST_TEST(reported < dt[1] / (1.0 - dt[1] / 0.05));
  expect_bad_input(box, "dynamic " + scene + " --grid corrected --set rod.model=kirchhoff "
                        "--t-end 0.01 --out a.json",
                   {"solver.grid", "cosserat"});
}

BOOST_AUTO_TEST_CASE(unknown_scheme_lists_the_valid_ones_for_the_command) {
  Sandbox box;
  const std::string scene = quote(kScene);
  const Run s = box.run("static " + scene + " --scheme simpson");
  BOOST_TEST(s.status == 2);
  BOOST_TEST(contains(s.err, "simpson"));
  BOOST_TEST(contains(s.err, rodlab::solvers::scheme_names(rodlab::solvers::Problem::statics)));
  BOOST_TEST(!contains(s.err, "variational"));

  const Run d = box.run("dynamic " + scene + " --scheme simpson");
  BOOST_TEST(d.status == 2);
  BOOST_TEST(contains(d.err, rodlab::solvers::scheme_names(rodlab::solvers::Problem::dynamics)));
  BOOST_TEST(box.files().empty());
}

BOOST_AUTO_TEST_CASE(a_scheme_of_the_other_problem_class_is_refused) {
  Sandbox box;
  const std::string scene = quote(kScene);
  expect_bad_input(box, "static " + scene + " --scheme variational",
                   {"'variational' is a dynamics scheme"});
  expect_bad_input(box, "dynamic " + scene + " --scheme kinsol", {"'kinsol' is a statics scheme"});
  // From the scene itself when --scheme does not replace it.
  expect_bad_input(box, "static " + scene + " --set solver.scheme=ida",
                   {"solver.scheme", "'ida' is a dynamics scheme"});
}

BOOST_AUTO_TEST_CASE(bad_overrides_name_the_field) {
  Sandbox box;
  const std::string scene = quote(kScene);
  expect_bad_input(box, "check " + scene + " --set rod.material.E=-5",
                   {"rod.material.E", "must be > 0", "-5"});
  expect_bad_input(box, "static " + scene + " --set rod.material.E=-5 --out r.json",
                   {"rod.material.E"});
  expect_bad_input(box, "check " + scene + " --set rod.material.E", {"--set", "rod.material.E"});
  expect_bad_input(box, "check " + scene + " --set rod.colour=red", {"rod.colour"});
}

BOOST_AUTO_TEST_CASE(a_bad_scene_reports_file_line_column_field_and_writes_nothing) {
  Sandbox box;
  const std::string text =
      "schema: rodlab.scene/1\n"
      "name: bad\n"
      "rod:\n"
      "  model: cosserat\n"
      "  length: 0.1\n"
      "  section: {shape: circle, diameter: 0.01}\n"
      "  material:\n"
      "    E: -1\n"
      "    G: 0.33e6\n"
      "    rho: 1000\n"
      "tip:\n"
      "  free: {}\n";
  box.write("bad.yaml", text);
  // Where "-1" is: line 8, column 8.
  const std::string expected = "bad.yaml:8:8: rod.material.E: must be > 0 (got -1)";
  expect_bad_input(box, "check bad.yaml", {expected});
  expect_bad_input(box, "static bad.yaml --out r.json", {expected});
  expect_bad_input(box, "dynamic bad.yaml --out r.csv --t-end 1", {expected});
  expect_bad_input(box, "check missing.yaml", {"missing.yaml"});
}

// A rest strain over spans (issue #18): `rodlab static` solves it (tests/statics/
// test_constant_strain.cpp "rest_strain_spans" holds every scheme to the closed form), and so
// does `rodlab dynamic` with every scheme when every span begins on a node (tests/dynamics/
// test_pre_curved_at_rest.cpp); a grid that misses a span's begin is refused where the scene
// gives the spans, with exit status 2 and nothing written.
BOOST_AUTO_TEST_CASE(rest_strain_spans_solve_and_a_grid_off_them_is_refused) {
  Sandbox box;
  box.write("spans.yaml",
            "schema: rodlab.scene/1\n"
            "rod:\n"
            "  length: 0.1\n"
            "  section: {shape: circle, diameter: 0.01}\n"
            "  material: {E: 1.0e6, G: 0.33e6, rho: 1000}\n"
            "  rest_strain:\n"
            "    spans:\n"
            "      - {length: 0.04, strain: [0, 0, 0, 0, 0, 1]}\n"
            "      - {length: 0.06, arc: {radius: 0.1}}\n"
            "tip: {free: {}}\n");
  const auto s = box.run("static spans.yaml --out r.json");
  BOOST_TEST(s.status == 0, s.out);
  const Json j = Json::parse(read(box.work / "r.json"));
  // The rest shape: 4 cm straight, then 6 cm of an arc of radius 0.1 m about x.
  const auto tip = j["centerline"].back()["position"];
  const double a = 0.6;  // 0.06 m / 0.1 m
  BOOST_TEST(std::abs(tip[1].get<double>() - 0.1 * (std::cos(a) - 1.0)) <= 1e-12);
  BOOST_TEST(std::abs(tip[2].get<double>() - (0.04 + 0.1 * std::sin(a))) <= 1e-12);
  // the default grid misses s = 0.04 m
  expect_bad_input(box, "dynamic spans.yaml --t-end 0.01 --out d.json",
                   {"spans.yaml:8:7: rod.rest_strain.spans: the span that begins at s = 0.04 m "
                    "does not begin on a node of variational's"});
  expect_bad_input(box, "dynamic spans.yaml --scheme ida --nodes 12 --t-end 0.01 --out d.json",
                   {"spans.yaml:8:7: rod.rest_strain.spans: the span that begins at s = 0.04 m "
                    "does not begin on a node"});
  for (const char* scheme : {"ida", "variational", "implicit-midpoint"}) {
    const auto d = box.run(std::string("dynamic spans.yaml --scheme ") + scheme +
                           " --nodes 11 --t-end 0.01 --out d.json");
    BOOST_TEST(d.status == 0, scheme << ": " << d.err);
  }
}

// --- schemes --------------------------------------------------------------------------------

BOOST_AUTO_TEST_CASE(schemes_lists_all_twelve) {
  Sandbox box;
  const Run r = box.run("schemes");
  BOOST_TEST(r.status == 0);
  BOOST_TEST(rodlab::solvers::all_schemes().size() == 12u);
  for (const auto& s : rodlab::solvers::all_schemes()) {
    BOOST_TEST(contains(r.out, std::string(s.name) + " "), s.name);
    BOOST_TEST(contains(r.out, std::string(s.method)));
  }
  BOOST_TEST(contains(r.out, "statics"));
  BOOST_TEST(contains(r.out, "dynamics"));
  BOOST_TEST(contains(r.out, "implicit"));
  BOOST_TEST(contains(r.out, "explicit"));
}

// --- input checked before anything runs -----------------------------------------------------

BOOST_AUTO_TEST_CASE(unfinished_subcommands_check_their_input_first) {
  Sandbox box;
  const std::string scene = quote(kScene);
  expect_bad_input(box, "study convergence " + scene + " --jobs 0", {"--jobs"});
  expect_bad_input(box, "study sideways " + scene, {"sideways", "convergence, work-precision"});
  expect_bad_input(box, "study convergence " + scene + " --schemes chebyshev,variational",
                   {"--schemes", "variational"});
  expect_bad_input(box, "study convergence " + scene + " --reference ode45",
                   {"--reference", "ode45"});
  expect_bad_input(box, "workspace " + scene, {"--samples", "required"});
  expect_bad_input(box, "workspace " + scene + " --samples 1", {"--samples"});
  const Run study = box.run("study convergence " + scene + " --nodes 5,10,20 --out study");
  BOOST_TEST((study.status != 2 || contains(study.err, "not available yet")), study.err);
}

// --- validate -------------------------------------------------------------------------------

// The scene family only (the whole quick suite takes minutes: tests/cli/test_validate.cpp,
// label validation); without figures (the writers are tested in test_validation_report.cpp).
BOOST_AUTO_TEST_CASE(validate_writes_a_report_with_checks_for_every_scene) {
  Sandbox box;
  const Run r = box.run("validate --quick --only scenes --no-figures --out report");
  BOOST_TEST_CONTEXT(r.out << r.err) { BOOST_TEST(r.status == 0); }
  BOOST_TEST(contains(r.out, " passed, 0 failed"));
  BOOST_REQUIRE(fs::exists(box.work / "report" / "report.json"));
  BOOST_REQUIRE(fs::exists(box.work / "report" / "report.md"));
  BOOST_TEST((box.files() == std::set<std::string>{"report", "report/report.json",
                                                    "report/report.md", "report/index.html",
                                                    "report/data", "report/figures"}));

  const Json j = Json::parse(read(box.work / "report" / "report.json"));
  BOOST_TEST(j["schema"] == "rodlab.validation-report/1");
  BOOST_TEST(j["summary"]["failed"].get<int>() == 0);
  BOOST_TEST(j["provenance"].contains("git_commit"));
  BOOST_TEST(j["provenance"]["command_line"] ==
             "rodlab validate --quick --only scenes --no-figures --out report");
  BOOST_TEST(j["figures"]["state"] == "skipped");
  BOOST_TEST(j["provenance"]["libraries"].contains("Eigen"));
  for (const auto& c : j["checks"]) {
    BOOST_TEST(c.contains("name"));
    BOOST_TEST(c.contains("measured"));
    BOOST_TEST(c.contains("tolerance"));
    BOOST_TEST(c["reference"].is_string());
    BOOST_TEST(c["passed"].get<bool>());
  }
  for (const auto& e : fs::directory_iterator(RODLAB_SOURCE_DIR "/scenes")) {
    if (e.path().extension() != ".yaml") continue;
    const std::string stem = e.path().stem().string();
    int n = 0;
    for (const auto& c : j["checks"]) {
      const std::string name = c["name"];
      n += name == "scene " + stem + " loads" || name.rfind(stem + ": ", 0) == 0;
    }
    BOOST_TEST(n >= 2, stem << " has " << n << " checks");
  }
  BOOST_TEST(contains(read(box.work / "report" / "report.md"), "| pass |"));
}

BOOST_AUTO_TEST_CASE(validate_fails_on_a_bad_scene) {
  Sandbox box;
  fs::create_directory(box.work / "scenes");
  box.write("scenes/broken.yaml", "schema: rodlab.scene/1\nname: broken\n");
  const Run r = box.run("validate --only scenes --no-figures --scenes scenes --out out");
  BOOST_TEST(r.status == 1);
  // Exactly one failure: the broken scene.
  BOOST_TEST(contains(r.out, " passed, 1 failed"));
  BOOST_TEST(contains(r.out, "scene broken loads"));
  BOOST_TEST(fs::exists(box.work / "out" / "report.json"));
}

BOOST_AUTO_TEST_CASE(validate_usage_errors_write_nothing) {
  Sandbox box;
  expect_bad_input(box, "validate --quick --full --out out", {"--quick", "--full"});
  expect_bad_input(box, "validate --scenes nowhere --out out", {"--scenes", "nowhere"});
  box.write("file", "x");
  expect_bad_input(box, "validate --out file", {"--out", "not a directory"});
  expect_bad_input(box, "validate --only scenes,nope --out out", {"--only", "nope", "statics"});
}
