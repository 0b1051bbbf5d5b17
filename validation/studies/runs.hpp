#pragma once
// One run of a study: a scheme at N nodes (and a time step, for dynamics) on a scene, timed
// over repeats, reduced to what the studies compare (the tip position at the end, the tip
// trajectory for dynamics) and serialised as JSON so that runs made on other ranks or threads
// come back bit for bit.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rodlab/lie/se3.hpp"
#include "rodlab/scene/scene.hpp"
#include "rodlab/solvers/schemes.hpp"

namespace rodlab::validation::study {

using Json = nlohmann::json;

/// What to run.
struct RunSpec {
  std::string scheme;
  solvers::Problem problem = solvers::Problem::statics;
  int nodes = 0;
  double dt = 0.0;      ///< requested step (dynamics); 0 for statics
  double t_end = 0.0;   ///< dynamics
  double tol = 1e-10;   ///< nonlinear solver tolerance
  int repeats = 1;      ///< timed repetitions (the result is the same every time)
  bool keep_series = true;  ///< dynamics: keep the tip trajectory (for errors over time)
  /// The study's reference run (docs/studies.md "recommend"); on the scene's grid, as every run.
  bool reference = false;
};

/// What came out.
struct RunRecord {
  std::string scheme;
  int nodes = 0;
  double dt = 0.0;  ///< the step used (t_end / steps; 0 for statics)
  long steps = 0;
  bool converged = false;
  std::string reason;
  double wall_time_s = 0.0;      ///< median over the repeats
  double wall_time_min_s = 0.0;  ///< fastest repeat
  int repeats = 0;
  double t_reached = 0.0;
  lie::Vector3 tip = lie::Vector3::Zero();  ///< tip position at the end [m]
  std::vector<double> t;                    ///< dynamics: output times [s]
  std::vector<lie::Vector3> tips;           ///< dynamics: tip positions at t [m]
};

/// A repeat that takes longer than this [s] is not repeated (quick single runs for slow cases).
inline constexpr double kSlowRunSeconds = 2.0;

/// Runs the spec. Solver exceptions (a feature the scheme does not support) become a record
/// with converged = false and the message as the reason.
RunRecord run_case(const scene::Scene& scene, const RunSpec& spec);

Json to_json(const RunRecord& record);
RunRecord record_from_json(const Json& json);

}  // namespace rodlab::validation::study
