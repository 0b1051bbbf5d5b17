#pragma once
// The options several subcommands share (interface spec section 2: --scheme, --nodes, --tol,
// --out, --set; dynamic adds --dt, --t-end, --output-every), their help lines, how they are
// read and checked, and how they combine with the scene's own settings (command-line
// options win over the scene).
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/dynamics/solve_dynamic.hpp"
#include "rodlab/solvers/schemes.hpp"
#include "rodlab/solvers/statics/solve_static.hpp"

#include "options.hpp"

namespace rodlab::cli {

inline constexpr OptionSpec kSchemeOption{
    "--scheme", "NAME", "scheme (`rodlab schemes` lists them); default: from the scene"};
inline constexpr OptionSpec kNodesOption{
    "--nodes", "N", "number of nodes along the rod, integer >= 2; default: solver.nodes"};
inline constexpr OptionSpec kTolOption{"--tol", "X", "solver tolerance > 0; default: solver.tol"};
inline constexpr OptionSpec kOutFileOption{
    "--out", "FILE", "write the result to FILE (.json or .csv); its directory must exist"};
inline constexpr OptionSpec kVtkOption{
    "--vtk", "DIR",
    "write ParaView files of the run (.vtp, and a .pvd for a time series) into DIR, created if "
    "missing (docs/visualisation.md)"};
inline constexpr OptionSpec kQuietOption{
    "--quiet", "", "no progress line on standard error (there is none unless it is a terminal)"};
inline constexpr OptionSpec kSetOption{
    "--set", "KEY=VALUE", "override a scene field by its dotted path, e.g. rod.material.E=2e6",
    true};
inline constexpr OptionSpec kDtOption{
    "--dt", "X|auto", "time step > 0, or auto (the explicit step (3.44)); default: dynamics.dt"};
inline constexpr OptionSpec kTimeOption{
    "--time", "T", "time >= 0 at which the scene's schedules are evaluated; default: 0"};
inline constexpr OptionSpec kTEndOption{"--t-end", "T", "end time > 0; default: dynamics.t_end"};
// The options whose defaults are the solvers' own: their help lines are made from the option
// structs (DynamicSolveOptions and the schemes' options), so they cannot disagree.
extern const OptionSpec kRtolOption;   ///< ida: rtol
extern const OptionSpec kAtolOption;   ///< ida: atol
extern const OptionSpec kAlphaOption;  ///< bdf-alpha: alpha
extern const OptionSpec kGridOption;   ///< implicit-midpoint, bdf-alpha: the march's grid
extern const OptionSpec kVariationalStepOption;  ///< variational: verlet or symplectic-euler

inline constexpr OptionSpec kMaxWallTimeOption{
    "--max-wall-time", "S",
    "stop the solve (exit 1, the result so far written, the reason naming the limit) once it has "
    "taken S seconds, S > 0; default: no limit"};
inline constexpr OptionSpec kOutputEveryOption{
    "--output-every", "K", "record every K-th step, integer >= 1; default: dynamics.output_every"};

/// The scheme `rodlab dynamic` uses without --scheme: dynamics.scheme, else solver.scheme
/// when that names a dynamics scheme, else the solvers' default (DynamicSolveOptions::scheme).
std::string scene_dynamics_scheme(const scene::Scene& scene);

/// A time step: a value, or automatic (the explicit step (3.44) from rod::characteristics).
struct TimeStep {
  bool automatic = true;
  double value = 0.0;
};

/// The shared options as given on the command line (not yet combined with the scene).
struct SolveOptions {
  std::string scene_path;
  std::vector<io::Override> overrides;
  std::optional<solvers::SchemeInfo> scheme;
  std::optional<int> nodes;
  std::optional<double> tol;
  std::optional<std::filesystem::path> out;
  std::optional<std::filesystem::path> vtk;  ///< --vtk DIR
  bool quiet = false;                        ///< --quiet: no progress line
  std::optional<double> time;  ///< static: when the schedules are evaluated
  // dynamic only
  std::optional<TimeStep> dt;
  std::optional<double> t_end;
  std::optional<int> output_every;
  std::optional<double> rtol, atol;
  std::optional<double> alpha;  ///< bdf-alpha
  std::optional<std::string> grid;  ///< implicit-midpoint, bdf-alpha: "euler" or "staggered"
  /// variational: "verlet" or "symplectic-euler"
  std::optional<std::string> variational_step;
  std::optional<double> max_wall_time;  ///< seconds
};

/// Reads the options of `command` that are among the shared ones above, recording problems
/// in `reader`. `problem` is the class of schemes the command takes.
SolveOptions read_solve_options(OptionReader& reader, solvers::Problem problem,
                                std::string_view command);

/// Every --set, parsed; a malformed one is recorded as a problem.
std::vector<io::Override> read_overrides(OptionReader& reader);

/// The scheme of that name if `command` (which takes `problem` schemes) can use it; otherwise
/// nullopt and `why` says what is wrong and lists the valid names.
std::optional<solvers::SchemeInfo> fitting_scheme(std::string_view name, solvers::Problem problem,
                                                  std::string_view command, std::string& why);

/// --out FILE: extension .json or .csv, existing directory, not a directory itself.
std::optional<std::filesystem::path> read_out_file(OptionReader& reader);
/// An output file's place: its directory exists and the file is not a directory. Records the
/// problem (naming `option`) and returns false otherwise.
bool check_out_file_place(OptionReader& reader, const std::filesystem::path& path,
                          std::string_view option = kOutFileOption.name);
/// --out DIR (or another directory option): not an existing non-directory.
std::optional<std::filesystem::path> read_out_dir(OptionReader& reader,
                                                  std::string_view option = kOutFileOption.name);

/// Loads and checks the scene with the overrides (throws io::SceneError).
scene::Scene load_checked_scene(const SolveOptions& options);

/// The settings of one run, command line over scene over the solvers' defaults: the scheme and
/// the options the solvers take (each default is written once, in the solvers' option structs).
struct StaticRun {
  solvers::SchemeInfo scheme;
  solvers::statics::StaticSolveOptions solve;
};
struct DynamicRun {
  solvers::SchemeInfo scheme;
  bool automatic_dt = true;  ///< dt: auto, until resolve_time_step() sets solve.dt
  solvers::dynamics::DynamicSolveOptions solve;
};

/// Replaces dt: auto by the scheme's automatic step (solvers::dynamics::auto_time_step).
void resolve_time_step(DynamicRun& run, const scene::Scene& scene);

/// Combine options and scene; throws io::SceneError when the scene's own scheme does not fit
/// (and --scheme does not replace it), or UsageError when dynamic lacks an end time.
StaticRun resolve_static_run(const SolveOptions& options, const scene::Scene& scene,
                             std::string_view command);
DynamicRun resolve_dynamic_run(const SolveOptions& options, const scene::Scene& scene,
                               std::string_view command);
/// The solver part of it alone (no time settings): scheme (--scheme, else `scene_scheme`,
/// checked to fit), nodes, tol, iterations, ida's tolerances, alpha, grid, the wall-time guard.
DynamicRun resolve_dynamic_solver(const SolveOptions& options, const scene::Scene& scene,
                                  std::string_view scene_scheme, std::string_view command);

/// The solver of a controller's plant (`rodlab control`, `rodlab train`): --scheme, else
/// dynamics.scheme, else implicit-midpoint (the thesis' plant), the rest as `rodlab dynamic`'s;
/// its step: dynamics.dt when set, else the plant's (dt_control, or stable steps for
/// variational; solvers/control/plant.hpp).
solvers::dynamics::DynamicSolveOptions resolve_plant_solver(const SolveOptions& options,
                                                            const scene::Scene& scene,
                                                            std::string_view command);

}  // namespace rodlab::cli
