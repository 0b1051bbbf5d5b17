#include "studies/runs.hpp"

#include <algorithm>
#include <exception>
#include <limits>

#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::validation::study {
namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void run_static(const scene::Scene& scene, const RunSpec& spec, RunRecord& out,
                std::vector<double>& times) {
  solvers::statics::StaticSolveOptions options;
  options.scheme = spec.scheme;
  options.nodes = spec.nodes;
  options.tol = spec.tol;
  options.max_iterations = std::max(scene.solver.max_iterations, 50);
  for (int r = 0; r < std::max(1, spec.repeats); ++r) {
    const auto result = solvers::statics::solve_static(scene, options);
    times.push_back(result.wall_time_s);
    out.converged = result.converged;
    out.reason = result.reason;
    if (!result.centerline.empty()) out.tip = result.centerline.back().pose.translation();
    if (result.wall_time_s > kSlowRunSeconds) break;
  }
}

void run_dynamic(const scene::Scene& scene, const RunSpec& spec, RunRecord& out,
                 std::vector<double>& times) {
  solvers::dynamics::DynamicSolveOptions options;
  options.scheme = spec.scheme;
  options.nodes = spec.nodes;
  options.dt = spec.dt;
  options.t_end = spec.t_end;
  options.output_every = 1;
  if (!spec.keep_series) options.output_every = 1 << 30;  // the last step is always recorded
  options.tol = spec.tol;
  options.max_iterations = std::max(scene.solver.max_iterations, 50);
  solvers::dynamics::apply_scene_options(scene, options);  // as `rodlab dynamic`
  for (int r = 0; r < std::max(1, spec.repeats); ++r) {
    auto result = solvers::dynamics::solve_dynamic(scene, options);
    times.push_back(result.wall_time_s);
    out.converged = result.converged;
    out.reason = result.reason;
    out.dt = result.dt;
    out.steps = result.steps;
    out.t_reached = result.t.empty() ? 0.0 : result.t.back();
    if (!result.tip_position.empty()) out.tip = result.tip_position.back();
    out.t = std::move(result.t);
    out.tips = std::move(result.tip_position);
    if (result.wall_time_s > kSlowRunSeconds) break;
  }
}

}  // namespace

RunRecord run_case(const scene::Scene& scene, const RunSpec& spec) {
  RunRecord out;
  out.scheme = spec.scheme;
  out.nodes = spec.nodes;
  out.dt = spec.dt;
  std::vector<double> times;
  try {
    if (spec.problem == solvers::Problem::statics)
      run_static(scene, spec, out, times);
    else
      run_dynamic(scene, spec, out, times);
  } catch (const std::exception& e) {
    out.converged = false;
    out.reason = std::string("rejected by the solver: ") + e.what();
  }
  if (!out.converged && out.reason.empty()) out.reason = "did not converge";
  out.repeats = static_cast<int>(times.size());
  out.wall_time_s = median(times);
  out.wall_time_min_s = times.empty() ? 0.0 : *std::min_element(times.begin(), times.end());
  return out;
}

Json to_json(const RunRecord& r) {
  Json tips = Json::array();
  for (const auto& p : r.tips) tips.push_back({p.x(), p.y(), p.z()});
  return Json{{"scheme", r.scheme},
              {"nodes", r.nodes},
              {"dt", r.dt},
              {"steps", r.steps},
              {"converged", r.converged},
              {"reason", r.reason},
              {"wall_time_s", r.wall_time_s},
              {"wall_time_min_s", r.wall_time_min_s},
              {"repeats", r.repeats},
              {"t_reached", r.t_reached},
              {"tip", {r.tip.x(), r.tip.y(), r.tip.z()}},
              {"t", r.t},
              {"tips", tips}};
}

RunRecord record_from_json(const Json& j) {
  RunRecord r;
  if (j.contains("error")) {
    r.reason = "internal error: " + j["error"].get<std::string>();
    return r;
  }
  r.scheme = j.at("scheme").get<std::string>();
  r.nodes = j.at("nodes").get<int>();
  r.dt = j.at("dt").get<double>();
  r.steps = j.at("steps").get<long>();
  r.converged = j.at("converged").get<bool>();
  r.reason = j.at("reason").get<std::string>();
  r.wall_time_s = j.at("wall_time_s").get<double>();
  r.wall_time_min_s = j.at("wall_time_min_s").get<double>();
  r.repeats = j.at("repeats").get<int>();
  r.t_reached = j.at("t_reached").get<double>();
  const auto& tip = j.at("tip");
  // A non-finite number travels as null; keep it non-finite.
  auto number = [](const Json& v) {
    return v.is_null() ? std::numeric_limits<double>::quiet_NaN() : v.get<double>();
  };
  r.tip = lie::Vector3(number(tip[0]), number(tip[1]), number(tip[2]));
  for (const auto& v : j.at("t")) r.t.push_back(number(v));
  for (const auto& p : j.at("tips")) r.tips.emplace_back(number(p[0]), number(p[1]), number(p[2]));
  return r;
}

}  // namespace rodlab::validation::study
