#include "studies/convergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "rodlab/io/text_format.hpp"
#include "rodlab/io/text_table.hpp"

namespace rodlab::validation::study {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
using solvers::Problem;

struct Plan {
  std::vector<RunSpec> specs;
  std::vector<std::string> roles;
  std::vector<int> reference_of;  ///< index of the spec a spec is compared with; -1: none
  std::vector<std::string> grids;  ///< dynamics: the run's grid (plan_grids); empty: the scene's
  Json reference;

  /// Appends a run; returns its index.
  int add(RunSpec spec, const char* role, int reference) {
    spec.reference = std::string_view(role) == "reference";
    specs.push_back(std::move(spec));
    roles.emplace_back(role);
    reference_of.push_back(reference);
    grids.emplace_back();
    return static_cast<int>(specs.size()) - 1;
  }
};

/// study.json's `reference` for a reference solved by one scheme at one N.
Json scheme_reference(const std::string& scheme, int nodes, double tol,
                      const std::string& detail = "") {
  return {{"kind", "scheme"},
          {"scheme", scheme},
          {"nodes", nodes},
          {"tol", tol},
          {"description", scheme + " at N = " + std::to_string(nodes) + ", tol " +
                              io::format_number(tol) + detail}};
}

/// Joint and grid refinement's reference: ida at 4 (N_finest - 1) + 1 nodes, tol min(tol, 1e-10).
struct FineIda {
  int nodes;
  double tol;
};
FineIda fine_ida(const Settings& s, const std::vector<int>& nodes) {
  return {4 * (*std::max_element(nodes.begin(), nodes.end()) - 1) + 1, std::min(s.tol, 1e-10)};
}

Plan plan_statics(const Settings& s) {
  Plan plan;
  const auto nodes = study_nodes(s);
  const int finest = *std::max_element(nodes.begin(), nodes.end());
  const std::string ref = s.reference.value_or("kinsol");
  const int ref_nodes = ref == "chebyshev" ? std::max(2 * finest, 48) : std::max(4 * finest, 200);
  const double ref_tol = std::min(s.tol, 1e-12);
  plan.add({ref, Problem::statics, ref_nodes, 0.0, 0.0, ref_tol, 1, false}, "reference", -1);
  plan.reference = scheme_reference(ref, ref_nodes, ref_tol);
  for (const auto& scheme : s.schemes)
    for (const int n : nodes)
      plan.add({std::string(scheme.name), Problem::statics, n, 0.0, 0.0, s.tol, s.repeats, false},
               "study", 0);
  return plan;
}

Plan plan_dynamics(const Settings& s) {
  Plan plan;
  const bool use_ida = !s.reference || *s.reference == "ida";
  for (const int n : study_nodes(s)) {
    int ref_index = -1;
    if (use_ida) {
      double finest = std::numeric_limits<double>::infinity();
      for (const auto& scheme : s.schemes)
        for (const double dt : study_steps(s, scheme, n)) finest = std::min(finest, dt);
      ref_index = plan.add(
          {"ida", Problem::dynamics, n, finest, s.t_end, std::min(s.tol, 1e-10), 1, true},
          "reference", -1);
    }
    for (const auto& scheme : s.schemes) {
      auto steps = study_steps(s, scheme, n);
      std::sort(steps.begin(), steps.end(), std::greater<>());
      steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
      const int first = static_cast<int>(plan.specs.size());
      for (const double dt : steps)
        plan.add({std::string(scheme.name), Problem::dynamics, n, dt, s.t_end, s.tol, s.repeats,
                  true},
                 "study", ref_index);
      if (!use_ida) {  // Richardson: the finest step of the same scheme and N
        const int last = static_cast<int>(plan.specs.size()) - 1;
        plan.roles[last] = "reference";
        for (int i = first; i <= last; ++i) plan.reference_of[i] = i == last ? -1 : last;
      }
    }
  }
  if (use_ida)
    plan.reference = {{"kind", "scheme"},
                      {"scheme", "ida"},
                      {"tol", std::min(s.tol, 1e-10)},
                      {"description", "ida at the same N, tol " +
                                          io::format_number(std::min(s.tol, 1e-10)) +
                                          ", output at the finest step of that N"}};
  else
    plan.reference = {
        {"kind", "richardson"},
        {"description",
         "Richardson: the finest time step of the same scheme and N (ida is not available)"}};
  return plan;
}

/// Joint refinement: every scheme at every N with dt proportional to ds (joint_steps), against
/// ida at 4 (N_finest - 1) + 1 nodes, output at the coarsest step of all runs.
Plan plan_dynamics_joint(const Settings& s) {
  Plan plan;
  auto nodes = study_nodes(s);
  std::sort(nodes.begin(), nodes.end());
  const FineIda ref = fine_ida(s, nodes);
  std::vector<std::vector<double>> steps;
  double coarsest = 0.0;
  for (const auto& scheme : s.schemes) {
    steps.push_back(joint_steps(s, scheme, nodes));
    coarsest = std::max(coarsest, *std::max_element(steps.back().begin(), steps.back().end()));
  }
  // the reference's output step: the coarsest run's (ida's cost grows with its output count)
  plan.add({"ida", Problem::dynamics, ref.nodes, coarsest, s.t_end, ref.tol, 1, true},
           "reference", -1);
  for (std::size_t k = 0; k < s.schemes.size(); ++k)
    for (std::size_t i = 0; i < nodes.size(); ++i)
      plan.add({std::string(s.schemes[k].name), Problem::dynamics, nodes[i], steps[k][i], s.t_end,
                s.tol, s.repeats, true},
               "study", 0);
  plan.reference = scheme_reference("ida", ref.nodes, ref.tol,
                                    ", output at the coarsest step; N and dt refined together "
                                    "(dt proportional to ds)");
  return plan;
}

/// Grid refinement: every scheme at every N and every step of grid_steps, against ida at
/// 4 (N_finest - 1) + 1 nodes, one reference run per distinct step with its output at that step
/// (so that every output time of a run has its reference value, not an interpolation): the
/// error of the whole discretisation, space and time together (what work-precision and
/// recommend weigh against the wall time when the question is the physical answer, not one
/// grid's time error).
Plan plan_dynamics_grid(const Settings& s) {
  Plan plan;
  auto nodes = study_nodes(s);
  std::sort(nodes.begin(), nodes.end());
  const FineIda ref = fine_ida(s, nodes);
  std::map<double, int> reference_at;  // step -> its reference row
  for (const auto& scheme : s.schemes)
    for (const int n : nodes)
      for (const double dt : grid_steps(s, scheme, n)) {
        auto it = reference_at.find(dt);
        if (it == reference_at.end())
          it = reference_at
                   .emplace(dt, plan.add({"ida", Problem::dynamics, ref.nodes, dt, s.t_end,
                                          ref.tol, 1, true},
                                         "reference", -1))
                   .first;
        plan.add({std::string(scheme.name), Problem::dynamics, n, dt, s.t_end, s.tol, s.repeats,
                  true},
                 "study", it->second);
      }
  plan.reference = scheme_reference("ida", ref.nodes, ref.tol,
                                    ", output at each run's step; every dt at every N (the error "
                                    "of space and time together)");
  return plan;
}

/// The plan of one grid's sweep (or of the scene's grid).
Plan plan_for(const Settings& s) {
  const bool joint = s.problem == Problem::dynamics && s.refine == Refinement::joint;
  const bool grid = s.problem == Problem::dynamics && s.refine == Refinement::grid;
  return s.problem == Problem::statics ? plan_statics(s)
         : joint                       ? plan_dynamics_joint(s)
         : grid                        ? plan_dynamics_grid(s)
                                       : plan_dynamics(s);
}

/// Whether two planned runs are the same run (a reference two grids share).
bool same_run(const Plan& a, std::size_t i, const Plan& b, std::size_t j) {
  const RunSpec &x = a.specs[i], &y = b.specs[j];
  return a.roles[i] == b.roles[j] && a.grids[i] == b.grids[j] && x.scheme == y.scheme &&
         x.nodes == y.nodes && x.dt == y.dt && x.t_end == y.t_end && x.tol == y.tol &&
         x.repeats == y.repeats && x.keep_series == y.keep_series;
}

/// Several grids: one plan per grid (settings_on_grid, with the schemes that take the grid),
/// its runs on that grid, one after the other; the reference says each grid's. A run on a grid
/// it does not take (ida on the Euler grid) is on the staggered grid, and a reference that an
/// earlier grid's plan already has is not run again.
Plan plan_grids(const Settings& s) {
  Plan all;
  Json references = Json::array();
  std::string description;
  for (const auto& grid : s.grids) {
    Settings on = settings_on_grid(s, grid);
    std::erase_if(on.schemes, [&](const auto& scheme) { return !takes_grid(scheme.name, grid); });
    if (on.schemes.empty()) continue;
    Plan plan = plan_for(on);
    std::vector<int> index(plan.specs.size(), -1);  // plan's runs in `all`
    for (std::size_t i = 0; i < plan.specs.size(); ++i) {
      plan.grids[i] = run_grid(plan.specs[i].scheme, grid);
      for (std::size_t j = 0; j < all.specs.size() && index[i] < 0; ++j)
        if (plan.roles[i] == "reference" && same_run(plan, i, all, j))
          index[i] = static_cast<int>(j);
      if (index[i] >= 0) continue;
      index[i] = static_cast<int>(all.specs.size());
      all.specs.push_back(plan.specs[i]);
      all.roles.push_back(plan.roles[i]);
      all.grids.push_back(plan.grids[i]);
      all.reference_of.push_back(-1);
    }
    for (std::size_t i = 0; i < plan.specs.size(); ++i)
      if (plan.reference_of[i] >= 0)
        all.reference_of[static_cast<std::size_t>(index[i])] =
            index[static_cast<std::size_t>(plan.reference_of[i])];
    const std::string reference_grid = run_grid("ida", grid);
    plan.reference["grid"] = grid;
    if (reference_grid != grid) plan.reference["reference_grid"] = reference_grid;
    references.push_back(plan.reference);
    description += (description.empty() ? "" : "; ") + grid + " grid: " +
                   plan.reference.value("description", "") +
                   (reference_grid == grid ? "" : " (ida on the " + reference_grid + " grid)");
  }
  all.reference = {{"kind", "per grid"}, {"grids", references}, {"description", description}};
  return all;
}

/// Largest tip distance over the output times the run shares with its reference.
double max_common_error(const RunRecord& run, const RunRecord& ref, double t_end) {
  double worst = 0.0;
  std::size_t j = 0;
  const double match = 1e-9 * t_end;
  for (std::size_t i = 0; i < run.t.size(); ++i) {
    while (j < ref.t.size() && ref.t[j] < run.t[i] - match) ++j;
    if (j < ref.t.size() && std::abs(ref.t[j] - run.t[i]) <= match)
      worst = std::max(worst, (run.tips[i] - ref.tips[j]).norm());
  }
  return worst;
}

}  // namespace

