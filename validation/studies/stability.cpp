#include "studies/stability.hpp"
#include "studies/stable_step.hpp"

#include <cmath>

#include "rodlab/io/text_format.hpp"
#include "rodlab/io/text_table.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

#include "studies/runs.hpp"

namespace rodlab::validation::study {
namespace {

using solvers::Problem;

scene::Scene with_modulus(const scene::Scene& scene, double E) {
  scene::Scene out = scene;
  const double ratio = E / scene.rod.material.E;
  out.rod.material.E = E;
  out.rod.material.G *= ratio;
  return out;
}

ExplicitLimit bisect_limit(const Settings& s, const std::string& scheme, double E, int nodes) {
  ExplicitLimit out;
  out.scheme = scheme;
  out.E = E;
  out.nodes = nodes;
  const scene::Scene sc = with_modulus(s.scene, E);
  const auto problem = solvers::dynamics::DynamicProblem::from_scene(sc);
  out.dt_linear = solvers::dynamics::variational_stable_step(problem, nodes);
  auto stable = [&](double dt) {
    RunSpec spec{scheme, Problem::dynamics, nodes, dt, static_cast<double>(kExplicitSteps) * dt,
                 s.tol, 1, false};
    const auto r = run_case(sc, spec);
    ++out.runs;
    out.wall_time_s += r.wall_time_s;
    return r.converged;
  };
  double lo = 0.5 * out.dt_linear, hi = 2.0 * out.dt_linear;
  while (!stable(lo)) {
    hi = lo;
    lo /= 2.0;
    if (lo < out.dt_linear / 64.0) {
      out.dt_unstable = hi;
      out.note = "unstable down to dt_linear / 32";
      return out;
    }
  }
  while (stable(hi)) {
    lo = hi;
    hi *= 2.0;
    if (hi > 64.0 * out.dt_linear) {
      out.dt_max = lo;
      out.note = "stable up to 32 dt_linear";
      return out;
    }
  }
  const StepBracket b = bisect_stable_step(stable, lo, hi, kBisectionRatio);
  out.dt_max = b.stable;
  out.dt_unstable = b.unstable;
  return out;
}

Json limit_json(const ExplicitLimit& l) {
  return {{"scheme", l.scheme},          {"E", l.E},           {"nodes", l.nodes},
          {"dt_linear", l.dt_linear},    {"dt_max", l.dt_max}, {"dt_unstable", l.dt_unstable},
          {"runs", l.runs},              {"wall_time_s", l.wall_time_s}, {"note", l.note}};
}

ExplicitLimit limit_from_json(const Json& j) {
  ExplicitLimit l;
  if (j.contains("error")) {
    l.note = "internal error: " + j["error"].get<std::string>();
    return l;
  }
  l.scheme = j["scheme"];
  l.E = j["E"];
  l.nodes = j["nodes"];
  l.dt_linear = j["dt_linear"];
  l.dt_max = j["dt_max"];
  l.dt_unstable = j["dt_unstable"];
  l.runs = j["runs"];
  l.wall_time_s = j["wall_time_s"];
  l.note = j["note"];
  return l;
}

Json scan(const Settings& s, const std::string& scheme, int nodes) {
  const auto problem = solvers::dynamics::DynamicProblem::from_scene(s.scene);
  const double dt_auto = solvers::dynamics::auto_time_step(problem, scheme, nodes);
  Json points = Json::array();
  auto run = [&](double dt, const char* direction) {
    const double t_run = std::min(s.t_end, static_cast<double>(kScanSteps) * dt);
    RunSpec spec{scheme, Problem::dynamics, nodes, dt, t_run, s.tol, 1, false};
    const auto r = run_case(s.scene, spec);
    points.push_back({{"scheme", scheme},
                      {"nodes", nodes},
                      {"dt_auto", dt_auto},
                      {"dt", dt},
                      {"direction", direction},
                      {"converged", r.converged},
                      {"reason", r.reason},
                      {"t_run", t_run},
                      {"steps", r.steps},
                      {"wall_time_s", r.wall_time_s}});
    return r.converged;
  };
  for (double dt = dt_auto; dt >= kScanMin * (1 - 1e-9); dt /= kScanFactor)
    if (!run(dt, "down")) break;
  for (double dt = dt_auto * kScanFactor; dt <= kScanMax * (1 + 1e-9) && dt <= s.t_end;
       dt *= kScanFactor)
    if (!run(dt, "up")) break;
  return points;
}

}  // namespace

std::vector<double> default_moduli() { return {1e4, 1e6, 1e8}; }
std::vector<int> default_stability_nodes() { return {10, 20, 40}; }

Stability run_stability(const Settings& s, const Executor& executor) {
  const auto moduli = s.moduli.empty() ? default_moduli() : s.moduli;
  const auto nodes = s.nodes.empty() ? default_stability_nodes() : s.nodes;
  std::vector<std::function<Json()>> tasks;
  std::vector<bool> is_limit;
  for (const auto& scheme : s.schemes) {
    if (scheme.reference) continue;
    const std::string name(scheme.name);
    for (const int n : nodes) {
      if (!scheme.implicit) {
        for (const double E : moduli) {
          tasks.push_back([&s, name, E, n] { return limit_json(bisect_limit(s, name, E, n)); });
          is_limit.push_back(true);
        }
      } else {
        tasks.push_back([&s, name, n] { return scan(s, name, n); });
        is_limit.push_back(false);
      }
    }
  }
  const auto results = run_tasks(tasks, executor);
  Stability out;
  if (results.empty()) return out;
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (is_limit[i]) {
      out.limits.push_back(limit_from_json(results[i]));
      continue;
    }
    if (results[i].contains("error")) continue;
    ScanSummary sum;
    for (const auto& p : results[i]) {
      ScanPoint sp;
      sp.scheme = p["scheme"];
      sp.nodes = p["nodes"];
      sp.dt_auto = p["dt_auto"];
      sp.dt = p["dt"];
      sp.direction = p["direction"];
      sp.converged = p["converged"];
      sp.reason = p["reason"];
      sp.t_run = p["t_run"];
      sp.steps = p["steps"];
      sp.wall_time_s = p["wall_time_s"];
      sum.scheme = sp.scheme;
      sum.nodes = sp.nodes;
      sum.dt_auto = sp.dt_auto;
      if (sp.direction == "down") {
        if (sp.converged) sum.smallest_ok = sp.dt;
        else sum.first_failed_below = sp.dt;
      } else {
        if (sp.converged) sum.largest_ok = sp.dt;
        else sum.first_failed_above = sp.dt;
      }
      out.scan.push_back(std::move(sp));
    }
    if (sum.largest_ok == 0.0 && sum.smallest_ok > 0.0) sum.largest_ok = sum.dt_auto;
    if (!sum.scheme.empty()) out.summaries.push_back(sum);
  }
  return out;
}

