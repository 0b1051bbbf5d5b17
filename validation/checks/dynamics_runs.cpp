#include "checks/dynamics_runs.hpp"

#include <algorithm>
#include <cmath>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/io/text_format.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"

#include "reference/reference_rods.hpp"

namespace rodlab::validation::dynamics {

using solvers::dynamics::DynamicProblem;
using solvers::dynamics::DynamicSolveOptions;

scene::Scene rod_scene(const std::string& name, const std::string& loads, const std::string& tip,
                       double alpha) {
  const std::string yaml =
      "schema: rodlab.scene/1\nname: " + name + "\n" +
      reference::table21_rod_yaml(io::format_number(alpha)) + "tip:\n  free: " + tip +
      "\nloads: " + loads + "\n";
  return io::load_scene_from_string(yaml, name + ".yaml");
}

scene::Scene released(double P, double alpha) {
  const std::string force =
      "{steps: [[0, [" + io::format_number(P) + ", 0, 0]], [1.0e-9, [0, 0, 0]]]}";
  return rod_scene("released-cantilever", "{}", "{wrench: {force: " + force + ", frame: world}}",
                   alpha);
}

scene::Scene viscous_cantilever(double alpha) {
  return rod_scene("viscous-cantilever", "{gravity: [-9.81, 0, 0]}", "{}", alpha);
}

double auto_dt(const scene::Scene& s, std::string_view scheme, int nodes) {
  return solvers::dynamics::auto_time_step(DynamicProblem::from_scene(s), scheme, nodes);
}

DynamicResult simulate(const scene::Scene& s, const std::string& scheme, int nodes, double dt,
                       double t_end, scene::Initial initial, int outputs) {
  DynamicSolveOptions o;
  solvers::dynamics::apply_scene_options(s, o);  // solver.variational_step, as `rodlab dynamic`
  o.scheme = scheme;
  o.nodes = nodes;
  o.dt = dt;
  o.t_end = t_end;
  o.initial = initial;
  const long steps = std::max(1L, std::lround(std::ceil(t_end / dt - 1e-9)));
  o.output_every = static_cast<int>(std::max(1L, steps / outputs));
  return solve_dynamic(s, o);
}

std::string run_text(const DynamicResult& r) {
  return r.scheme + ", N = " + std::to_string(r.nodes) + ", dt = " + io::format_number(r.dt) +
         " s, " + std::to_string(r.steps) + " steps, wall " + io::format_number(r.wall_time_s) + " s" +
         (r.converged ? "" : "; NOT CONVERGED: " + r.reason);
}

namespace {

/// The tip of `b` at the times of `a`, by linear interpolation (both series start at 0).
lie::Vector3 tip_at(const DynamicResult& b, double t) {
  const auto it = std::lower_bound(b.t.begin(), b.t.end(), t);
  if (it == b.t.begin()) return b.tip_position.front();
  if (it == b.t.end()) return b.tip_position.back();
  const auto i = static_cast<std::size_t>(it - b.t.begin());
  const double w = (t - b.t[i - 1]) / (b.t[i] - b.t[i - 1]);
  return (1 - w) * b.tip_position[i - 1] + w * b.tip_position[i];
}

}  // namespace

double max_tip_difference(const DynamicResult& a, const DynamicResult& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.t.size(); ++i)
    if (a.t[i] <= b.t.back() + 1e-12) d = std::max(d, (a.tip_position[i] - tip_at(b, a.t[i])).norm());
  return d;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

double ledger_drift(const DynamicResult& r) {
  double d = 0.0;
  for (double e : r.energy.total) d = std::max(d, std::abs(e - r.energy.total.front()));
  return d;
}

double max_mechanical_rise(const DynamicResult& r, double after) {
  double rise = -INFINITY;
  for (std::size_t i = 1; i < r.t.size(); ++i) {
    if (r.t[i - 1] < after) continue;
    const auto m = [&](std::size_t k) {
      return r.energy.kinetic[k] + r.energy.strain[k] + r.energy.gravity[k];
    };
    rise = std::max(rise, m(i) - m(i - 1));
  }
  return rise;
}

void DynamicsData::add_shape(const std::string& name, const std::vector<result::CenterlineSample>& c) {
  for (const auto& x : c) {
    const lie::Vector3 p = x.pose.translation();
    shapes.add_row({name, x.s, p.x(), p.y(), p.z()});
  }
}

void DynamicsData::add(const std::string& name, const DynamicResult& r, double scale) {
  const double t0 = r.energy.total.empty() ? 0.0 : r.energy.total.front();
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const auto& e = r.energy;
    energy.add_row({name, r.t[i], e.kinetic[i], e.strain[i], e.gravity[i], e.dissipated[i],
                    e.work_in[i], e.total[i], e.kinetic[i] + e.strain[i] + e.gravity[i],
                    std::abs(e.total[i] - t0) / scale});
    det.add_row({name, r.t[i], r.max_det_deviation[i]});
  }
  const double d = max_abs(r.max_det_deviation);
  if (d >= worst_det) {
    worst_det = d;
    worst_det_case = name;
  }
}
void DynamicsData::add_tip(const DynamicResult& r) {
  for (std::size_t i = 0; i < r.t.size(); ++i)
    tip.add_row({r.scheme, r.t[i], r.tip_position[i].x(), r.tip_position[i].y(),
                 r.tip_position[i].z()});
}