namespace {

/// Each study row's error (and max error over time) against its reference row.
void measure_errors(const Settings& s, const Plan& plan, Sweep& sweep) {
  for (std::size_t i = 0; i < sweep.rows.size(); ++i) {
    auto& row = sweep.rows[i];
    row.error = row.max_error = kNaN;
    if (row.role == "study" && !row.run.converged) ++sweep.failed;
    const int r = plan.reference_of[i];
    if (r < 0) continue;
    const auto& ref = sweep.rows[static_cast<std::size_t>(r)].run;
    if (!ref.converged) {
      row.note = "the reference did not converge: " + ref.reason;
      continue;
    }
    if (!row.run.converged) continue;
    row.error = (row.run.tip - ref.tip).norm();
    if (s.problem == Problem::dynamics)
      row.max_error = std::max(row.error, max_common_error(row.run, ref, s.t_end));
  }
}

/// What a group of study rows shares: the scheme, the grid (dynamics) and N (time refinement).
struct GroupKey {
  std::string scheme, grid;
  int nodes = 0;
  auto operator<=>(const GroupKey&) const = default;
};

/// The observed order of one group of study rows (one scheme, or one scheme and N).
SchemeOrder fit_group(const Settings& s, bool joint, const GroupKey& key,
                      const std::vector<std::size_t>& members, Sweep& sweep) {
  std::vector<FitPoint> points;
  for (const auto i : members) {
    const auto& row = sweep.rows[i];
    points.push_back({row.h, row.error, row.run.converged && std::isfinite(row.error)});
  }
  SchemeOrder o;
  o.scheme = key.scheme;
  o.grid = key.grid;
  o.nodes = key.nodes;
  o.variable = s.problem == Problem::statics ? "ds" : joint ? "ds (dt ~ ds)" : "dt";
  if (const auto info = solvers::find_scheme(key.scheme)) o.expected = std::string(info->order);
  // the catalogue's order of the shooting schemes is that of their default, staggered grid; the
  // thesis' Euler grid (solver.grid: euler) is first order in s
  if (key.grid == "euler" && takes_grid(key.scheme, "euler")) o.expected = "2 (t) / 1 (s)";
  // variational's catalogue order is that of its default time rule, verlet; the thesis'
  // symplectic Euler (solver.variational_step: symplectic-euler) is first order in t
  if (s.scene.solver.variational_step == std::optional<std::string>("symplectic-euler") &&
      key.scheme == "variational")
    o.expected = "1 (t) / 2 (s)";
  o.fit = fit_order(points, sweep.rounding_floor);
  o.h_max = 0.0;
  o.h_min = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < members.size(); ++k) {
    if (!o.fit.used[k]) continue;
    sweep.rows[members[k]].in_fit = true;
    o.h_max = std::max(o.h_max, points[k].h);
    o.h_min = std::min(o.h_min, points[k].h);
  }
  if (o.fit.points == 0) o.h_min = o.h_max = kNaN;
  return o;
}

