// The "studies" family of `rodlab validate`: the studies of `rodlab study` (docs/studies.md) on
// two example scenes, through the same functions (study::run_sweep, study::pareto_front,
// study::recommend, study::run_stability):
//   - work-precision of every statics scheme on scenes/cantilever-gravity.yaml
//     (N = 6 .. 81, against kinsol at N = 324) and of every non-reference dynamics
//     scheme on scenes/viscous-cantilever.yaml (N = 10, 20, dt = dt auto / 1, 2, 4, 8, a short
//     run, against ida at the same N): the diagrams (error against median wall time, Pareto
//     front and the recommendations marked), and `study recommend` answers for a statics and a
//     dynamics tolerance. Timing never gates a check: the checks are that the timings are
//     finite and positive, that the Pareto front is non-empty and monotone, and that the
//     recommended run, run again and measured against a reference other than the sweep's,
//     meets the tolerance (the recommendation itself is the check's detail);
//   - the stability map of the explicit scheme (largest stable dt / computed limit against N
//     and E), and the implicit schemes' step scans (where they stop working: implicit-midpoint
//     by multiple shooting below single shooting's bound and collocation down to 1e-6 s).
// The numbers measured on the development machine are in docs/validation.md.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/schemes.hpp"

#include "studies/convergence.hpp"
#include "studies/runs.hpp"
#include "studies/settings.hpp"
#include "studies/stability.hpp"
#include "studies/work_precision.hpp"
#include "checks/check.hpp"

