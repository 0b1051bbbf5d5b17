// The families of `rodlab validate`, in report order, and the loop that runs them.
#include <algorithm>
#include <array>
#include <exception>

#include "checks/check.hpp"

namespace rodlab::validation {

std::span<const CheckFamily> check_families() {
  // Add a family here (and its function in its own file, declared in validation_checks.hpp).
  static const std::array<CheckFamily, 8> families{{
      {"scenes", "example scenes load; derived quantities equal their closed forms", &scene_checks},
      {"statics", "statics schemes on the thesis's 2.7 problems and closed forms", &statics_checks},
      {"dynamics",
       "dynamics schemes on the Table 2.1 cantilever: bending frequency, energy with and without "
       "damping, det drift, stability limit, static limit, agreement between schemes and with IDA",
       &dynamics_checks},
      {"literature",
       "the classic rod benchmarks against independent references: the self-weight and the "
       "post-buckled elastica, Euler's and Greenhill's critical loads with the Cosserat "
       "corrections and lateral-torsional buckling, Bathe and Bolourchi's 45-degree bend, and "
       "the cantilever's natural frequencies against the Timoshenko beam (--full: every load, "
       "finer meshes and ida)",
       &literature_checks},
      {"studies",
       "the studies of `rodlab study` on example scenes: work-precision diagrams (statics and "
       "dynamics) with their Pareto fronts and `study recommend` answers verified against an "
       "independent reference; the stability map of the explicit scheme and the implicit "
       "schemes' step scans",
       &study_checks},
      {"control",
       "the thesis' Table 4.1 reproduced by `rodlab study control` on the cable robot: NLSQ-MPC "
       "on the implicit midpoint reaches every dynamic-workspace target and tracks the middle "
       "circle below the thesis' error (--full: every column, task and horizon)",
       &control_checks},
      {"learning",
       "the thesis' Table 4.1 learning columns by `rodlab study learning` on the cable robot: "
       "DDPG and GPS policies reach one dynamic-workspace point (--full: any point over five "
       "seeds, the middle circle, learning curves), in real time",
       &learning_checks},
      {"extremes",
       "every scheme at the extremes of material (E 1e3 .. 2e11 Pa), mesh (N 2 .. 1000) and step "
       "(dt 1e-7 .. 1 s), run as `rodlab` child processes: exit 0 only with finite results, "
       "otherwise exit 1 with a reason or exit 2 up front; no crash, no hang past the budget",
       &extremes_checks},
  }};
  return families;
}

std::vector<Check> run_checks(const ValidationContext& context, std::span<const std::string> only) {
  std::vector<Check> all;
  const auto selected = [&](std::string_view name) {
    return only.empty() || std::find(only.begin(), only.end(), name) != only.end();
  };
  int total = 0, done = 0;
  for (const auto& family : check_families()) total += selected(family.name) ? 1 : 0;
  for (const auto& family : check_families()) {
    if (!selected(family.name)) continue;
    if (context.on_family) context.on_family(family.name, done++, total);
    if (context.sink) context.sink->current_family = std::string(family.name);
    std::vector<Check> checks;
    try {
      checks = family.run(context);
    } catch (const std::exception& e) {
      checks = {boolean_check(std::string(family.name) + " family runs", false,
                              "runs without an exception", e.what())};
    }
    for (auto& c : checks) {
      c.family = std::string(family.name);
      all.push_back(std::move(c));
    }
  }
  if (context.on_family) context.on_family("", done, total);
  return all;
}

}  // namespace rodlab::validation
