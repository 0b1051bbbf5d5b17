#include "rodlab/solvers/statics/workspace.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>
#include <variant>

#include "rodlab/check.hpp"

namespace rodlab::solvers::statics {
namespace {

WorkspaceInput input_of(scene::Actuator& actuator, std::size_t index) {
  struct Visit {
    WorkspaceInput operator()(scene::Cable& c) const {
      return {c.tension ? &*c.tension : &*c.displacement, c.limits.value_or(std::pair{NAN, NAN})};
    }
    WorkspaceInput operator()(scene::Fluidic& f) const {
      return {f.pressure ? &*f.pressure : &*f.volume, f.limits.value_or(std::pair{NAN, NAN})};
    }
    WorkspaceInput operator()(scene::Muscle& m) const {
      return {&m.input, m.limits.value_or(std::pair{NAN, NAN})};
    }
  };
  WorkspaceInput in = std::visit(Visit{}, actuator);
  RODLAB_THROW_UNLESS(!std::isnan(in.limits.first),
                      "actuators.{}: the workspace needs `limits: [min, max]` on every actuator",
                      index);
  return in;
}

}  // namespace

std::vector<WorkspaceInput> workspace_inputs(scene::Scene& scene) {
  if (scene.actuators.empty()) throw std::invalid_argument("the workspace needs actuators");
  std::vector<WorkspaceInput> inputs;
  for (std::size_t k = 0; k < scene.actuators.size(); ++k) inputs.push_back(input_of(scene.actuators[k], k));
  return inputs;
}

double workspace_uniform(std::mt19937& rng, double lo, double hi) {
  const double u = static_cast<double>(rng()) / static_cast<double>(std::mt19937::max());
  return lo + u * (hi - lo);
}

WorkspaceBounds fit_workspace_bounds(std::span<const result::WorkspaceSample> samples) {
  WorkspaceBounds b;
  bool first = true;
  for (const auto& sample : samples) {
    if (!sample.converged) continue;
    const auto& c = sample.coordinates;
    b.omega_bound = first ? c.omega : std::max(b.omega_bound, c.omega);
    b.eps_low = first ? c.epsilon : std::min(b.eps_low, c.epsilon);
    b.eps_high = first ? c.epsilon : std::max(b.eps_high, c.epsilon);
    first = false;
  }
  return b;
}

WorkspaceCoordinates workspace_coordinates(const Vector3& p, double L) {
  const double rho = std::hypot(p.x(), p.y());
  WorkspaceCoordinates c;
  c.omega = 2.0 / L * std::atan2(rho, p.z());  // (2.122), atan2 for tips past 90 degrees
  c.phi = rho > 0.0 ? std::atan2(p.x(), -p.y()) : 0.0;  // (2.121), (2.126)
  // Chord |p| = 2 sin(omega L/2)/omega (1 + eps) = L sinc(omega L/2) (1 + eps): (2.127) at omega = 0.
  const double half = 0.5 * c.omega * L;
  c.epsilon = p.norm() / (L * lie::coefficients::sinc(half)) - 1.0;
  return c;
}

Vector3 workspace_tip(const WorkspaceCoordinates& c, double L) {  // (2.120), (2.124)
  const double half = 0.5 * c.omega * L;
  const double lateral = L * std::sin(half) * lie::coefficients::sinc(half);  // 2 sin^2(wL/2)/w
  const double axial = L * lie::coefficients::sinc(c.omega * L);              // sin(wL)/w
  return (1.0 + c.epsilon) * Vector3(lateral * std::sin(c.phi), -lateral * std::cos(c.phi), axial);
}

bool workspace_contains(const WorkspaceBounds& b, const Vector3& p, double L, double margin) {
  const auto c = workspace_coordinates(p, L);
  return c.omega <= b.omega_bound + margin && c.epsilon >= b.eps_low - margin &&
         c.epsilon <= b.eps_high + margin;
}

result::WorkspaceResult sample_workspace(const scene::Scene& scene_in, const StaticSolveOptions& options,
                                         int samples, unsigned seed,
                                         const std::function<void(int, int)>& progress) {
  if (samples < 1) throw std::invalid_argument("samples must be >= 1");
  const auto start = std::chrono::steady_clock::now();
  scene::Scene scene = scene_in;
  const std::vector<WorkspaceInput> inputs = workspace_inputs(scene);

  result::WorkspaceResult out;
  out.scene = scene.name;
  out.scheme = options.scheme;
  out.nodes = options.nodes;
  out.length = scene.rod.length;
  out.seed = seed;
  std::mt19937 rng(seed);
  const lie::SE3 base_inv = scene.base.pose.inverse();
  for (int i = 0; i < samples; ++i) {
    result::WorkspaceSample sample;
    for (const auto& in : inputs) {
      const double v = workspace_uniform(rng, in.limits.first, in.limits.second);
      *in.value = scene::ScalarSchedule(v);
      sample.inputs.push_back(v);
    }
    const auto r = solve_static(scene, options);
    sample.converged = r.converged;
    sample.tip = base_inv * r.centerline.back().pose.translation();
    sample.coordinates = workspace_coordinates(sample.tip, scene.rod.length);
    if (!sample.converged) ++out.failed;
    out.samples.push_back(std::move(sample));
    if (progress) progress(i + 1, samples);
  }
  out.bounds = fit_workspace_bounds(out.samples);
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace rodlab::solvers::statics