// Data sets and figure specs are written with designated initializers; the fields left out keep
// their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace rodlab::validation {
namespace {

using solvers::Problem;

std::string candidate_text(const study::Candidate& c) {
  std::string t = c.scheme + ", N = " + std::to_string(c.nodes);
  if (c.dt) t += ", dt = " + io::format_number(*c.dt) + " s";
  t += ": tip error " + io::format_number(c.error) + " m in " + io::format_number(c.wall_time_s * 1e3) +
       " ms (median of " + std::to_string(c.repeats) + ")";
  return t;
}

std::string row_label(const study::SweepRow& r, bool dynamics) {
  return dynamics ? r.spec.scheme + " N=" + std::to_string(r.spec.nodes) : r.spec.scheme;
}

/// The work-precision data set of a sweep: one row per study run with a measured error; the
/// pareto column is 1 on the front, recommended 1 for the runs `recommend` chose.
DataSet wp_data(const std::string& name, const std::string& description, const study::Sweep& sweep,
                const std::vector<bool>& pareto, const std::vector<study::Candidate>& chosen,
                bool dynamics) {
  DataSet d{.name = name,
            .description = description,
            .columns = {"series", "scheme", "nodes", "dt", "error", "wall_time_s",
                        "wall_time_min_s", "repeats", "converged", "pareto", "recommended"}};
  for (std::size_t i = 0; i < sweep.rows.size(); ++i) {
    const auto& r = sweep.rows[i];
    if (r.role != "study") continue;
    bool rec = false;
    for (const auto& c : chosen)
      rec = rec || (c.scheme == r.spec.scheme && c.nodes == r.spec.nodes &&
                    (!c.dt || *c.dt == r.run.dt) && r.run.converged && c.error == r.error);
    d.add_row({row_label(r, dynamics), r.spec.scheme, r.spec.nodes,
               dynamics ? r.run.dt : double(NAN), r.error, r.run.wall_time_s, r.run.wall_time_min_s,
               r.run.repeats, r.run.converged ? 1 : 0, pareto[i] ? 1 : 0, rec ? 1 : 0});
  }
  return d;
}

/// Timings finite and positive; the front non-empty and monotone.
void front_checks(std::vector<Check>& out, const std::string& what, const study::Sweep& sweep,
                  const std::vector<bool>& pareto) {
  int timed = 0, bad = 0;
  std::vector<std::pair<double, double>> front;  // (time, error)
  std::string front_text;
  for (std::size_t i = 0; i < sweep.rows.size(); ++i) {
    const auto& r = sweep.rows[i];
    if (r.role != "study" || !r.run.converged) continue;
    ++timed;
    if (!(std::isfinite(r.run.wall_time_s) && r.run.wall_time_s > 0.0)) ++bad;
    if (pareto[i]) {
      front.emplace_back(r.run.wall_time_s, r.error);
      front_text +=
          (front_text.empty() ? "" : "; ") + r.spec.scheme +
          " N = " + std::to_string(r.spec.nodes) +
          (r.spec.problem == Problem::dynamics ? " dt = " + io::format_number(r.run.dt) : "") + ": " +
          io::format_number(r.error) + " m, " + io::format_number(r.run.wall_time_s * 1e3) + " ms";
    }
  }
  out.push_back(boolean_check(what + ": every study run converged", sweep.failed == 0,
                              "the schemes converge on this scene (docs/studies.md)",
                              std::to_string(sweep.failed) + " of " +
                                  std::to_string(timed + sweep.failed) + " runs failed"));
  out.push_back(boolean_check(what + ": median wall times finite and positive",
                              timed > 0 && bad == 0,
                              "measured timings (timing itself never gates a check)",
                              std::to_string(timed) + " timed runs, " + std::to_string(bad) +
                                  " not finite or not positive"));
  std::sort(front.begin(), front.end());
  bool monotone = !front.empty();
  for (std::size_t k = 1; k < front.size(); ++k)
    monotone =
        monotone && front[k].first > front[k - 1].first && front[k].second < front[k - 1].second;
  out.push_back(boolean_check(what + ": Pareto front non-empty, error falls as time rises along it",
                              monotone,
                              "definition of the front (no run at least as accurate and as fast)",
                              std::to_string(front.size()) + " runs on the front: " + front_text));
}

/// The recommendation for `tol` and its check: the recommended run, run again, measured
/// against `reference_tip` (an independent reference), is within tol. Also: it lies on the front.
study::Recommendation recommend_checks(std::vector<Check>& out, const std::string& what,
                                       const study::Sweep& sweep, const std::vector<bool>& pareto,
                                       const study::Settings& settings, double tol,
                                       const auto& independent_error,
                                       const std::string& reference) {
  const study::Json j = study::work_precision_json(sweep, pareto, settings);
  const study::Recommendation rec = study::recommend(j["rows"], tol, std::nullopt);
  const std::string name = what + ": `study recommend --tol " + io::format_number(tol) + "`";
  if (!rec.best) {
    out.push_back(boolean_check(name + " finds a run", false, "the sweep's measurements",
                                rec.most_accurate
                                    ? "most accurate: " + candidate_text(*rec.most_accurate)
                                    : "no converged run"));
    return rec;
  }
  const auto& b = *rec.best;
  const double err = independent_error(b);
  Check c = upper_bound_check(
      name + ": recommended run, re-run, error vs independent reference [m]", err, tol, reference);
  c.detail = "recommendation: " + candidate_text(b) + " (" + std::to_string(rec.candidates) +
             " candidates); " + c.detail;
  c.topic = "recommend";
  out.push_back(std::move(c));
  bool on_front = false;
  for (std::size_t i = 0; i < sweep.rows.size(); ++i) {
    const auto& r = sweep.rows[i];
    on_front = on_front || (pareto[i] && r.spec.scheme == b.scheme && r.spec.nodes == b.nodes &&
                            r.error == b.error && r.run.wall_time_s == b.wall_time_s);
  }
  out.push_back(boolean_check(name + ": the recommendation lies on the Pareto front", on_front,
                              "the fastest run meeting a tolerance is never dominated",
                              candidate_text(b)));
  return rec;
}

FigureSpec wp_figure(const std::string& name, const std::string& title,
                     const std::string& caption) {
  return {.name = name,
          .kind = "pareto",
          .x = "wall_time_s",
          .y = {"error"},
          .series = "series",
          .title = title,
          .xlabel = "median wall time [s]",
          .ylabel = "tip error [m]",
          .caption = caption,
          .style = "markers"};
}

// --- work-precision: statics ---------------------------------------------------------------

void statics_work_precision(const ValidationContext& context, std::vector<Check>& out) {
  study::Settings s;
  s.scene_path = (context.scenes_dir / "cantilever-gravity.yaml").string();
  s.scene = io::load_scene(s.scene_path);
  s.problem = Problem::statics;
  s.schemes = study::schemes_of(Problem::statics);
  s.nodes = {6, 11, 21, 41, 81};
  s.tol = 1e-10;
  s.repeats = context.full ? 5 : 3;
  s.command_line =
      "rodlab study work-precision " + s.scene_path + " --repeats " + std::to_string(s.repeats);
  const study::Sweep sweep = study::run_sweep(s, study::Executor{});
  const auto pareto = study::pareto_front(sweep);
  const std::string what = "statics work-precision (cantilever-gravity)";
  front_checks(out, what, sweep, pareto);

  // Independent reference: chebyshev at N = 32 (spectral: at the rounding level, 2e-14 m, from
  // N = 21 on), not the sweep's kinsol at N = 324.
  const study::RunRecord cheb =
      study::run_case(s.scene, {"chebyshev", Problem::statics, 32, 0.0, 0.0, 1e-12, 1, false});
  const auto error = [&](const study::Candidate& c) {
    const auto r =
        study::run_case(s.scene, {c.scheme, Problem::statics, c.nodes, 0.0, 0.0, s.tol, 1, false});
    return (cheb.converged && r.converged) ? (r.tip - cheb.tip).norm() : double(NAN);
  };
  std::vector<study::Candidate> chosen;
  for (const double tol : {1e-5, 1e-8, 1e-11}) {
    const auto rec =
        recommend_checks(out, what, sweep, pareto, s, tol, error,
                         "chebyshev at N = 32, tol 1e-12 (the sweep's reference: " +
                             sweep.reference.value("description", std::string{}) + ")");
    if (rec.best) chosen.push_back(*rec.best);
  }
  DataSet d = wp_data("studies_wp_statics",
                      "statics work-precision on scenes/cantilever-gravity.yaml: every available "
                      "scheme at N = 6, 11, 21, 41, 81; tip error against " +
                          sweep.reference.value("description", std::string{}) +
                          "; median wall time of " + std::to_string(s.repeats) + " repeats",
                      sweep, pareto, chosen, false);
  d.figures.push_back(wp_figure(
      "studies_wp_statics", "Work-precision, statics: gravity cantilever",
      "Work-precision diagram of the statics schemes on scenes/cantilever-gravity.yaml (N = 6 .. "
      "81): tip error against kinsol at N = 324 versus the solver's median wall time over " +
          std::to_string(s.repeats) +
          " repeats on this machine. The black line joins the Pareto front; stars mark the "
          "`study recommend` answers for 1e-5, 1e-8 and 1e-11 m."));
  context.emit(std::move(d));
}

// --- work-precision: dynamics --------------------------------------------------------------

void dynamics_work_precision(const ValidationContext& context, std::vector<Check>& out) {
  study::Settings s;
  s.scene_path = (context.scenes_dir / "viscous-cantilever.yaml").string();
  s.scene = io::load_scene(s.scene_path);
  s.problem = Problem::dynamics;
  for (const auto& scheme : study::schemes_of(Problem::dynamics))
    if (!scheme.reference) s.schemes.push_back(scheme);
  if (s.schemes.empty()) return;
  s.nodes = {10, 20};
  s.tol = 1e-10;
  s.t_end = context.full ? 0.1 : 0.05;
  s.repeats = context.full ? 5 : 3;
  s.command_line = "rodlab study work-precision " + s.scene_path + " --nodes 10,20 --t-end " +
                   io::format_number(s.t_end) + " --repeats " + std::to_string(s.repeats);
  const study::Sweep sweep = study::run_sweep(s, study::Executor{});
  const auto pareto = study::pareto_front(sweep);
  const std::string what =
      "dynamics work-precision (viscous-cantilever, " + io::format_number(s.t_end) + " s)";
  front_checks(out, what, sweep, pareto);

  // Independent reference: ida at the same N with rtol = atol = 1e-12 (the sweep's: 1e-10,
  // output at the finest step).
  const auto error = [&](const study::Candidate& c) {
    const auto r = study::run_case(
        s.scene, {c.scheme, Problem::dynamics, c.nodes, *c.dt, s.t_end, s.tol, 1, false});
    solvers::dynamics::DynamicSolveOptions o;
    o.scheme = "ida";
    o.nodes = c.nodes;
    o.dt = r.dt;
    o.t_end = s.t_end;
    o.output_every = 1 << 30;
    o.rtol = o.atol = 1e-12;
    if (s.scene.dynamics) o.initial = s.scene.dynamics->initial;
    const auto ref = solvers::dynamics::solve_dynamic(s.scene, o);
    if (!r.converged || !ref.converged || ref.tip_position.empty()) return double(NAN);
    return (r.tip - ref.tip_position.back()).norm();
  };
  const std::string reference =
      "ida at the same N, rtol = atol = 1e-12, tip at t_end (the sweep's reference: ida, "
      "tol 1e-10; the error of the shooting schemes is mostly their different spatial "
      "discretisation)";
  std::vector<study::Candidate> chosen;
  for (const double tol : {1e-4}) {
    const auto rec = recommend_checks(out, what, sweep, pareto, s, tol, error, reference);
    if (rec.best) chosen.push_back(*rec.best);
  }
  DataSet d = wp_data("studies_wp_dynamics",
                      "dynamics work-precision on scenes/viscous-cantilever.yaml (t_end = " +
                          io::format_number(s.t_end) +
                          " s): every available non-reference scheme at N = 10, 20 and dt = dt "
                          "auto / 1, 2, 4, 8; tip error at t_end against " +
                          sweep.reference.value("description", std::string{}) +
                          "; median wall time of " + std::to_string(s.repeats) + " repeats",
                      sweep, pareto, chosen, true);
  d.figures.push_back(wp_figure(
      "studies_wp_dynamics", "Work-precision, dynamics: viscous cantilever",
      "Work-precision diagram of the dynamics schemes on scenes/viscous-cantilever.yaml, runs of " +
          io::format_number(s.t_end) +
          " s at N = 10 and 20 with dt = dt auto / 1, 2, 4, 8: tip error at t_end against ida at "
          "the same N versus the median wall time over " +
          std::to_string(s.repeats) +
          " repeats. ida shares the semi-discretisation of variational and collocation (their "
          "error is the time error); the shooting schemes discretise space differently, so "
          "their error is mostly spatial. Black line: the Pareto front; star: the `study "
          "recommend` answer for 1e-4 m."));
  context.emit(std::move(d));
}

// --- joint convergence: N and dt refined together ----------------------------------------------

/// The joint refinement of the viscous cantilever (0.1 s) at N = 6, 11, 21, 41 with
/// dt = 0.01 s x ds / ds(6) (variational at its stability limit when that is smaller), against
/// ida at N = 161, for `schemes` with the scene overrides `overrides` (KEY=VALUE): the sweep and
/// its data set (rows: scheme, N, ds, dt, error), and the check that every run converged.
struct JointStudy {
  study::Sweep sweep;
  std::string reference;
  DataSet data;
};
JointStudy joint_convergence_study(const ValidationContext& context,
                                   std::vector<solvers::SchemeInfo> schemes,
                                   const std::vector<std::string>& overrides,
                                   const std::string& name, const std::string& what,
                                   const std::string& label, std::vector<Check>& out) {
  study::Settings s;
  s.scene_path = (context.scenes_dir / "viscous-cantilever.yaml").string();
  s.overrides = overrides;
  std::vector<io::Override> parsed;
  for (const auto& o : overrides) parsed.push_back(io::parse_override(o));
  s.scene = io::load_scene(s.scene_path, parsed);
  s.problem = Problem::dynamics;
  s.schemes = std::move(schemes);
  s.refine = study::Refinement::joint;
  s.nodes = {6, 11, 21, 41};
  s.dts = {0.01};
  s.tol = 1e-10;
  s.t_end = 0.1;
  s.command_line = "rodlab study convergence " + s.scene_path + " --refine joint --dt 0.01 --t-end 0.1";
  for (const auto& o : overrides) s.command_line += " --set " + o;
  const study::Executor two{.jobs = 2};  // no timing here
  JointStudy j{study::run_sweep(s, two), {}, {}};
  j.reference = j.sweep.reference.value("description", std::string{});
  j.data = DataSet{.name = name,
                   .description = what + " on scenes/viscous-cantilever.yaml (0.1 s), N and dt "
                                  "refined together; tip error at t_end against " + j.reference,
                   .columns = {"series", "scheme", "nodes", "ds", "dt", "error", "max_error"}};
  for (const auto& r : j.sweep.rows)
    if (r.role == "study")
      j.data.add_row({r.spec.scheme, r.spec.scheme, r.spec.nodes, r.h, r.run.dt, r.error,
                      r.max_error});
  out.push_back(boolean_check("joint convergence" + label + ": every run converged",
                              j.sweep.failed == 0,
                              "the schemes run at these steps, down to dt = 1.25 ms at N = 41 "
                              "(docs/studies.md)",
                              std::to_string(j.sweep.failed) + " runs failed"));
  return j;
}

/// The observed order of one scheme in ds with dt ~ ds, checked in [lo, hi].
Check joint_order_check(const study::SchemeOrder& o, const std::string& label, double lo,
                        double hi, const std::string& why) {
  Check c = range_check("joint convergence" + label + ": " + o.scheme +
                            " observed order in ds, dt ~ ds",
                        o.fit.order, lo, hi, why);
  c.detail += "; " + std::to_string(o.fit.points) + " points" +
              (o.fit.note.empty() ? "" : ", " + o.fit.note);
  c.topic = "order";
  return c;
}

FigureSpec joint_figure(const std::string& name, const std::string& title,
                        const std::string& caption) {
  return {.name = name,
          .kind = "loglog",
          .x = "ds",
          .y = {"error"},
          .series = "series",
          .title = title,
          .xlabel = "ds [m]",
          .ylabel = "tip error at t = 0.1 s [m]",
          .caption = caption,
          .reference_slopes = {1.0, 2.0},
          .style = "lines+markers"};
}

/// Every dynamics scheme at its defaults (the shooting schemes on the staggered grid): the
/// discretisation error shrinks at each scheme's observed order. Measured (docs/validation.md):
/// implicit-midpoint 1.87 (errors 2.2e-4 .. 8.7e-6 m), bdf-alpha 1.48 (4.5e-4 .. 1.9e-5 m: its
/// damping of the stiff viscous modes at the coarse steps leaves the first points
/// pre-asymptotic; against ida on the same grid it reaches 1.91 at fine dt,
/// tests/dynamics/test_staggered_shooting.cpp).
void dynamics_joint_convergence(const ValidationContext& context, std::vector<Check>& out) {
  JointStudy j = joint_convergence_study(context, study::schemes_of(Problem::dynamics), {},
                                         "studies_joint_convergence", "every dynamics scheme",
                                         " (viscous-cantilever)", out);
  // Expected: the spatial order, since dt ~ ds keeps the time error of the second-order schemes
  // at the same order and variational's step (its stability limit, ~1e-5 s) makes its
  // first-order time error smaller than its spatial one on these grids.
  for (const auto& o : j.sweep.orders) {
    const bool bdf = o.scheme == "bdf-alpha";
    out.push_back(joint_order_check(
        o, " (viscous-cantilever)", bdf ? 1.3 : 1.7, 2.3,
        j.reference + "; design order " + o.expected + " (second order in s; the time error is "
            "smaller" + (bdf ? "; bdf-alpha pre-asymptotic at the coarse steps)" : ")")));
  }
  j.data.figures.push_back(joint_figure(
      "studies_joint_convergence", "Dynamics: N and dt refined together (viscous cantilever)",
      "Tip error at t = 0.1 s against " + j.reference +
          ", N = 6, 11, 21, 41 with dt = 0.01 s x ds / ds(N = 6) (variational at its stability "
          "limit). Dashed: slopes 1 and 2. Every scheme at its defaults is second order in s "
          "(the shooting schemes on the staggered grid)."));
  context.emit(std::move(j.data));
}

/// The shooting schemes on the thesis' Euler grid (solver.grid: euler, docs/dynamics.md): the
/// same joint refinement, first order in s (measured 1.08, 1.07; 2.5e-3 m at N = 41 where the
/// default grid errs 8.7e-6 m).
void dynamics_joint_convergence_euler(const ValidationContext& context, std::vector<Check>& out) {
  JointStudy j = joint_convergence_study(
      context, {*solvers::find_scheme("implicit-midpoint"), *solvers::find_scheme("bdf-alpha")},
      {"solver.grid=euler"}, "studies_joint_convergence_euler",
      "implicit-midpoint and bdf-alpha on the thesis' Euler grid", ", Euler shooting grid", out);
  for (const auto& o : j.sweep.orders)
    out.push_back(joint_order_check(o, ", Euler shooting grid", 0.9, 1.3,
                                    j.reference + "; design order " + o.expected +
                                        " (first order in s dominates)"));
  j.data.figures.push_back(joint_figure(
      "studies_joint_convergence_euler", "Dynamics: the shooting schemes on the thesis' Euler grid",
      "As the previous figure, for implicit-midpoint and bdf-alpha with solver.grid: euler "
      "(explicit Euler RKMK on the nodes, thesis Algorithm 2): first order in s, where the "
      "default staggered grid is second. Dashed: slopes 1 and 2."));
  context.emit(std::move(j.data));
}

// --- stability map ---------------------------------------------------------------------------

/// The viscous cantilever's stability study settings, without schemes.
study::Settings stability_settings(const ValidationContext& context) {
  study::Settings s;
  s.scene_path = (context.scenes_dir / "viscous-cantilever.yaml").string();
  s.scene = io::load_scene(s.scene_path);
  s.problem = Problem::dynamics;
  s.tol = 1e-10;
  s.nodes = {10, 20, 40};
  s.moduli = {1e4, 1e6, 1e8};
  return s;
}

/// Two jobs: the stability results do not depend on them (no timing is checked here).
const study::Executor kTwoJobs{.jobs = 2};

/// The explicit scheme's stability study with variational's time rule `rule`.
study::Stability explicit_stability(const ValidationContext& context, const std::string& rule) {
  study::Settings s = stability_settings(context);
  s.scene.solver.variational_step = rule;
  for (const auto& scheme : study::schemes_of(Problem::dynamics))
    if (!scheme.reference && !scheme.implicit) s.schemes.push_back(scheme);
  if (s.schemes.empty()) return {};
  return study::run_stability(s, kTwoJobs);
}

/// The explicit scheme's stability study with variational's time rule `rule` as a data set
/// (one row per N and E) and one check per limit: measured / computed (variational_stable_step)
/// in [lo, hi]. `label` follows the scheme's name in the series and the checks.
DataSet stability_limits(const ValidationContext& context, const std::string& rule,
                         const std::string& label, double lo, double hi, const std::string& why,
                         std::vector<Check>& out) {
  const study::Stability st = explicit_stability(context, rule);
  DataSet d{.columns = {"series", "scheme", "E", "log10_E", "nodes", "dt_linear", "dt_max",
                        "dt_unstable", "safety_factor", "runs"}};
  for (const auto& l : st.limits) {
    const double ratio = l.dt_linear > 0 ? l.dt_max / l.dt_linear : double(NAN);
    const std::string scheme = l.scheme + label;
    d.add_row({scheme + " E=" + io::format_number(l.E) + " Pa", scheme, l.E, std::log10(l.E),
               l.nodes, l.dt_linear, l.dt_max, l.dt_unstable, ratio, l.runs});
    Check c = range_check("stability map: " + scheme + " measured / computed limit, N = " +
                              std::to_string(l.nodes) + ", E = " + io::format_number(l.E) + " Pa",
                          ratio, lo, hi, why);
    c.detail += "; dt_max " + io::format_number(l.dt_max) + " s, computed " +
                io::format_number(l.dt_linear) + " s, " + std::to_string(l.runs) + " runs" +
                (l.note.empty() ? "" : "; " + l.note);
    out.push_back(std::move(c));
  }
  return d;
}

/// The measured largest stable step and the computed limit against N, one curve per E.
FigureSpec step_limit_figure(const std::string& name, const std::string& title,
                             const std::string& caption) {
  return {.name = name,
          .kind = "loglog",
          .x = "nodes",
          .y = {"dt_max", "dt_linear"},
          .series = "series",
          .title = title,
          .xlabel = "N (nodes)",
          .ylabel = "dt [s]",
          .caption = caption,
          .style = "lines+markers"};
}

/// The explicit scheme's measured stability limit against the computed one, over N and E: the
/// thesis' time rule (symplectic-euler), whose criterion time_step.hpp computes. Below 0.95 the
/// computed limit would be unsafe; above 1.10, needlessly small. At N = 10 the measured onset
/// lies 3.6-5.9 % above it (E = 1e6, 1e4 Pa: a sharp blow-up within 140 steps at 1.06); until
/// (3.42)'s Newton took its Jacobian at the iterate (2f26d9c), the tip node's Newton failed
/// first, at 1.005 (docs/validation.md).
void explicit_stability_map(const ValidationContext& context, std::vector<Check>& out) {
  DataSet d = stability_limits(context, "symplectic-euler", "", 0.95, 1.10,
                               "Jury criterion with the von Neumann omega_max "
                               "(variational_stable_step, docs/dynamics.md)",
                               out);
  if (d.rows.empty()) return;
  d.name = "studies_stability_explicit";
  d.description =
      "largest stable step of the explicit schemes (bisection to 0.5 %, runs of 2000 steps from "
      "the viscous cantilever's initial state) against N and E (G scaled with E), and the "
      "computed limit";
  d.figures.push_back({.name = "studies_stability_map",
                       .kind = "map",
                       .x = "nodes",
                       .y = {"safety_factor", "log10_E"},
                       .title = "Stability map of the explicit scheme",
                       .xlabel = "N (nodes)",
                       .ylabel = "log10 E [Pa]",
                       .caption = "Stability map: the largest stable step of the explicit "
                                  "scheme measured by bisection (2000-step runs of the viscous "
                                  "cantilever), divided by the computed limit "
                                  "variational_stable_step, for N = 10, 20, 40 and E = 1e4, "
                                  "1e6, 1e8 Pa (colour: the ratio, 1 = the computed limit)."});
  d.figures.push_back(step_limit_figure(
      "studies_stability_dt", "Explicit step limit against N",
      "The measured largest stable step (dt_max) and the computed limit (dt_linear) of the "
      "explicit scheme against N for each E."));
  context.emit(std::move(d));
}

/// Verlet (variational's default) against the same computed limit, which is the thesis' rule's
/// (Jury criterion of the lagged damping) and which `dt: auto` uses for both rules at 0.9: the
/// Heun corrector's region contains the lagged one (docs/dynamics.md "Second order in time"),
/// so the measured limit must stay above 0.92 of it (auto's 0.9 with a margin).
void verlet_stability_map(const ValidationContext& context, std::vector<Check>& out) {
  DataSet d = stability_limits(context, "verlet", " (verlet)", 0.92, 64.0,
                               "dt: auto = 0.9 x the computed (lagged) limit stays stable "
                               "(variational_stable_step)",
                               out);
  if (d.rows.empty()) return;
  d.name = "studies_stability_verlet";
  d.description = "largest stable step of variational with its default time rule (verlet: "
                  "trapezoidal damping by a Heun corrector), as the previous table, against the "
                  "computed limit of the lagged rule";
  d.figures.push_back(step_limit_figure(
      "studies_stability_verlet", "variational (verlet): step limit against N",
      "The measured largest stable step of variational with its default Stormer-Verlet rule "
      "(dt_max) and the computed limit of the lagged rule (dt_linear) that dt: auto uses."));
  context.emit(std::move(d));
}

/// The checks of one implicit scheme's step scan: it runs at its dt auto, and neither the
/// shooting (multiple shooting below single shooting's bound) nor collocation has a lower step
/// bound.
void scan_checks(const study::ScanSummary& sum, std::vector<Check>& out) {
  const std::string range =
      "runs from " + io::format_number(sum.smallest_ok) + " to " + io::format_number(sum.largest_ok) +
      " s; first failure below: " + io::format_number(sum.first_failed_below) +
      " s, above: " + io::format_number(sum.first_failed_above) + " s (0: none)";
  out.push_back(
      boolean_check("stability scan: " + sum.scheme + " runs at its dt auto (" +
                        io::format_number(sum.dt_auto) + " s), N = " + std::to_string(sum.nodes),
                    sum.smallest_ok > 0.0,
                    "auto_time_step (time_step.hpp): the step `dt: auto` chooses", range));
  const bool shooting = sum.scheme == "implicit-midpoint";
  if (shooting || sum.scheme == "implicit-midpoint-collocation")
    out.push_back(boolean_check(
        "stability scan: " + sum.scheme + " has no lower step bound down to 2e-6 s, N = " +
            std::to_string(sum.nodes),
        sum.first_failed_below == 0.0 && sum.smallest_ok > 0.0 && sum.smallest_ok <= 2e-6,
        shooting ? "multiple shooting below single shooting's bound, which the thesis' "
                   "Algorithm 2 has (docs/dynamics.md \"Multiple shooting below the bound\")"
                 : "collocation's global BVP solve (docs/dynamics.md)",
        range));

}

/// The implicit schemes' step scans from their dt auto, down and up.
void implicit_step_scans(const ValidationContext& context, std::vector<Check>& out) {
  // The implicit schemes' step scans: runs of min(t_end, 2000 dt), t_end 0.1 s (--full: 0.3 s,
  // and N = 40 too).
  study::Settings si = stability_settings(context);
  for (const auto& scheme : study::schemes_of(Problem::dynamics))
    if (!scheme.reference && scheme.implicit) si.schemes.push_back(scheme);
  if (si.schemes.empty()) return;
  si.nodes = context.full ? std::vector<int>{10, 20, 40} : std::vector<int>{10, 20};
  si.t_end = context.full ? 0.3 : 0.1;
  const std::string runs = "runs of min(" + io::format_number(si.t_end) + " s, 2000 dt)";
  const study::Stability st = study::run_stability(si, kTwoJobs);
  DataSet d{.name = "studies_stability_implicit",
            .description =
                "step scans of the implicit schemes on the viscous cantilever: from "
                "dt auto down by 3 to 1e-6 s and up by 3 to min(0.1 s, t_end), each "
                "way until a run fails; " +
                runs,
            .columns = {"series", "scheme", "nodes", "dt", "log10_dt", "direction", "converged",
                        "steps", "reason"}};
  for (const auto& p : st.scan)
    d.add_row({p.scheme + " N=" + std::to_string(p.nodes), p.scheme, p.nodes, p.dt,
               std::log10(p.dt), p.direction, p.converged ? 1 : 0, p.steps, p.reason});
  for (const auto& sum : st.summaries) scan_checks(sum, out);
  d.figures.push_back({.name = "studies_stability_scan",
                       .kind = "map",
                       .x = "log10_dt",
                       .y = {"converged"},
                       .series = "series",
                       .title = "Implicit schemes: where the steps work",
                       .xlabel = "log10 dt [s]",
                       .ylabel = "scheme, N",
                       .caption = "Step scans of the implicit schemes (viscous cantilever, " +
                                  runs +
                                  "): each row is a scheme at N nodes, each point a run (colour: "
                                  "1 converged, 0 failed), from dt auto down and up by factors of "
                                  "3 until a run fails."});
  context.emit(std::move(d));
}

}  // namespace

std::vector<Check> study_checks(const ValidationContext& context) {
  std::vector<Check> out;
  statics_work_precision(context, out);
  dynamics_work_precision(context, out);
  dynamics_joint_convergence(context, out);
  dynamics_joint_convergence_euler(context, out);
  explicit_stability_map(context, out);
  verlet_stability_map(context, out);
  implicit_step_scans(context, out);
  return out;
}

}  // namespace rodlab::validation
