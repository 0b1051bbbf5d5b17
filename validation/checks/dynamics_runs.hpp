#pragma once
// The runs and measurements of the "dynamics" family (dynamics_checks.cpp): the Table 2.1 rod's
// scenes, solve_dynamic with a bounded number of outputs, tip and energy metrics, and the data
// sets (with their figures) that the family's cases fill.
#include <string>
#include <string_view>
#include <vector>

#include "rodlab/result/dynamic_result.hpp"
#include "rodlab/scene/scene.hpp"

#include "checks/check.hpp"

// Data sets and figure specs are written with designated initializers; the fields left out keep
// their defaults on purpose.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace rodlab::validation::dynamics {

using result::DynamicResult;

/// The Table 2.1 rod with YAML under `loads:` and `tip: free:`; Kelvin-Voigt viscosity alpha.
scene::Scene rod_scene(const std::string& name, const std::string& loads, const std::string& tip,
                       double alpha);
/// Free vibration: held bent by a world tip force P (x) until t = 1e-9 s, then released at rest
/// from the static equilibrium; no gravity.
scene::Scene released(double P, double alpha);
/// scenes/viscous-cantilever.yaml: gravity [-9.81, 0, 0], released straight, viscosity alpha.
scene::Scene viscous_cantilever(double alpha);
/// The scheme's `dt: auto`.
double auto_dt(const scene::Scene& s, std::string_view scheme, int nodes);
/// solve_dynamic with about `outputs` recorded times.
result::DynamicResult simulate(const scene::Scene& s, const std::string& scheme, int nodes,
                               double dt, double t_end, scene::Initial initial, int outputs = 400);
/// "scheme, N = .., dt = .. s, .. steps, wall .. s" (and why it did not converge).
std::string run_text(const result::DynamicResult& r);
/// max_t |tip_a(t) - tip_b(t)| over a's times inside both runs (b interpolated linearly).
double max_tip_difference(const result::DynamicResult& a, const result::DynamicResult& b);
double max_abs(const std::vector<double>& v);
/// max_t |total(t) - total(0)|: the drift of the energy ledger.
double ledger_drift(const result::DynamicResult& r);
/// Largest rise of kinetic + strain + gravity between recorded times after `after`.
double max_mechanical_rise(const result::DynamicResult& r, double after = 0.0);

/// The data sets the family fills while it runs.
struct DynamicsData {
  DataSet tip{.name = "dynamics_tip",
              .description = "tip trajectories of the viscous cantilever (alpha = 300 Pa s, "
                             "gravity, released straight, N = 20) per scheme",
              .columns = {"scheme", "t", "x", "y", "z"}};
  DataSet energy{.name = "dynamics_energy",
                 .description = "energies against time per run: kinetic, strain, gravity, "
                                "dissipated, work_in, total (ledger), mechanical = T + U + P, "
                                "ledger_error = |total - total(0)| / scale",
                 .columns = {"case", "t", "kinetic", "strain", "gravity", "dissipated", "work_in",
                             "total", "mechanical", "ledger_error"}};
  DataSet det{.name = "dynamics_det",
              .description = "max |det R - 1| over the nodes against time per run",
              .columns = {"case", "t", "det_deviation"}};
  DataSet shapes{.name = "dynamics_shapes",
                 .description = "rod shapes at the end of dynamics runs (s, x, y, z), with the "
                                "statics equilibrium they settle on",
                 .columns = {"case", "s", "x", "y", "z"}};
  double worst_det = 0.0;
  std::string worst_det_case;

  /// Appends a centreline (s, x, y, z) to the shapes data set.
  void add_shape(const std::string& name, const std::vector<result::CenterlineSample>& c);

  /// Records a run's energies and det drift; `scale` normalises the ledger error.
  void add(const std::string& name, const DynamicResult& r, double scale);
  /// Records a run's tip trajectory under its scheme's name.
  void add_tip(const DynamicResult& r);
  /// Adds the figure specs and emits the four data sets.
  void emit(const ValidationContext& context);

 private:
  void add_trajectory_figures();  ///< tip trajectories, energies
  void add_drift_figures();       ///< ledger error, det R drift, shapes
};


}  // namespace rodlab::validation::dynamics
