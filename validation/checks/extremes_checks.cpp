// The "extremes" family of `rodlab validate` (#13 item 4): every scheme at the extremes of
// material, mesh and step, run as `rodlab dynamic` / `rodlab static` child processes under a
// hard time limit, each case checked against the invariant of the command line:
//   exit 0: the result file says converged and every number in it is finite;
//   exit 1: the result file says not converged and gives a reason;
//   exit 2: refused before it starts (bad input, or a scheme outside its validity range),
//           a message on stderr and no result file;
//   never: a crash (a signal), another exit status, or a run past its budget (a hang).
// The rod: Table 2.1's geometry (L = 0.1 m, D = 1 cm, rho = 1000 kg/m^3, Poisson 0.3) released
// straight under gravity, E from 1e3 Pa (gravity bends it far past its length) to 2e11 Pa
// (steel); N from 2 (below the dynamics schemes' minimum) to 1000; dt from 1e-7 s (below the
// shooting schemes' lower step bound) to 1 s (far beyond the explicit scheme's limit); three
// steps per dynamics run; every run under --max-wall-time (the guard reaches inside the solvers'
// residual evaluations, common/deadline.hpp) and killed kGrace later. --quick runs a sample of
// the corners;
// --full the whole map (docs/validation.md "Extremes").
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <future>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "rodlab/io/text_format.hpp"
#include "rodlab/solvers/schemes.hpp"

#include "checks/check.hpp"
#include "studies/child_process.hpp"

