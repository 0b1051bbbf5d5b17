#include "rodlab/solvers/schemes.hpp"

#include <array>

namespace rodlab::solvers {
namespace {

constexpr std::string_view kStaticsIssue = "the statics issue (#3)";
constexpr std::string_view kDynamicsIssue = "the dynamics issue (#4)";

constexpr std::array<SchemeInfo, 12> kSchemes{{
    {"rkmk-euler-explicit", Problem::statics, "1", false, false,
     "shooting, explicit Euler RKMK", ""},
    {"rkmk-euler-implicit", Problem::statics, "1", true, false,
     "shooting, implicit Euler RKMK", ""},
    {"rkmk-midpoint-explicit", Problem::statics, "2", false, false,
     "shooting, explicit midpoint RKMK", ""},
    {"rkmk-midpoint-implicit", Problem::statics, "2", true, false,
     "shooting, implicit midpoint RKMK", ""},
    {"rkmk-rk4", Problem::statics, "4", false, false,
     "shooting, classical RK4 Munthe-Kaas, dexp^-1 series of order 2", ""},
    {"chebyshev", Problem::statics, "spectral", true, false,
     "Chebyshev-Lobatto pseudospectral collocation, Newton with a dense Jacobian", ""},
    {"kinsol", Problem::statics, ">=4", true, true,
     "reference: Lie-group Hermite-Simpson (RKMK Lobatto IIIA) collocation, KINSOL + KLU", ""},
    {"variational", Problem::dynamics, "1 (t) / 2 (s)", false, false,
     "explicit discrete variational Lie-group integrator (thesis Algorithm 1)", ""},
    {"implicit-midpoint", Problem::dynamics, "2 (t) / 1 (s)", true, false,
     "implicit midpoint in time, explicit RKMK in space, single shooting (thesis Algorithm 2)",
     ""},
    {"implicit-midpoint-collocation", Problem::dynamics, "2 (t) / 2 (s)", true, false,
     "implicit midpoint in time, each step's BVP solved globally by KINSOL + KLU", ""},
    {"bdf-alpha", Problem::dynamics, "2 (t) / 1 (s)", true, false,
     "BDF-alpha in time with shooting in space (Till, Aloi & Rucker 2019)", ""},
    {"ida", Problem::dynamics, "BDF 1-5 (t) / 2 (s)", true, true,
     "reference: method of lines in s, SUNDIALS IDA with KLU at tight tolerances", ""},
}};

}  // namespace

std::span<const SchemeInfo> all_schemes() { return kSchemes; }

std::optional<SchemeInfo> find_scheme(std::string_view name) {
  for (const auto& s : kSchemes)
    if (s.name == name) return s;
  return std::nullopt;
}

std::string scheme_names(Problem problem) {
  std::string out;
  for (const auto& s : kSchemes) {
    if (s.problem != problem) continue;
    if (!out.empty()) out += ", ";
    out += s.name;
  }
  return out;
}

std::string_view to_string(Problem problem) {
  return problem == Problem::statics ? "statics" : "dynamics";
}

}  // namespace rodlab::solvers