/// Orders: statics and joint refinement per scheme (in ds), dynamics per scheme and N (in dt);
/// each grid's apart.
void fit_orders(const Settings& s, bool joint, Sweep& sweep) {
  std::map<GroupKey, std::vector<std::size_t>> groups;
  std::vector<GroupKey> order;
  for (std::size_t i = 0; i < sweep.rows.size(); ++i) {
    const auto& row = sweep.rows[i];
    if (row.role != "study") continue;
    const GroupKey key{row.spec.scheme, row.grid,
                       s.problem == Problem::statics || joint ? 0 : row.spec.nodes};
    if (!groups.count(key)) order.push_back(key);
    groups[key].push_back(i);
  }
  for (const auto& key : order) sweep.orders.push_back(fit_group(s, joint, key, groups[key], sweep));
}

}  // namespace

Sweep run_sweep(const Settings& s, const Executor& executor) {
  const bool joint = s.problem == Problem::dynamics && s.refine == Refinement::joint;
  const bool grid = s.problem == Problem::dynamics && s.refine == Refinement::grid;
  const bool by_grid = s.problem == Problem::dynamics && !s.grids.empty();
  const Plan plan = by_grid ? plan_grids(s) : plan_for(s);
  std::vector<std::function<Json()>> tasks;
  for (std::size_t i = 0; i < plan.specs.size(); ++i)
    tasks.push_back([&s, spec = plan.specs[i], grid = plan.grids[i]] {
      if (grid.empty()) return to_json(run_case(s.scene, spec));
      return to_json(run_case(settings_on_grid(s, grid).scene, spec));
    });
  const auto results = run_tasks(tasks, executor);
  Sweep sweep;
  sweep.reference = plan.reference;
  sweep.by_grid = by_grid;
  if (results.empty()) return sweep;  // not rank 0

  const double length = s.scene.rod.length;
  double scale = length;
  for (std::size_t i = 0; i < plan.specs.size(); ++i) {
    SweepRow row;
    row.role = plan.roles[i];
    row.spec = plan.specs[i];
    if (s.problem == Problem::dynamics) {  // run_grid: a non-marching scheme on euler
      row.grid = run_grid(row.spec.scheme, plan.grids[i].empty() ? scene_grid(s) : plan.grids[i]);
    }
    row.run = record_from_json(results[i]);
    row.h = s.problem == Problem::statics || joint ? length / (row.spec.nodes - 1) : row.run.dt;
    if (row.run.dt == 0.0 && s.problem == Problem::dynamics && !joint) row.h = row.spec.dt;
    if (row.role == "reference" && row.run.converged) scale = std::max(scale, row.run.tip.norm());
    sweep.rows.push_back(std::move(row));
  }
  sweep.rounding_floor = rounding_floor(scale);
  measure_errors(s, plan, sweep);
  // A grid's errors mix the spatial and the time error: no order in either is fitted.
  if (!grid) fit_orders(s, joint, sweep);
  return sweep;
}

