// rodlab-test-labels: validation
#define BOOST_TEST_MODULE cli_validate
#include <boost/test/unit_test.hpp>

// `rodlab validate --quick --out DIR` as `make validate` runs it (a few minutes, hence the
// validation label): exit status 0; at least 20 checks over the scenes, statics, dynamics and
// studies families, all passed (the studies: a recommendation for a statics and a dynamics
// tolerance, two Pareto fronts); every data set's CSV and (with python3-matplotlib) every
// figure exists; index.html names every check and embeds every figure with its caption (the
// work-precision diagrams and the stability map among them); report.json has the provenance;
// the summary line printed equals report.json's. Then a run with an interpreter that does not
// exist still writes the whole report, says the figures are unavailable, and exits
// with the checks' status (family scenes only, to keep it short).

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"
#include "report/report.hpp"

namespace fs = std::filesystem;
using Json = nlohmann::json;

namespace {

using rodlab::testing::cli::contains;
using rodlab::testing::cli::read;

struct Run {
  int status = -1;
  std::string out;
};

struct Box {
  fs::path root;
  Box() {
    root = fs::temp_directory_path() / ("rodlab-validate-" + std::to_string(::getpid()));
    fs::remove_all(root);
    fs::create_directories(root);
  }
  ~Box() { fs::remove_all(root); }
  Run run(const std::string& env, const std::string& args) const {
    const fs::path out = root / "stdout.txt";
    const std::string command = "cd '" + root.string() + "' && " + env + " '" RODLAB_BINARY "' " +
                                args + " >'" + out.string() + "' 2>&1";
    const int raw = std::system(command.c_str());
    return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read(out)};
  }
};

/// python3 on PATH or Debian's /usr/bin/python3 can import matplotlib (what rodlab tries).
bool have_matplotlib() {
  return std::system("python3 -c 'import matplotlib, numpy' >/dev/null 2>&1") == 0 ||
         std::system("/usr/bin/python3 -c 'import matplotlib, numpy' >/dev/null 2>&1") == 0;
}

}  // namespace

BOOST_AUTO_TEST_CASE(quick_suite_writes_the_whole_report) {
  Box box;
  const Run r = box.run("", "validate --quick --out report");
  BOOST_TEST_MESSAGE(r.out);
  BOOST_TEST(r.status == 0, r.out);
  const fs::path dir = box.root / "report";
  for (const char* f : {"index.html", "report.json", "report.md"})
    BOOST_REQUIRE_MESSAGE(fs::is_regular_file(dir / f), f);
  const Json j = Json::parse(read(dir / "report.json"));
  BOOST_TEST(j["schema"] == "rodlab.validation-report/1");
  BOOST_TEST(j["mode"] == "quick");
  BOOST_TEST(j["checks"].size() >= 20u);
  BOOST_TEST(j["summary"]["failed"] == 0);
  const std::string summary = std::to_string(j["summary"]["passed"].get<int>()) + " passed, 0 failed";
  BOOST_TEST(contains(r.out, summary), "printed: " << r.out);
  std::set<std::string> families;
  for (const auto& c : j["checks"]) families.insert(c["family"].get<std::string>());
  BOOST_TEST((families == std::set<std::string>{"scenes", "statics", "dynamics", "literature",
                                                "studies", "control", "learning", "extremes"}));
  // The studies family: recommend answers for a statics and a dynamics tolerance, the front.
  int statics_recommends = 0, dynamics_recommends = 0, fronts = 0;
  for (const auto& c : j["checks"]) {
    if (c["family"] != "studies") continue;
    const std::string name = c["name"];
    if (contains(name, "recommended run, re-run")) {
      (contains(name, "statics") ? statics_recommends : dynamics_recommends) += 1;
      BOOST_TEST(contains(c["detail"].get<std::string>(), "recommendation: "), name);
    }
    if (contains(name, "Pareto front non-empty")) ++fronts;
  }
  BOOST_TEST(statics_recommends >= 1);
  BOOST_TEST(dynamics_recommends >= 1);
  BOOST_TEST(fronts == 2);
  for (const char* key : rodlab::validation::kProvenanceKeys) BOOST_TEST(j["provenance"].contains(key), key);

  const std::string html = read(dir / "index.html");
  for (const auto& c : j["checks"]) {
    const std::string name = c["name"];
    BOOST_TEST(contains(html, rodlab::validation::html_escape(name)), name);
  }
  const bool figures = have_matplotlib();
  BOOST_TEST(j["figures"]["state"] == (figures ? "generated" : "unavailable"),
             j["figures"]["message"]);
  int n_figures = 0;
  for (const auto& d : j["data_sets"]) {
    BOOST_TEST(fs::is_regular_file(dir / d["file"].get<std::string>()), d["file"]);
    const std::string csv = read(dir / d["file"].get<std::string>());
    BOOST_TEST(csv.size() > 0u);
    for (const auto& f : d["figures"]) {
      ++n_figures;
      BOOST_TEST(contains(html, rodlab::validation::html_escape(f["caption"].get<std::string>())),
                 f["name"]);
      if (!figures) continue;
      const std::string svg = read(dir / f["file"].get<std::string>());
      BOOST_TEST(contains(svg, "<svg"), f["file"]);
      BOOST_TEST(contains(html, "data:image/svg+xml;base64," + rodlab::validation::base64(svg)),
                 f["file"] << " embedded");
    }
  }
  // The figures a reader expects: shapes, convergence, tips, energy, det, stability,
  // work-precision diagrams and the stability map.
  BOOST_TEST(n_figures >= 11);
  for (const char* f : {"studies_wp_statics", "studies_wp_dynamics", "studies_joint_convergence",
                        "studies_stability_map"})
    BOOST_TEST(contains(html, std::string("id=\"figure-") + f + "\""), f);
  BOOST_TEST(!contains(html, " missing (figures"));
  BOOST_TEST(contains(read(dir / "report.md"), "](figures/statics_shapes.svg)"));
}

BOOST_AUTO_TEST_CASE(without_python_the_report_is_still_written) {
  Box box;
  const Run r = box.run("RODLAB_PYTHON=/nonexistent/python3",
                        "validate --only scenes,statics --out report");
  BOOST_TEST(r.status == 0, r.out);
  BOOST_TEST(contains(r.out, "figures unavailable"), r.out);
  const fs::path dir = box.root / "report";
  const Json j = Json::parse(read(dir / "report.json"));
  BOOST_TEST(j["figures"]["state"] == "unavailable");
  BOOST_TEST(fs::is_regular_file(dir / "data" / "statics_shapes.csv"));
  BOOST_TEST(contains(read(dir / "index.html"), "figures/statics_shapes.svg missing"));
}
