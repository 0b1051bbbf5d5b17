#pragma once
// What a study runs on: the checked scene, the schemes (from the catalogue), the resolutions
// and the run settings. cmd_study.cpp fills it from the command line; the validation report
// can fill it directly and call the study functions (study_convergence.hpp,
// study_work_precision.hpp, study_stability.hpp).
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/schemes.hpp"

namespace rodlab::validation::study {

using Json = nlohmann::json;

/// How a dynamics study refines and what its error is: the step at each N against ida at the
/// same N (time: the time error alone); N and the step together with dt proportional to ds,
/// against ida at a finer N (joint); or every step at every N against ida at a finer N (grid:
/// the error of space and time together, for work-precision and recommend).
enum class Refinement { time, joint, grid };

struct Settings {
  std::string scene_path;
  std::vector<std::string> overrides;  ///< the --set texts (part of the scene's identity)
  scene::Scene scene;
  solvers::Problem problem = solvers::Problem::statics;
  std::vector<solvers::SchemeInfo> schemes;  ///< schemes of `problem` to study
  std::vector<int> nodes;                    ///< empty: default_nodes()
  std::vector<double> dts;                   ///< dynamics; empty: auto / 2^k per scheme and N
  Refinement refine = Refinement::time;      ///< dynamics convergence studies
  std::optional<std::string> reference;      ///< --reference; nullopt: the default
  double tol = 1e-10;                        ///< nonlinear solver tolerance of every run
  double t_end = 0.0;                        ///< dynamics run length [s]
  int repeats = 1;                           ///< timed repeats (work-precision)
  std::vector<double> moduli;                ///< stability: Young's moduli [Pa]
  /// Dynamics (not stability): the spatial grids to sweep ("euler", "staggered", "corrected";
  /// --grids). Every grid is its own sweep, on the scene with solver.grid set to it and against
  /// its own reference (ida on that grid); `euler` only for the schemes that march it
  /// (takes_grid). Empty: the scene's grid alone, and no grid in the outputs' settings.
  std::vector<std::string> grids;
  std::string command_line;
};

/// Whether a dynamics scheme runs on `grid`: the thesis' Euler grid is a grid of the shooting
/// schemes (implicit-midpoint, bdf-alpha) only; every scheme takes staggered and corrected.
bool takes_grid(std::string_view scheme, std::string_view grid);
/// The grid `scheme` runs on when asked for `grid`: `grid`, or the default grid (staggered)
/// where the scheme does not march the Euler grid.
std::string run_grid(std::string_view scheme, const std::string& grid);
/// The grid the runs of `settings` (with grids empty) are on: solver.grid, else the default.
std::string scene_grid(const Settings& settings);
/// `settings` for one of its grids: the scene's solver.grid set to it, no grids.
Settings settings_on_grid(const Settings& settings, const std::string& grid);
/// The grids a study of the trade (work-precision, recommend) sweeps when neither --grids nor the
/// scene's solver.grid names one: the default grid and, where the scene takes it (a Cosserat rod
/// without actuators), the corrected grid, so that every grid the schemes could run competes
/// (issue #17: the fastest run to 1e-4 m on the cantilever is on the corrected grid). Empty (the
/// scene's grid alone) for statics, a scene that names its grid, or one the corrected grid
/// refuses.
std::vector<std::string> trade_grids(const Settings& settings);

/// Statics: 6, 11, 21, 41, 81 (ds halves); dynamics: 10, 20; joint refinement: 6, 11, 21, 41.
std::vector<int> default_nodes(solvers::Problem problem, Refinement refine = Refinement::time);
/// The nodes of the study (settings.nodes or the default).
std::vector<int> study_nodes(const Settings& settings);
/// The time steps of `scheme` at N nodes: settings.dts, or auto_time_step / {1, 2, 4, 8}.
std::vector<double> study_steps(const Settings& settings, const solvers::SchemeInfo& scheme,
                                int nodes);
/// Joint refinement: the step of `scheme` at each of `nodes` (ascending): dt_0 (settings.dts'
/// first value, or the scheme's auto_time_step at the coarsest N) times ds / ds_0, made an
/// exact divisor of t_end; for a scheme whose auto step is a stability limit (variational),
/// never above its limit at that N.
std::vector<double> joint_steps(const Settings& settings, const solvers::SchemeInfo& scheme,
                                const std::vector<int>& nodes);
/// Grid refinement: the steps of `scheme` at N nodes, study_steps made exact divisors of t_end,
/// and for a scheme whose auto step is a stability limit (variational) none above that limit
/// (descending, without repeats).
std::vector<double> grid_steps(const Settings& settings, const solvers::SchemeInfo& scheme,
                               int nodes);
/// "time", "joint" or "grid".
std::string_view to_string(Refinement refine);
/// The schemes of a problem class, in catalogue order.
std::vector<solvers::SchemeInfo> schemes_of(solvers::Problem problem);

/// The settings that determine a study's runs (for study.json and for reusing measurements).
Json settings_json(const Settings& settings);

/// Writes `content` to DIR/name atomically (DIR is created if missing).
void write_output(const std::string& dir, const std::string& name, const std::string& content);

/// "%.17g" (files), "" for NaN.
std::string csv_number(double v);
/// A CSV field, quoted when it contains a comma, quote or newline.
std::string csv_text(const std::string& text);

}  // namespace rodlab::validation::study
