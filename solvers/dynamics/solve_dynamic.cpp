#include "rodlab/solvers/dynamics/solve_dynamic.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "rodlab/check.hpp"
#include "rodlab/rod/energies.hpp"
#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/dynamics/corrected_grid.hpp"
#include "rodlab/solvers/dynamics/shooting/step_bound.hpp"
#include "rodlab/solvers/dynamics/time_step.hpp"
#include "rodlab/solvers/registry.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

namespace rodlab::solvers::dynamics {
namespace {

/// Static-equilibrium start: rkmk-rk4 on a grid refined by this factor, sampled at the nodes.
constexpr int kStaticRefinement = 4;
/// A run is unstable once kinetic + strain energy exceed this multiple of the energy the scene
/// can account for (see energy_budget).
constexpr double kUnstableFactor = 1e3;

/// How far (scaled, DynamicProblem::clamp_mismatch) a clamp may sit from the rest shape's tip
/// for `initial: straight`: rounding of base exp(L xi*) against the scene's numbers.
constexpr double kClampRestTolerance = 1e-9;

/// An energy scale the run can legitimately reach: the strain energy of a quarter-circle bend,
/// plus what gravity and the inputs have exchanged so far, plus the initial energy.
double energy_budget(const DynamicProblem& problem, const Energy& e0, const Energy& e) {
  const auto& K = problem.model().K_diag();
  const double L = problem.length();
  const double bend = 0.5 * std::min(K[0], K[1]) * std::pow(0.5 * std::numbers::pi / L, 2) * L;
  return bend + std::abs(e.gravity) + std::abs(e.work_in) + std::abs(e0.mechanical());
}

}  // namespace

RestState rest_shape(const DynamicProblem& problem, int nodes) {
  const double ds = problem.length() / (nodes - 1);
  RestState state{std::vector<SE3>(nodes), std::vector<Vector6>(nodes)};
  for (int j = 0; j < nodes; ++j) {
    state.g[j] = rod::reference_pose(problem.model(), problem.base(), j * ds);
    state.xi[j] = problem.model().node_xi_star(j, nodes);
  }
  return state;
}

RestState initial_state(const scene::Scene& scene, const DynamicProblem& problem,
                        const DynamicSolveOptions& options, std::string& failure) {
  const int n = options.nodes;
  RestState state = rest_shape(problem, n);
  if (options.initial == scene::Initial::straight) {
    if (problem.tip_clamped()) {
      const double miss = problem.clamp_mismatch(problem.reference_tip()).lpNorm<Eigen::Infinity>();
      RODLAB_THROW_UNLESS(
          miss <= kClampRestTolerance,
          "tip.clamped: the clamp's pose is not the rest shape's tip pose (scaled mismatch "
          "{:.3g}), so dynamics.initial: straight is not a state of the rod; use "
          "dynamics.initial: static (the clamped equilibrium under the t = 0 loads)",
          miss);
    }
    return state;
  }
  // The shooting schemes on the Euler grid rebuild their poses from the node strains by explicit
  // Euler RKMK, which misses a clamp by O(ds) with rk4's strains; with a clamped tip they start
  // from the statics of their own grid (rkmk-euler-explicit at N: the same recursion at eta = 0,
  // xi_dot = 0). The staggered grid takes its strains from the poses and meets the clamp exactly.
  const bool own_grid =
      problem.tip_clamped() && options.grid == ShootingGrid::euler && marches_in_s(options.scheme);
  const int refinement = own_grid ? 1 : kStaticRefinement;
  statics::StaticSolveOptions so;
  so.scheme = own_grid ? "rkmk-euler-explicit" : "rkmk-rk4";
  so.nodes = refinement * (n - 1) + 1;
  so.tol = std::min(options.tol, 1e-10);
  so.max_iterations = std::max(options.max_iterations, 50);
  const auto eq = statics::solve_static(scene, so);
  if (!eq.converged) failure = "the initial static equilibrium did not converge: " + eq.reason;
  if (eq.centerline.size() != static_cast<std::size_t>(refinement * (n - 1) + 1))
    return state;  // no solution to start from; failure says why
  for (int j = 0; j < n; ++j) {
    state.g[j] = eq.centerline[refinement * j].pose;
    state.xi[j] = eq.centerline[refinement * j].twist;
  }
  state.equilibrium = true;
  return state;
}

void apply_scene_options(const scene::Scene& scene, DynamicSolveOptions& options) {
  options.alpha = scene.solver.alpha.value_or(options.alpha);
  if (scene.solver.grid) {
    const auto grid = shooting_grid_from_name(*scene.solver.grid);
    if (!grid) throw std::invalid_argument("solver.grid: must be euler, staggered or corrected");
    options.grid = *grid;
  }
  if (scene.solver.variational_step) {
    const auto step = variational_step_from_name(*scene.solver.variational_step);
    if (!step)
      throw std::invalid_argument("solver.variational_step: must be verlet or symplectic-euler");
    options.variational_step = *step;
  }
  if (scene.dynamics) options.initial = scene.dynamics->initial;
}

DynamicProblem problem_on_grid(DynamicProblem problem, const DynamicSolveOptions& options) {
  if (options.grid != ShootingGrid::corrected) return problem;
  require_corrected_grid(problem);
  return corrected_grid_problem(problem, options.nodes);
}

DynamicProblem scene_problem_on_grid(const scene::Scene& scene, std::string_view scheme,
                                     int nodes) {
  DynamicSolveOptions options;
  options.scheme = std::string(scheme);
  options.nodes = nodes;
  apply_scene_options(scene, options);
  return problem_on_grid(DynamicProblem::from_scene(scene), options);
}

bool marches_in_s(std::string_view scheme) {
  const auto info = find_scheme(scheme);
  return info && (info->id == SchemeId::implicit_midpoint || info->id == SchemeId::bdf_alpha);
}

std::string step_problem(const DynamicProblem& problem, const DynamicSolveOptions& options,
                         double dt) {
  if (!marches_in_s(options.scheme)) return {};
  return shooting_step_problem(problem, options.scheme, options.grid, dt, options.tol);
}

result::DynamicResult solve_dynamic(const scene::Scene& scene, const DynamicSolveOptions& options) {
  RODLAB_THROW_UNLESS(options.nodes >= min_nodes(Problem::dynamics), "nodes must be >= {}",
                      min_nodes(Problem::dynamics));
  if (!(options.dt > 0.0) || !std::isfinite(options.dt))
    throw std::invalid_argument("dt must be > 0");
  if (!(options.t_end > 0.0) || !std::isfinite(options.t_end))
    throw std::invalid_argument("t_end must be > 0");
  if (options.output_every < 1) throw std::invalid_argument("output_every must be >= 1");
  if (!(options.max_wall_time >= 0.0) || !std::isfinite(options.max_wall_time))
    throw std::invalid_argument("max_wall_time must be >= 0");
  const SchemeInfo& scheme = scheme_for(options.scheme, Problem::dynamics);
  const DynamicProblem problem = problem_on_grid(DynamicProblem::from_scene(scene), options);

  result::DynamicResult out;
  out.scene = scene.name;
  out.scheme = options.scheme;
  out.nodes = options.nodes;
  // Equal steps that end exactly at t_end (a variational integrator keeps its step).
  const long steps = std::max(1L, std::lround(std::ceil(options.t_end / options.dt - 1e-9)));
  const double dt = options.t_end / static_cast<double>(steps);
  // refused before it starts where shooting cannot converge (step_bound.hpp)
  if (const std::string why = step_problem(problem, options, dt); !why.empty())
    throw std::invalid_argument(why);
  out.dt = dt;
  const auto start = std::chrono::steady_clock::now();
  const DeadlineScope deadline(options.max_wall_time);
  std::string failure;
  const RestState initial = initial_state(scene, problem, options, failure);
  const std::unique_ptr<Stepper> stepper =
      stepper_factory(scheme.id)(problem, options, initial);

  const Energy e0 = stepper->energy();
  double observer_time = 0.0;  // [s] spent in options.on_output
  auto record = [&](double t) {
    if (options.on_output) {
      const auto t0 = std::chrono::steady_clock::now();
      options.on_output(t, *stepper);
      observer_time += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    const Energy e = stepper->energy();
    out.t.push_back(t);
    out.tip_position.push_back(stepper->tip_position());
    out.energy.kinetic.push_back(e.kinetic);
    out.energy.strain.push_back(e.strain);
    out.energy.gravity.push_back(e.gravity);
    out.energy.dissipated.push_back(e.dissipated);
    out.energy.work_in.push_back(e.work_in);
    out.energy.total.push_back(e.total());
    out.max_det_deviation.push_back(stepper->max_det_deviation());
    const double active = e.kinetic + e.strain;
    if (!failure.empty()) return;  // a failed step's own reason (it names t and dt) stays
    if (!std::isfinite(e.total()) || !out.tip_position.back().allFinite())
      failure = rodlab::format("unstable: the state became non-finite by t = {:g} s", t);
    else if (active > kUnstableFactor * energy_budget(problem, e0, e))
      failure = rodlab::format("unstable: kinetic + strain energy grew to {:g} J by t = {:g} s",
                               active, t);
  };
  record(0.0);
  long done = 0;
  double t = 0.0;
  while (failure.empty() && done < steps) {
    const double t1 = done + 1 == steps ? options.t_end : static_cast<double>(done + 1) * dt;
    StepStatus status;
    try {
      status = stepper->step(t, dt);
      if (status.ok && done + 1 < steps) check_deadline();  // and between steps
    } catch (const WallTimeExceeded& e) {  // common/deadline.hpp
      status = StepStatus::failed(rodlab::format("{} in the step from t = {:g} s", e.what(), t));
    }
    ++done;
    t = t1;
    if (!status.ok) {
      failure = status.reason;
      record(std::isfinite(status.reached) ? status.reached : t);
      break;
    }
    if (done % options.output_every == 0 || done == steps) record(t);
    if (options.on_step) options.on_step(done, steps, t, dt);
  }
  out.steps = done;
  if (!failure.empty() && scheme.id == SchemeId::variational) {
    // the explicit scheme above its stability limit: say so, and what to use
    const double limit = variational_stable_step(problem, options.nodes);
    if (dt > limit)
      failure += rodlab::format(
          "; dt = {:g} s is {:.3g} times variational's stability limit {:.3g} s (time_step.hpp): "
          "use dt: auto, or an implicit scheme (implicit-midpoint, "
          "implicit-midpoint-collocation, ida)",
          dt, dt / limit, limit);
  }
  out.converged = failure.empty();
  out.reason = failure;
  out.final_centerline = stepper->centerline();
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
      observer_time;
  out.real_time_ratio = t > 0.0 ? out.wall_time_s / t : 0.0;
  return out;
}

}  // namespace rodlab::solvers::dynamics
