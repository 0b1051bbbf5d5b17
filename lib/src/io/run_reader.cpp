// dynamics and solver settings, and the scheme names they accept.
#include <algorithm>
#include <array>

#include "rodlab/scene/schemes.hpp"

#include "scene_readers.hpp"

namespace rodlab::io {
namespace {

/// The names of all schemes, or of the dynamics schemes only (rodlab/scene/schemes.hpp).
std::vector<std::string_view> names(bool dynamics_only) {
  std::vector<std::string_view> out;
  for (const auto& s : scene::all_schemes())
    if (!dynamics_only || s.problem == scene::Problem::dynamics) out.push_back(s.name);
  return out;
}

}  // namespace

namespace detail {

scene::Dynamics read_dynamics(Checker& c, const Field& f) {
  scene::Dynamics d;
  if (!c.keys(f, {"t_end", "dt", "initial", "output_every", "scheme"})) return d;
  d.t_end = c.number(c.child(f, "t_end"), Range::positive());

  const Field dt = c.child(f, "dt");
  if (dt.present() && !(dt.node.IsScalar() && dt.node.Scalar() == "auto")) {
    if (dt.node.IsScalar() && !looks_like_number(dt.node))
      c.error(dt, "must be a number > 0 or auto (got " + describe(dt.node) + ")");
    else if ((d.dt = c.number(dt, Range::positive())) && d.t_end && *d.dt > *d.t_end)
      c.error(dt, "must not exceed t_end = " + format_number(*d.t_end) + " (got " +
                      describe(dt.node) + ")");
  }

  if (auto initial = c.choice(c.child(f, "initial"), {"straight", "static"}))
    d.initial = *initial == 0 ? scene::Initial::straight : scene::Initial::static_equilibrium;
  if (auto every = c.integer(c.child(f, "output_every"), 1)) d.output_every = *every;

  const Field scheme = c.child(f, "scheme");
  const auto dynamics_names = names(true);
  if (auto k = c.choice(scheme, dynamics_names)) d.scheme = std::string(dynamics_names[*k]);
  return d;
}

scene::Solver read_solver(Checker& c, const Field& f) {
  scene::Solver s;
  if (!c.keys(f, {"scheme", "nodes", "tol", "max_iterations", "alpha", "grid", "variational_step"}))
    return s;
  const auto all_names = names(false);
  if (auto k = c.choice(c.child(f, "scheme"), all_names)) s.scheme = std::string(all_names[*k]);
  if (auto nodes = c.integer(c.child(f, "nodes"), 2)) s.nodes = *nodes;
  if (auto tol = c.number(c.child(f, "tol"), Range::positive())) s.tol = *tol;
  if (auto it = c.integer(c.child(f, "max_iterations"), 1)) s.max_iterations = *it;
  // bdf-alpha: 0 is BDF2, -0.5 the trapezoidal rule (Till, Aloi & Rucker 2019)
  s.alpha = c.number(c.child(f, "alpha"), Range{-0.5, 0.0, false, false});
  // the spatial grid: of the shooting march (implicit-midpoint, bdf-alpha: euler, staggered) and
  // of variational (staggered, corrected); docs/dynamics.md
  static constexpr std::string_view kGrids[] = {"euler", "staggered", "corrected"};
  if (auto k = c.choice(c.child(f, "grid"), kGrids)) s.grid = std::string(kGrids[*k]);
  // variational: its time rule (docs/dynamics.md "Second order in time")
  static constexpr std::string_view kSteps[] = {"verlet", "symplectic-euler"};
  if (auto k = c.choice(c.child(f, "variational_step"), kSteps))
    s.variational_step = std::string(kSteps[*k]);
  return s;
}

}  // namespace detail
}  // namespace rodlab::io
