#pragma once
// The scheme catalogue: every scheme's name (fixed by the interface spec, section 2), the problem
// it solves, its design order and kind. The one list of schemes: the scene loader checks
// solver.scheme and dynamics.scheme against it, the command line and the studies list and
// choose from it, and rodlab::solvers attaches each scheme's solver to its entry
// (rodlab/solvers/registry.hpp, checked complete at compile time). A scheme is added here and
// in solvers/registry.cpp (docs/development.md "How to add a scheme").
#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace rodlab::scene {

enum class Problem { statics, dynamics };

/// One per scheme, in the catalogue's order (the index into all_schemes()).
enum class SchemeId {
  rkmk_euler_explicit,
  rkmk_euler_implicit,
  rkmk_midpoint_explicit,
  rkmk_midpoint_implicit,
  rkmk_rk4,
  chebyshev,
  kinsol,
  variational,
  implicit_midpoint,
  implicit_midpoint_collocation,
  bdf_alpha,
  ida,
};
inline constexpr int kSchemeCount = static_cast<int>(SchemeId::ida) + 1;

struct SchemeInfo {
  SchemeId id;
  std::string_view name;
  Problem problem;
  std::string_view order;   ///< design order: statics "1", "2", "4", ">=4", "spectral"; dynamics "p (t) / q (s)"
  bool implicit;            ///< implicit in the marching direction (s for statics, t for dynamics)
  bool reference;           ///< the SUNDIALS reference of its problem class
  std::string_view method;  ///< one-line description
};

/// The catalogue, statics first, in the order of the spec's tables.
inline constexpr std::array<SchemeInfo, kSchemeCount> kSchemeCatalogue{{
    {SchemeId::rkmk_euler_explicit, "rkmk-euler-explicit", Problem::statics, "1", false, false,
     "shooting, explicit Euler RKMK"},
    {SchemeId::rkmk_euler_implicit, "rkmk-euler-implicit", Problem::statics, "1", true, false,
     "shooting, implicit Euler RKMK"},
    {SchemeId::rkmk_midpoint_explicit, "rkmk-midpoint-explicit", Problem::statics, "2", false,
     false, "shooting, explicit midpoint RKMK"},
    {SchemeId::rkmk_midpoint_implicit, "rkmk-midpoint-implicit", Problem::statics, "2", true,
     false, "shooting, implicit midpoint RKMK"},
    {SchemeId::rkmk_rk4, "rkmk-rk4", Problem::statics, "4", false, false,
     "shooting, classical RK4 Munthe-Kaas, dexp^-1 series of order 2"},
    {SchemeId::chebyshev, "chebyshev", Problem::statics, "spectral", true, false,
     "Chebyshev-Lobatto pseudospectral collocation, Newton with a dense Jacobian"},
    {SchemeId::kinsol, "kinsol", Problem::statics, ">=4", true, true,
     "reference: Lie-group Hermite-Simpson (RKMK Lobatto IIIA) collocation, KINSOL with an "
     "almost block diagonal LU"},
    {SchemeId::variational, "variational", Problem::dynamics, "2 (t) / 2 (s)", false, false,
     "explicit discrete variational Lie-group integrator (thesis Algorithm 1), Stormer-Verlet "
     "start (first order in t as the thesis: solver.variational_step symplectic-euler)"},
    {SchemeId::implicit_midpoint, "implicit-midpoint", Problem::dynamics, "2 (t) / 2 (s)", true,
     false,
     "implicit midpoint in time, shooting in space on the staggered grid (single; multiple "
     "below its step bound) (thesis Algorithm 2, explicit RKMK, first order in s: solver.grid "
     "euler)"},
    {SchemeId::implicit_midpoint_collocation, "implicit-midpoint-collocation", Problem::dynamics,
     "2 (t) / 2 (s)", true, false,
     "implicit midpoint in time, each step's BVP solved globally by KINSOL + KLU"},
    {SchemeId::bdf_alpha, "bdf-alpha", Problem::dynamics, "2 (t) / 2 (s)", true, false,
     "BDF-alpha in time (Till, Aloi & Rucker 2019), shooting in space on the staggered grid "
     "(single; multiple below its step bound) (first order in s: solver.grid euler)"},
    {SchemeId::ida, "ida", Problem::dynamics, "BDF 1-5 (t) / 2 (s)", true, true,
     "reference: method of lines in s, SUNDIALS IDA with KLU at tight tolerances"},
}};

namespace detail {
constexpr bool catalogue_indexed_by_id() {
  for (int i = 0; i < kSchemeCount; ++i)
    if (static_cast<int>(kSchemeCatalogue[i].id) != i) return false;
  return true;
}
static_assert(catalogue_indexed_by_id(), "kSchemeCatalogue must list the schemes in SchemeId order");
}  // namespace detail

/// The fewest nodes a scheme of the problem runs on (statics: a segment; dynamics: a node
/// between base and tip): the one rule of the option check, the studies and the solvers.
constexpr int min_nodes(Problem problem) { return problem == Problem::statics ? 2 : 3; }

/// All schemes, statics first, in the order of the spec's tables (all_schemes()[i].id == i).
std::span<const SchemeInfo> all_schemes();
const SchemeInfo& scheme_info(SchemeId id);

/// The scheme of that name, or nullopt.
std::optional<SchemeInfo> find_scheme(std::string_view name);

/// "a, b, c": the names of the schemes for a problem (for error messages).
std::string scheme_names(Problem problem);

std::string_view to_string(Problem problem);

}  // namespace rodlab::scene