std::string explicit_csv(const Stability& study) {
  std::string out = "scheme,E,nodes,dt_linear,dt_max,dt_unstable,safety_factor,runs,steps_per_run,"
                    "wall_time_s,note\n";
  for (const auto& l : study.limits)
    out += csv_text(l.scheme) + ',' + csv_number(l.E) + ',' + std::to_string(l.nodes) + ',' +
           csv_number(l.dt_linear) + ',' + csv_number(l.dt_max) + ',' +
           csv_number(l.dt_unstable) + ',' +
           csv_number(l.dt_max > 0 ? l.dt_max / l.dt_linear : NAN) + ',' +
           std::to_string(l.runs) + ',' + std::to_string(kExplicitSteps) + ',' +
           csv_number(l.wall_time_s) + ',' + csv_text(l.note) + '\n';
  return out;
}

std::string implicit_csv(const Stability& study) {
  std::string out = "scheme,nodes,dt_auto,dt,direction,converged,t_run,steps,wall_time_s,reason\n";
  for (const auto& p : study.scan)
    out += csv_text(p.scheme) + ',' + std::to_string(p.nodes) + ',' + csv_number(p.dt_auto) +
           ',' + csv_number(p.dt) + ',' + p.direction + ',' + (p.converged ? "true" : "false") +
           ',' + csv_number(p.t_run) + ',' + std::to_string(p.steps) + ',' +
           csv_number(p.wall_time_s) + ',' + csv_text(p.reason) + '\n';
  return out;
}