namespace rodlab::validation {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using solvers::Problem;

/// Outcome codes of the map (its colour).
enum Outcome { kFinished = 0, kStopped = 1, kRefused = 2, kViolation = 3 };

struct Case {
  std::string scheme;
  Problem problem;
  double E;
  int nodes;
  double dt;  ///< dynamics only
};

struct CaseResult {
  Case c;
  Outcome outcome = kViolation;
  double wall_time_s = 0.0;
  std::string why;  ///< the reason (exit 1 or 2) or the violation
};

struct Grid {
  std::vector<double> E;
  std::vector<int> nodes;
  std::vector<double> dt;
  double budget_s;  ///< --max-wall-time of a run; the hard limit adds kGrace
};
constexpr double kGrace = 10.0;

Grid grid_of(bool full) {
  if (full) return {{1e3, 1e5, 1e7, 1e9, 2e11}, {2, 3, 10, 100, 1000}, {1e-7, 1e-5, 1e-3, 1e-1, 1.0}, 20.0};
  return {{1e3, 2e11}, {2, 20}, {1e-7, 1.0}, 5.0};
}

/// DIR/E<E>.yaml (appended, not "E" + ...: GCC 12's -Wrestrict false positive).
fs::path scene_path(const fs::path& dir, double E) {
  std::string name = "E";
  name += io::format_number(E);
  name += ".yaml";
  return dir / name;
}

std::string scene_text(double E) {
  return "schema: rodlab.scene/1\nname: extremes-E" + io::format_number(E) +
         "\nrod:\n  length: 0.1\n  section: {shape: circle, diameter: 0.01}\n"
         "  material: {E: " + io::format_number(E) + ", poisson: 0.3, rho: 1000}\n"
         "tip:\n  free: {}\nloads:\n  gravity: [-9.81, 0, 0]\n";
}

/// True when every number in the document is finite and nothing is null (a NaN is written as
/// null).
bool all_finite(const Json& j) {
  if (j.is_null()) return false;
  if (j.is_number_float()) return std::isfinite(j.get<double>());
  if (j.is_structured())
    return std::all_of(j.begin(), j.end(), [](const Json& v) { return all_finite(v); });
  return true;
}

std::vector<std::string> command_of(const Case& c, const fs::path& program, const fs::path& scene,
                                    const fs::path& result, double budget_s) {
  std::vector<std::string> argv{program.string(),
                                c.problem == Problem::dynamics ? "dynamic" : "static",
                                scene.string(), "--scheme", c.scheme, "--nodes",
                                std::to_string(c.nodes), "--out", result.string(),
                                "--max-wall-time", io::format_number(budget_s)};
  if (c.problem == Problem::dynamics)
    argv.insert(argv.end(), {"--dt", io::format_number(c.dt), "--t-end",
                             io::format_number(3.0 * c.dt)});
  return argv;
}

/// The invariant of one finished child (see the file comment).
void classify(const study::ChildOutcome& child, const fs::path& result, CaseResult& r) {
  const bool has_result = fs::exists(result);
  Json doc;
  if (has_result) {
    std::ifstream in(result);
    doc = Json::parse(in, nullptr, false);
  }
  const auto first_line = [](const std::string& s) { return s.substr(0, s.find('\n')); };
  if (child.timed_out) {
    r.why = "no answer within its budget (killed)";
  } else if (child.signal != 0) {
    r.why = "crashed with signal " + std::to_string(child.signal);
  } else if (child.exit_code == 0) {
    if (has_result && !doc.is_discarded() && doc.value("converged", false) && all_finite(doc))
      r.outcome = kFinished;
    else
      r.why = "exit 0 without a converged, finite result";
  } else if (child.exit_code == 1) {
    const bool reason = has_result && !doc.is_discarded() && !doc.value("converged", true) &&
                        doc.value("reason", std::string()).size() > 0;
    if (reason) {
      r.outcome = kStopped;
      r.why = doc["reason"].get<std::string>();
    } else {
      r.why = "exit 1 without a result that gives the reason";
    }
  } else if (child.exit_code == 2) {
    if (!has_result && !child.stderr_text.empty()) {
      r.outcome = kRefused;
      r.why = first_line(child.stderr_text);
    } else {
      r.why = has_result ? "exit 2 but a result was written" : "exit 2 without a message";
    }
  } else {
    r.why = "exit status " + std::to_string(child.exit_code);
  }
}

CaseResult run_case(const Case& c, const fs::path& program, const fs::path& dir,
                    double budget_s, int index) {
  CaseResult r;
  r.c = c;
  const fs::path scene = scene_path(dir, c.E);
  const fs::path result = dir / ("run-" + std::to_string(index) + ".json");
  const fs::path err = dir / ("run-" + std::to_string(index) + ".err");
  try {
    const auto child =
        study::run_child(command_of(c, program, scene, result, budget_s), budget_s + kGrace, err);
    r.wall_time_s = child.wall_time_s;
    classify(child, result, r);
  } catch (const std::exception& e) {
    r.why = std::string("could not run: ") + e.what();
  }
  fs::remove(result);
  fs::remove(err);
  return r;
}

std::vector<Case> cases_of(const Grid& g) {
  std::vector<Case> out;
  for (const auto& info : solvers::all_schemes())
    for (const double E : g.E)
      for (const int n : g.nodes) {
        if (info.problem == Problem::statics) {
          out.push_back({std::string(info.name), info.problem, E, n, 0.0});
          continue;
        }
        for (const double dt : g.dt) out.push_back({std::string(info.name), info.problem, E, n, dt});
      }
  return out;
}

/// Every case, two (or as many as there are cores) at a time.
std::vector<CaseResult> run_all(const std::vector<Case>& cases, const fs::path& program,
                                const fs::path& dir, double budget_s) {
  std::vector<CaseResult> out(cases.size());
  const std::size_t width = std::max(1U, std::thread::hardware_concurrency());
  for (std::size_t first = 0; first < cases.size(); first += width) {
    std::vector<std::future<CaseResult>> batch;
    for (std::size_t i = first; i < std::min(cases.size(), first + width); ++i)
      batch.push_back(std::async(std::launch::async, run_case, cases[i], program, dir, budget_s,
                                 static_cast<int>(i)));
    for (std::size_t k = 0; k < batch.size(); ++k) out[first + k] = batch[k].get();
  }
  return out;
}

std::string case_label(const Case& c) {
  std::string s = c.scheme + " E=" + io::format_number(c.E) + " N=" + std::to_string(c.nodes);
  if (c.problem == Problem::dynamics) s += " dt=" + io::format_number(c.dt);
  return s;
}

/// One check per scheme: every case keeps the invariant.
void scheme_checks(const std::vector<CaseResult>& results, double budget_s,
                   std::vector<Check>& out) {
  for (const auto& info : solvers::all_schemes()) {
    int n = 0, counts[4] = {0, 0, 0, 0};
    double slowest = 0.0;
    std::string violations;
    for (const auto& r : results) {
      if (r.c.scheme != info.name) continue;
      ++n;
      ++counts[r.outcome];
      slowest = std::max(slowest, r.wall_time_s);
      if (r.outcome == kViolation && violations.size() < 600)
        violations += "; " + case_label(r.c) + ": " + r.why;
    }
    Check c = boolean_check(
        "extremes: " + std::string(info.name) + " keeps the invariant in every case (" +
            std::to_string(n) + " cases)",
        counts[kViolation] == 0,
        "exit 0 only with a converged, finite result; exit 1 with the reason in the result; exit "
        "2 with a message and nothing written; no crash, no run past " +
            io::format_number(budget_s) + " s + " + io::format_number(kGrace) + " s");
    c.detail = std::to_string(counts[kFinished]) + " finished, " + std::to_string(counts[kStopped]) +
               " stopped with a reason, " + std::to_string(counts[kRefused]) + " refused, " +
               std::to_string(counts[kViolation]) + " violations; slowest " +
               io::format_number(slowest) + " s" + violations;
    out.push_back(std::move(c));
  }
}

DataSet map_data(const std::vector<CaseResult>& results) {
  DataSet d;
  d.name = "extremes_map";
  d.description = "every scheme at the extremes: outcome per case (0 finished, 1 stopped with a "
                  "reason, 2 refused up front, 3 violation of the invariant)";
  d.columns = {"row", "scheme", "E", "nodes", "dt", "log10_dt", "outcome", "wall_time_s", "reason"};
  for (const auto& r : results) {
    const std::string row = r.c.scheme + " E=" + io::format_number(r.c.E) + " N=" +
                            std::to_string(r.c.nodes);
    const double log_dt = r.c.problem == Problem::dynamics ? std::log10(r.c.dt) : 0.0;
    d.add_row({row, r.c.scheme, r.c.E, r.c.nodes, r.c.dt, log_dt, static_cast<int>(r.outcome),
               r.wall_time_s, r.why.substr(0, 160)});
  }
  for (const auto& info : solvers::all_schemes()) {
    const bool dynamic = info.problem == Problem::dynamics;
    FigureSpec f;
    f.name = "extremes_map_" + std::string(info.name);
    f.kind = "map";
    f.x = "log10_dt";
    f.y = {"outcome"};
    f.series = "row";
    f.select = std::string(info.name) + " ";
    f.title = "Extremes: " + std::string(info.name);
    f.xlabel = dynamic ? "log10 dt [s]" : "(statics: no time step)";
    f.ylabel = "E [Pa], N";
    f.caption = "What runs: " + std::string(info.name) +
                " on the Table 2.1 rod released under gravity, by E, N" +
                (dynamic ? " and dt (three steps)" : "") +
                ". Colour: 0 finished, 1 stopped with a reason (exit 1), 2 refused up front "
                "(exit 2), 3 a violation (crash, hang, non-finite success).";
    d.figures.push_back(std::move(f));
  }
  return d;
}

}  // namespace

std::vector<Check> extremes_checks(const ValidationContext& context) {
  const Grid g = grid_of(context.full);
  const fs::path program =
      context.program.empty() ? study::own_executable() : context.program;
  const fs::path dir =
      fs::temp_directory_path() / ("rodlab-extremes-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const double E : g.E) {
    std::ofstream(scene_path(dir, E)) << scene_text(E);
  }
  const auto results = run_all(cases_of(g), program, dir, g.budget_s);
  fs::remove_all(dir);
  std::vector<Check> out;
  scheme_checks(results, g.budget_s, out);
  context.emit(map_data(results));
  return out;
}

}  // namespace rodlab::validation
