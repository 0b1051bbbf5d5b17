#include "studies/settings.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <functional>
#include <limits>

#include "rodlab/io/atomic_file.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

namespace rodlab::validation::study {

std::vector<int> default_nodes(solvers::Problem problem, Refinement refine) {
  if (problem == solvers::Problem::statics) return {6, 11, 21, 41, 81};
  if (refine == Refinement::joint) return {6, 11, 21, 41};
  return {10, 20};
}

std::vector<int> study_nodes(const Settings& settings) {
  return settings.nodes.empty() ? default_nodes(settings.problem, settings.refine)
                                : settings.nodes;
}

namespace {

/// The problem `scheme` runs at N nodes on the scene's grid (solver.grid: corrected changes the
/// shear stiffness and with it the automatic step); where the scheme does not
/// take that grid, the scene's own (its runs are refused, and recorded so).
solvers::dynamics::DynamicProblem study_problem(const Settings& settings, std::string_view scheme,
                                                int nodes) {
  try {
    return solvers::dynamics::scene_problem_on_grid(settings.scene, scheme, nodes);
  } catch (const std::invalid_argument&) {
    return solvers::dynamics::DynamicProblem::from_scene(settings.scene);
  }
}

}  // namespace

std::vector<double> study_steps(const Settings& settings, const solvers::SchemeInfo& scheme,
                                int nodes) {
  if (!settings.dts.empty()) return settings.dts;
  const double dt =
      solvers::dynamics::auto_time_step(study_problem(settings, scheme.name, nodes), scheme.name,
                                        nodes);
  return {dt, dt / 2, dt / 4, dt / 8};
}

namespace {

/// Equal steps that end at t_end, none longer than dt (what a run uses, so output times nest).
double equal_step(const Settings& settings, double dt) {
  return settings.t_end / std::ceil(settings.t_end / dt * (1.0 - 1e-12));
}

/// The longest step `scheme` may take at N nodes: its auto step for an explicit scheme (a
/// stability limit), none for an implicit one.
double step_limit(const Settings& settings, const solvers::SchemeInfo& scheme, int nodes) {
  if (scheme.implicit) return std::numeric_limits<double>::infinity();
  return solvers::dynamics::auto_time_step(study_problem(settings, scheme.name, nodes),
                                           scheme.name, nodes);
}

}  // namespace

std::vector<double> joint_steps(const Settings& settings, const solvers::SchemeInfo& scheme,
                                const std::vector<int>& nodes) {
  const double L = settings.scene.rod.length;
  const double ds0 = L / (nodes.front() - 1);
  const double dt0 = study_steps(settings, scheme, nodes.front()).front();  // --dt's first, or auto
  std::vector<double> steps;
  for (const int n : nodes)
    steps.push_back(equal_step(settings, std::min(dt0 * (L / (n - 1)) / ds0,
                                                  step_limit(settings, scheme, n))));
  return steps;
}

std::vector<double> grid_steps(const Settings& settings, const solvers::SchemeInfo& scheme,
                               int nodes) {
  std::vector<double> steps;
  const double limit = step_limit(settings, scheme, nodes);
  for (const double dt : study_steps(settings, scheme, nodes))
    steps.push_back(equal_step(settings, std::min(dt, limit)));
  std::sort(steps.begin(), steps.end(), std::greater<>());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  return steps;
}

bool takes_grid(std::string_view scheme, std::string_view grid) {
  return grid != "euler" || solvers::dynamics::marches_in_s(scheme);
}

namespace {
std::string default_grid() {
  namespace dyn = solvers::dynamics;
  return std::string(dyn::shooting_grid_name(dyn::DynamicSolveOptions{}.grid));
}
}  // namespace

std::string run_grid(std::string_view scheme, const std::string& grid) {
  return takes_grid(scheme, grid) ? grid : default_grid();
}

std::string scene_grid(const Settings& settings) {
  return settings.scene.solver.grid.value_or(default_grid());
}

Settings settings_on_grid(const Settings& settings, const std::string& grid) {
  Settings on = settings;
  on.scene.solver.grid = grid;
  on.grids.clear();
  return on;
}

std::vector<std::string> trade_grids(const Settings& settings) {
  namespace dyn = solvers::dynamics;
  if (settings.problem != solvers::Problem::dynamics || settings.scene.solver.grid ||
      dyn::corrected_grid_refusal(dyn::DynamicProblem::from_scene(settings.scene)))
    return {};
  return {default_grid(), "corrected"};
}

std::string_view to_string(Refinement refine) {
  return refine == Refinement::joint ? "joint" : refine == Refinement::grid ? "grid" : "time";
}

std::vector<solvers::SchemeInfo> schemes_of(solvers::Problem problem) {
  std::vector<solvers::SchemeInfo> out;
  for (const auto& s : solvers::all_schemes())
    if (s.problem == problem) out.push_back(s);
  return out;
}

namespace {
std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

Json settings_json(const Settings& s) {
  Json schemes = Json::array();
  for (const auto& scheme : s.schemes) schemes.push_back(std::string(scheme.name));
  Json j{{"scene_file", s.scene_path},
         {"scene_hash", std::to_string(std::hash<std::string>{}(file_text(s.scene_path)))},
         {"overrides", s.overrides},
         {"scene", s.scene.name},
         {"problem", std::string(solvers::to_string(s.problem))},
         {"schemes", schemes},
         {"nodes", study_nodes(s)},
         {"dt", s.dts},
         {"refine", std::string(to_string(s.refine))},
         {"reference", s.reference ? Json(*s.reference) : Json(nullptr)},
         {"solver_tol", s.tol},
         {"t_end", s.t_end},
         {"repeats", s.repeats}};
  if (!s.grids.empty()) j["grids"] = s.grids;
  return j;
}

void write_output(const std::string& dir, const std::string& name, const std::string& content) {
  std::filesystem::create_directories(dir);
  io::write_file_atomically(std::filesystem::path(dir) / name, content);
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

std::string csv_text(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c == '\n' ? ' ' : c;
  }
  return out + "\"";
}

}  // namespace rodlab::validation::study