void DynamicsData::emit(const ValidationContext& context) {
  add_trajectory_figures();
  add_drift_figures();
  context.emit(std::move(shapes));
  context.emit(std::move(tip));
  context.emit(std::move(energy));
  context.emit(std::move(det));
}

void DynamicsData::add_trajectory_figures() {
  tip.figures.push_back(
      {.name = "dynamics_tip",
       .kind = "line",
       .x = "t",
       .y = {"x"},
       .series = "scheme",
       .title = "Tip trajectories, viscous cantilever (N = 20)",
       .xlabel = "t [s]",
       .ylabel = "tip x [m]",
       .caption = "Tip deflection of the Table 2.1 rod (alpha = 300 Pa s) released straight "
                  "under gravity [-9.81, 0, 0] m/s^2, N = 20, per available scheme; variational "
                  "at its automatic step, the implicit schemes at the steps of the agreement "
                  "checks, ida at rtol = atol = 1e-10 (outputs every 1 ms)."});
  energy.figures.push_back(
      {.name = "dynamics_energy",
       .kind = "line",
       .x = "t",
       .y = {"mechanical"},
       .series = "case",
       .title = "Mechanical energy T + U + P against time",
       .xlabel = "t [s]",
       .ylabel = "T + U + P [J]",
       .caption = "Kinetic + strain + gravity energy of every dynamics run of the family "
                  "(energy.hpp, the same formulas for every scheme): constant without damping, "
                  "non-increasing with Kelvin-Voigt damping."});
  energy.figures.push_back(
      {.name = "dynamics_energy_schemes",
       .kind = "line",
       .x = "t",
       .y = {"mechanical"},
       .series = "case",
       .title = "Energy against time per scheme, viscous cantilever (N = 20)",
       .xlabel = "t [s]",
       .ylabel = "T + U + P [J]",
       .caption = "Kinetic + strain + gravity energy of the viscous cantilever (alpha = 300 Pa s, "
                  "released straight under gravity) per available scheme, from the same formulas "
                  "(energy.hpp): every scheme dissipates; the thesis-form shooting schemes "
                  "(implicit-midpoint, bdf-alpha) are softer (first order in s).",
       .select = "viscous cantilever:"});
}

void DynamicsData::add_drift_figures() {
  energy.figures.push_back(
      {.name = "dynamics_ledger",
       .kind = "semilogy",
       .x = "t",
       .y = {"ledger_error"},
       .series = "case",
       .title = "Energy ledger error against time",
       .xlabel = "t [s]",
       .ylabel = "|total(t) - total(0)| / scale",
       .caption = "Drift of T + U + P + dissipated - work_in, relative to the run's energy scale "
                  "(E0 of a release, max |gravity energy| otherwise); an exact solution keeps "
                  "it zero (zeros are not drawn on the log axis)."});
  det.figures.push_back(
      {.name = "dynamics_det",
       .kind = "semilogy",
       .x = "t",
       .y = {"det_deviation"},
       .series = "case",
       .title = "det R drift against time",
       .xlabel = "t [s]",
       .ylabel = "max_j |det R_j - 1|",
       .caption = "Largest deviation of det R from 1 over the nodes, every run of the family "
                  "(exact zeros are not drawn on the log axis)."});
  shapes.figures.push_back(
      {.name = "dynamics_shapes",
       .kind = "shape",
       .x = "z",
       .y = {"x"},
       .series = "case",
       .title = "Rod shapes at the end of the dynamics runs",
       .xlabel = "z [m]",
       .ylabel = "x [m]",
       .caption = "Centrelines at the end of the runs: the viscous cantilever (alpha = 300 Pa "
                  "s, N = 20) at 0.3 s per scheme, and the cantilever settled under gravity and "
                  "drag at 2.5 s (variational, N = 6, 11, 21) on the chebyshev statics "
                  "equilibrium (N = 24)."});
}

}  // namespace rodlab::validation::dynamics