std::string convergence_csv(const Sweep& sweep) {
  std::string out =
      "scheme,role,nodes,dt,h,tip_x,tip_y,tip_z,error,max_error,in_fit,converged,reason,"
      "wall_time_s,wall_time_min_s,repeats,steps,grid\n";
  for (const auto& r : sweep.rows) {
    const bool dyn = r.spec.problem == solvers::Problem::dynamics;
    out += csv_text(r.spec.scheme) + ',' + r.role + ',' + std::to_string(r.spec.nodes) + ',' +
           (dyn ? csv_number(r.run.dt) : "") + ',' + csv_number(r.h) + ',' +
           csv_number(r.run.tip.x()) + ',' + csv_number(r.run.tip.y()) + ',' +
           csv_number(r.run.tip.z()) + ',' + csv_number(r.error) + ',' +
           (dyn ? csv_number(r.max_error) : "") + ',' + (r.in_fit ? "true" : "false") + ',' +
           (r.run.converged ? "true" : "false") + ',' +
           csv_text(r.note.empty() ? r.run.reason : r.note) + ',' + csv_number(r.run.wall_time_s) +
           ',' + csv_number(r.run.wall_time_min_s) + ',' + std::to_string(r.run.repeats) + ',' +
           (dyn ? std::to_string(r.run.steps) : "") + ',' + r.grid + '\n';
  }
  return out;
}