Json stability_json(const Stability& study, const Settings& settings) {
  Json limits = Json::array(), scan_points = Json::array(), summaries = Json::array();
  for (const auto& l : study.limits) {
    Json j = limit_json(l);
    j["safety_factor"] = l.dt_max > 0 ? Json(l.dt_max / l.dt_linear) : Json(nullptr);
    limits.push_back(j);
  }
  for (const auto& p : study.scan)
    scan_points.push_back({{"scheme", p.scheme},         {"nodes", p.nodes},
                           {"dt_auto", p.dt_auto},       {"dt", p.dt},
                           {"direction", p.direction},   {"converged", p.converged},
                           {"reason", p.reason},         {"t_run", p.t_run},
                           {"steps", p.steps},           {"wall_time_s", p.wall_time_s}});
  auto opt = [](double v) { return v > 0 ? Json(v) : Json(nullptr); };
  for (const auto& s : study.summaries)
    summaries.push_back({{"scheme", s.scheme},
                         {"nodes", s.nodes},
                         {"dt_auto", s.dt_auto},
                         {"smallest_ok", opt(s.smallest_ok)},
                         {"first_failed_below", opt(s.first_failed_below)},
                         {"largest_ok", opt(s.largest_ok)},
                         {"first_failed_above", opt(s.first_failed_above)}});
  Json set = settings_json(settings);
  set["moduli"] = settings.moduli.empty() ? default_moduli() : settings.moduli;
  return Json{{"schema", "rodlab.study/1"},
              {"kind", "stability"},
              {"scene", settings.scene.name},
              {"command_line", settings.command_line},
              {"settings", set},
              {"explicit",
               {{"rule", "bisection of the largest step that runs " +
                             std::to_string(kExplicitSteps) +
                             " steps without being reported unstable, to " +
                             io::format_number((kBisectionRatio - 1) * 100) + " %"},
                {"limits", limits}}},
              {"implicit",
               {{"rule", "from dt auto, divide by 3 down to 1e-6 s and multiply by 3 up to "
                         "0.1 s, each way until a run fails; runs of min(t_end, " +
                             std::to_string(kScanSteps) + " dt)"},
                {"scan", scan_points},
                {"summary", summaries}}}};
}

std::string stability_table(const Stability& study) {
  using A = io::TextTable::Align;
  std::string out;
  if (!study.limits.empty()) {
    io::TextTable t({A::left, A::right, A::right, A::right, A::right, A::right, A::right, A::left});
    t.add_row({"explicit scheme", "E [Pa]", "N", "linear limit [s]", "measured [s]",
               "ratio", "runs", "note"});
    t.add_rule();
    for (const auto& l : study.limits)
      t.add_row({l.scheme, io::format_number(l.E), std::to_string(l.nodes), io::format_number(l.dt_linear),
                 l.dt_max > 0 ? io::format_number(l.dt_max) : "-",
                 l.dt_max > 0 ? io::format_number(l.dt_max / l.dt_linear) : "-",
                 std::to_string(l.runs), l.note});
    out += t.render();
  }
  if (!study.summaries.empty()) {
    if (!out.empty()) out += '\n';
    io::TextTable t({A::left, A::right, A::right, A::right, A::right, A::right, A::right});
    t.add_row({"implicit scheme", "N", "dt auto [s]", "smallest ok [s]", "failed below [s]",
               "largest ok [s]", "failed above [s]"});
    t.add_rule();
    auto f = [](double v) { return v > 0 ? io::format_number(v) : std::string("-"); };
    for (const auto& s : study.summaries)
      t.add_row({s.scheme, std::to_string(s.nodes), io::format_number(s.dt_auto), f(s.smallest_ok),
                 f(s.first_failed_below), f(s.largest_ok), f(s.first_failed_above)});
    out += t.render();
  }
  return out;
}

}  // namespace rodlab::validation::study
