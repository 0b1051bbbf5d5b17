#define BOOST_TEST_MODULE validation_report
#include <boost/test/unit_test.hpp>

// The writers of the validation report (apps/rodlab/validation_report.hpp,
// validation_figures.hpp) on a hand-made ValidationReport, without running the suite:
// index.html names every check and embeds every figure (or says it is missing), report.json
// parses and has every provenance key, report.md links the figures, the CSV writer quotes
// labels, and the figure script's failures (no interpreter, no matplotlib, a crash, a missing
// figure) are reported as such. References: the report's own input (every name must appear),
// RFC 4648 test vectors for base64.

#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "report/figures.hpp"
#include "cli_support.hpp"
#include "report/report.hpp"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using namespace rodlab::validation;

namespace {

using rodlab::testing::cli::contains;
using rodlab::testing::cli::read;

struct TempDir {
  fs::path path;
  TempDir() {
    static int n = 0;
    path = fs::temp_directory_path() /
           ("rodlab-report-" + std::to_string(::getpid()) + "-" + std::to_string(n++));
    fs::remove_all(path);
    fs::create_directories(path / "figures");
    fs::create_directories(path / "data");
  }
  ~TempDir() { fs::remove_all(path); }
};

/// Two families, three checks (one failed, one with HTML/Markdown specials), one data set with
/// two figures.
ValidationReport hand_made() {
  ValidationReport r;
  r.mode = "quick";
  r.scenes_dir = "/somewhere/scenes";
  r.families = {{"alpha", "the first family"}, {"beta", "the second family"}};
  r.provenance = collect_provenance(RODLAB_SOURCE_DIR, "rodlab validate --quick --out x");
  Check a = relative_check("alpha: K[0] = E pi D^4/64", 1.0, 1.0, 1e-12, "closed form");
  a.family = "alpha";
  Check b = upper_bound_check("alpha: error <= 1e-3 | with <html> & specials", 2e-3, 1e-3,
                              "a <reference> & more");
  b.family = "alpha";
  Check c = boolean_check("beta: converges", true, "thesis 2.7.2");
  c.family = "beta";
  r.checks = {a, b, c};
  DataSet d;
  d.name = "beta_convergence";
  d.family = "beta";
  d.description = "errors";
  d.columns = {"scheme", "N", "error"};
  d.add_row({"rk4", 11, 1e-6});
  d.add_row({"rk4", 21, 6.25e-8});
  d.add_row({"a, \"quoted\" one", 11, 1e-3});
  FigureSpec f1;
  f1.name = "beta_convergence";
  f1.kind = "loglog";
  f1.x = "N";
  f1.y = {"error"};
  f1.series = "scheme";
  f1.title = "Convergence of beta";
  f1.caption = "Caption of the convergence figure.";
  f1.reference_slopes = {-4.0};
  FigureSpec f2 = f1;
  f2.name = "beta_second";
  f2.kind = "line";
  f2.title = "Second figure";
  f2.caption = "Caption of the second figure.";
  d.figures = {f1, f2};
  r.data_sets = {d};
  r.figures.state = "generated";
  r.figures.command = "python3 make_figures.py x";
  return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(base64_rfc4648_vectors) {
  BOOST_TEST(base64("") == "");
  BOOST_TEST(base64("f") == "Zg==");
  BOOST_TEST(base64("fo") == "Zm8=");
  BOOST_TEST(base64("foo") == "Zm9v");
  BOOST_TEST(base64("foob") == "Zm9vYg==");
  BOOST_TEST(base64("fooba") == "Zm9vYmE=");
  BOOST_TEST(base64("foobar") == "Zm9vYmFy");
  BOOST_TEST(base64(std::string("\xff\x00\x80", 3)) == "/wCA");
}

BOOST_AUTO_TEST_CASE(check_constructors) {
  const Check lo = upper_bound_check("x", 0.5, 1.0, "r");
  BOOST_TEST(lo.passed);
  BOOST_TEST(!upper_bound_check("x", 1.5, 1.0, "r").passed);
  BOOST_TEST(!upper_bound_check("x", NAN, 1.0, "r").passed);
  BOOST_TEST(range_check("x", 1.0, 0.95, 1.05, "r").passed);
  BOOST_TEST(!range_check("x", 0.9, 0.95, 1.05, "r").passed);
  BOOST_TEST(!range_check("x", NAN, 0.95, 1.05, "r").passed);
}

BOOST_AUTO_TEST_CASE(csv_has_a_header_and_quotes_labels) {
  const auto r = hand_made();
  const std::string csv = r.data_sets[0].to_csv();
  BOOST_TEST(csv == "scheme,N,error\nrk4,11,9.9999999999999995e-07\nrk4,21,6.2499999999999997e-08\n"
                    "\"a, \"\"quoted\"\" one\",11,0.001\n");
  DataSet d = r.data_sets[0];
  BOOST_CHECK_THROW(d.add_row({1.0, 2.0}), std::logic_error);
}

BOOST_AUTO_TEST_CASE(json_parses_with_provenance_checks_data_and_figures) {
  const auto r = hand_made();
  const Json j = Json::parse(to_json(r));
  BOOST_TEST(j["schema"] == "rodlab.validation-report/1");
  BOOST_TEST(j["summary"]["checks"] == 3);
  BOOST_TEST(j["summary"]["failed"] == 1);
  for (const char* key : kProvenanceKeys) BOOST_TEST(j["provenance"].contains(key), key);
  for (const char* lib : {"Eigen", "SUNDIALS", "SuiteSparse", "GSL", "yaml-cpp", "Boost"}) {
    BOOST_TEST(j["provenance"]["libraries"].contains(lib), lib);
    BOOST_TEST(j["provenance"]["libraries"][lib] != "unknown", lib);
  }
  BOOST_TEST(j["provenance"]["cpu"] != "");
  BOOST_TEST(j["provenance"]["os"] != "");
  BOOST_TEST(j["provenance"]["command_line"] == "rodlab validate --quick --out x");
  BOOST_TEST(j["checks"].size() == 3u);
  BOOST_TEST(j["checks"][1]["passed"] == false);
  BOOST_TEST(j["families"].size() == 2u);
  BOOST_TEST(j["families"][0]["checks"] == 2);
  BOOST_TEST(j["data_sets"][0]["file"] == "data/beta_convergence.csv");
  BOOST_TEST(j["data_sets"][0]["figures"][0]["file"] == "figures/beta_convergence.svg");
  BOOST_TEST(j["data_sets"][0]["figures"][0]["reference_slopes"][0] == -4.0);
  BOOST_TEST(j["figures"]["files"].size() == 2u);
  BOOST_TEST(j["figures"]["state"] == "generated");
}

BOOST_AUTO_TEST_CASE(html_has_every_check_and_embeds_every_figure) {
  TempDir dir;
  const auto r = hand_made();
  const std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\"><text>fig one</text></svg>";
  std::ofstream(dir.path / "figures" / "beta_convergence.svg") << svg;
  // beta_second.svg is missing: the page must say so.
  const std::string html = to_html(r, dir.path);
  for (const auto& c : r.checks) BOOST_TEST(contains(html, html_escape(c.name)), c.name);
  BOOST_TEST(contains(html, "&lt;html&gt; &amp; specials"));
  BOOST_TEST(!contains(html, "<html> & specials"));
  BOOST_TEST(contains(html, "data:image/svg+xml;base64," + base64(svg)));
  BOOST_TEST(contains(html, "Caption of the convergence figure."));
  BOOST_TEST(contains(html, "Caption of the second figure."));
  BOOST_TEST(contains(html, "figures/beta_second.svg missing"));
  BOOST_TEST(contains(html, "the first family"));
  BOOST_TEST(contains(html, "2 passed, 1 failed"));
  BOOST_TEST(contains(html, "<style>"));
  BOOST_TEST(!contains(html, "<link"));  // self-contained: no external style sheet
  BOOST_TEST(contains(html, html_escape(r.provenance.git_commit)));
  BOOST_TEST(contains(html, "SUNDIALS"));
}

// A data set's table (the control study's Table 4.1) is shown as is in report.md and, escaped,
// in index.html; figures.json lists the same data sets as report.json for make_figures.py.
BOOST_AUTO_TEST_CASE(a_data_set_table_is_shown) {
  TempDir dir;
  auto r = hand_made();
  r.data_sets[0].table = "| H = 1 | a <b> |\n|---|---|\n| row | 10/10 |\n";
  BOOST_TEST(contains(to_markdown(r), r.data_sets[0].table));
  BOOST_TEST(contains(to_html(r, dir.path), "<pre>| H = 1 | a &lt;b&gt; |"));
  const auto index = nlohmann::json::parse(figure_index_json(r.data_sets));
  const auto report = nlohmann::json::parse(to_json(r));
  BOOST_TEST(index["schema"] == "rodlab.figures/1");
  BOOST_TEST(index["data_sets"] == report["data_sets"]);
}

BOOST_AUTO_TEST_CASE(markdown_has_every_check_and_links_every_figure) {
  const auto r = hand_made();
  const std::string md = to_markdown(r);
  BOOST_TEST(contains(md, "alpha: K[0] = E pi D^4/64"));
  BOOST_TEST(contains(md, "with <html> & specials"));
  BOOST_TEST(contains(md, "\\|"));  // the '|' of a check name is escaped
  BOOST_TEST(contains(md, "beta: converges"));
  BOOST_TEST(contains(md, "](figures/beta_convergence.svg)"));
  BOOST_TEST(contains(md, "](figures/beta_second.svg)"));
  BOOST_TEST(contains(md, "**FAIL**"));
  BOOST_TEST(contains(md, "| CPU |"));
}

namespace {

/// A fake interpreter script: `sh SCRIPT DIR` runs `body` with $1 = DIR.
fs::path script(const TempDir& dir, const std::string& name, const std::string& body) {
  const fs::path p = dir.path / name;
  std::ofstream(p) << body;
  return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(figure_script_failures_are_reported) {
  TempDir dir;
  const auto r = hand_made();
  // No interpreter.
  auto s = run_figure_script(r, "/nonexistent/python3", script(dir, "ok.sh", "exit 0\n"), dir.path);
  BOOST_TEST(s.state == "unavailable");
  BOOST_TEST(contains(s.message, "not found"), s.message);
  // No script.
  s = run_figure_script(r, "sh", dir.path / "none.py", dir.path);
  BOOST_TEST(s.state == "unavailable");
  // matplotlib missing: the script's exit status 3.
  s = run_figure_script(r, "sh",
                        script(dir, "nompl.sh", "echo 'cannot import matplotlib'\nexit 3\n"),
                        dir.path);
  BOOST_TEST(s.state == "unavailable");
  BOOST_TEST(contains(s.message, "python3-matplotlib"), s.message);
  // A crash: the tail of its output.
  s = run_figure_script(r, "sh", script(dir, "crash.sh", "echo Traceback boom >&2\nexit 1\n"),
                        dir.path);
  BOOST_TEST(s.state == "failed");
  BOOST_TEST(contains(s.message, "Traceback boom"), s.message);
  // Exit 0 but a figure is missing.
  s = run_figure_script(
      r, "sh", script(dir, "half.sh", "echo '<svg/>' > \"$1/figures/beta_convergence.svg\"\n"),
      dir.path);
  BOOST_TEST(s.state == "failed");
  BOOST_TEST(contains(s.message, "beta_second"), s.message);
  // Success: both figures, and the versions line.
  s = run_figure_script(r, "sh",
                        script(dir, "good.sh",
                               "echo 'rodlab-figures: fakeplot 1.0'\n"
                               "echo '<svg/>' > \"$1/figures/beta_convergence.svg\"\n"
                               "echo '<svg/>' > \"$1/figures/beta_second.svg\"\n"),
                        dir.path);
  BOOST_TEST(s.state == "generated");
  BOOST_TEST(s.message == "fakeplot 1.0");
  // A failed run removes stale figures first.
  s = run_figure_script(r, "sh", script(dir, "fail.sh", "exit 1\n"), dir.path);
  BOOST_TEST(!fs::exists(dir.path / "figures" / "beta_convergence.svg"));
  const std::string html = to_html([&] {
    auto copy = r;
    copy.figures = s;
    return copy;
  }(), dir.path);
  BOOST_TEST(contains(html, "figures/beta_convergence.svg missing (figures failed"));
}

BOOST_AUTO_TEST_CASE(the_first_usable_interpreter_runs_the_script) {
  // figure_pythons() may list PATH's python3 without matplotlib before Debian's with it
  // (`rodlab plot` and `rodlab validate` both go by this): an unusable one is skipped, and
  // nothing of it is reported once a usable one has run.
  TempDir dir;
  const fs::path echo = script(dir, "echo.sh", "echo \"$@\"\n");
  std::string unavailable = "stale";
  auto run = run_python_script({"/nonexistent/python3", "sh"}, echo, {"a b", "c"}, unavailable);
  BOOST_TEST(unavailable.empty(), unavailable);
  BOOST_TEST(run.exit_code == 0);
  BOOST_TEST(run.output == "a b c\n");  // each argument quoted: "a b" stays one
  const fs::path nompl = script(dir, "nompl.sh", "echo 'cannot import matplotlib'\nexit 3\n");
  run = run_python_script({"sh", "/nonexistent/python3"}, nompl, {}, unavailable);
  BOOST_TEST(contains(unavailable, "sh: cannot import matplotlib"), unavailable);
  BOOST_TEST(contains(unavailable, "; /nonexistent/python3: /nonexistent/python3 not found"),
             unavailable);
  // A failure that is not about the interpreter ends the search.
  run = run_python_script({"sh", "/nonexistent/python3"}, script(dir, "boom.sh", "exit 1\n"), {},
                          unavailable);
  BOOST_TEST(unavailable.empty(), unavailable);
  BOOST_TEST(run.exit_code == 1);
  const auto s = run_figure_script(hand_made(), std::vector<std::string>{"/nonexistent/py", "sh"},
                                   script(dir, "fail.sh", "exit 1\n"), dir.path);
  BOOST_TEST(s.state == "failed");
  BOOST_TEST(contains(s.command, "sh "), s.command);
}

BOOST_AUTO_TEST_CASE(make_figures_script_draws_a_hand_made_report) {
  // The real validation/make_figures.py, when python3 with matplotlib is installed (the
  // bootstrap installs python3-matplotlib; elsewhere this case only checks the report writers).
  std::string python;
  for (const char* p : {"python3", "/usr/bin/python3"})
    if (python.empty() &&
        std::system((std::string(p) + " -c 'import matplotlib, numpy' >/dev/null 2>&1").c_str()) == 0)
      python = p;
  if (python.empty()) {
    BOOST_TEST_MESSAGE("python3 with matplotlib not found: make_figures.py not exercised");
    return;
  }
  TempDir dir;
  auto r = hand_made();
  for (const auto& d : r.data_sets) std::ofstream(dir.path / data_file(d)) << d.to_csv();
  std::ofstream(dir.path / "report.json") << to_json(r);
  const auto s = run_figure_script(r, python, RODLAB_SOURCE_DIR "/validation/make_figures.py",
                                   dir.path);
  BOOST_TEST(s.state == "generated", s.message);
  BOOST_TEST(contains(s.message, "matplotlib"), s.message);
  for (const auto& f : r.data_sets[0].figures) {
    const std::string svg = read(dir.path / figure_file(f));
    BOOST_TEST(contains(svg, "<svg"), f.name);
    BOOST_TEST(contains(svg, f.title), f.name);  // svg.fonttype none: titles stay text
  }
}