std::string orders_csv(const Sweep& sweep) {
  std::string out =
      "scheme,nodes,variable,expected_order,observed_order,points,h_max,h_min,note,grid\n";
  for (const auto& o : sweep.orders)
    out += csv_text(o.scheme) + ',' + (o.nodes > 0 ? std::to_string(o.nodes) : "") + ',' +
           o.variable + ',' + csv_text(o.expected) + ',' + csv_number(o.fit.order) + ',' +
           std::to_string(o.fit.points) + ',' + csv_number(o.h_max) + ',' + csv_number(o.h_min) +
           ',' + csv_text(o.fit.note) + ',' + o.grid + '\n';
  return out;
}

namespace {
Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
}  // namespace

Json sweep_json(const Sweep& sweep, const Settings& settings, const std::string& kind) {
  Json rows = Json::array();
  for (const auto& r : sweep.rows) {
    const bool dyn = r.spec.problem == solvers::Problem::dynamics;
    rows.push_back({{"scheme", r.spec.scheme},
                    {"role", r.role},
                    {"nodes", r.spec.nodes},
                    {"dt", dyn ? Json(r.run.dt) : Json(nullptr)},
                    {"h", r.h},
                    {"tip", {r.run.tip.x(), r.run.tip.y(), r.run.tip.z()}},
                    {"error", number_or_null(r.error)},
                    {"max_error", dyn ? number_or_null(r.max_error) : Json(nullptr)},
                    {"in_fit", r.in_fit},
                    {"converged", r.run.converged},
                    {"reason", r.note.empty() ? r.run.reason : r.note},
                    {"wall_time_s", r.run.wall_time_s},
                    {"wall_time_min_s", r.run.wall_time_min_s},
                    {"repeats", r.run.repeats},
                    {"steps", r.run.steps},
                    {"grid", dyn ? Json(r.grid) : Json(nullptr)}});
  }
  Json orders = Json::array();
  for (const auto& o : sweep.orders)
    orders.push_back({{"scheme", o.scheme},
                      {"nodes", o.nodes > 0 ? Json(o.nodes) : Json(nullptr)},
                      {"variable", o.variable},
                      {"expected_order", o.expected},
                      {"observed_order", number_or_null(o.fit.order)},
                      {"points", o.fit.points},
                      {"h_max", number_or_null(o.h_max)},
                      {"h_min", number_or_null(o.h_min)},
                      {"note", o.fit.note},
                      {"grid", o.grid.empty() ? Json(nullptr) : Json(o.grid)}});
  return Json{{"schema", "rodlab.study/1"},
              {"kind", kind},
              {"scene", settings.scene.name},
              {"command_line", settings.command_line},
              {"settings", settings_json(settings)},
              {"reference", sweep.reference},
              {"error_measure", settings.problem == solvers::Problem::statics
                                    ? "tip position distance from the reference [m]"
                                    : "tip position distance from the reference at t_end [m]; "
                                      "max_error: largest over the shared output times"},
              {"order_fit",
               {{"rule", "least-squares slope of log(error) against log(h) on the asymptotic "
                         "range (docs/studies.md)"},
                {"rounding_floor", sweep.rounding_floor},
                {"preasymptotic_tolerance", kPreasymptoticTolerance}}},
              {"rows", rows},
              {"orders", orders},
              {"failed_runs", sweep.failed}};
}

/// The scheme's name, and its grid when the sweep has several.
std::string scheme_label(const Sweep& sweep, const std::string& scheme, const std::string& grid) {
  return sweep.by_grid ? scheme + " (" + grid + ")" : scheme;
}

std::string sweep_table(const Sweep& sweep, bool timing) {
  using A = io::TextTable::Align;
  io::TextTable t({A::left, A::left, A::right, A::right, A::right, A::right, A::right, A::left});
  const bool dyn = !sweep.rows.empty() && sweep.rows.front().spec.problem == Problem::dynamics;
  t.add_row({sweep.by_grid ? "scheme (grid)" : "scheme", "role", "N", dyn ? "dt [s]" : "",
             "error [m]", timing ? "median time [s]" : "time [s]", "fit", "status"});
  t.add_rule();
  for (const auto& r : sweep.rows) {
    std::string status = r.run.converged ? "converged" : r.run.reason;
    if (!r.note.empty()) status = r.note;
    t.add_row({scheme_label(sweep, r.spec.scheme, r.grid), r.role, std::to_string(r.spec.nodes),
               dyn ? io::format_number(r.run.dt) : "",
               std::isfinite(r.error) ? io::format_number(r.error) : "-",
               io::format_number(r.run.wall_time_s), r.in_fit ? "*" : "", status});
  }
  return t.render();
}

std::string orders_table(const Sweep& sweep) {
  using A = io::TextTable::Align;
  io::TextTable t({A::left, A::right, A::right, A::right, A::right, A::left});
  t.add_row({sweep.by_grid ? "scheme (grid)" : "scheme", "N", "expected order", "observed order",
             "points", "note"});
  t.add_rule();
  for (const auto& o : sweep.orders)
    t.add_row({scheme_label(sweep, o.scheme, o.grid), o.nodes > 0 ? std::to_string(o.nodes) : "",
               o.expected, std::isfinite(o.fit.order) ? io::format_number(o.fit.order) : "-",
               std::to_string(o.fit.points), o.fit.note});
  return t.render();
}

}  // namespace rodlab::validation::study
