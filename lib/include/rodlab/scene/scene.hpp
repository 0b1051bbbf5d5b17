#pragma once
// A scene (schema rodlab.scene/1, docs/scene-reference.md) as typed structs whose field names
// match the YAML keys. Loading and checking live in rodlab/io/scene_loader.hpp.
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "rodlab/lie/se3.hpp"
#include "rodlab/rod/material.hpp"
#include "rodlab/rod/rod_model.hpp"
#include "rodlab/rod/section.hpp"
#include "rodlab/scene/schedule.hpp"

namespace rodlab::scene {

using Vector2 = Eigen::Vector2d;
using Vector3 = Eigen::Vector3d;
using Vector6 = lie::Vector6;

inline constexpr const char* kSceneSchema = "rodlab.scene/1";

enum class Frame { body, world };
enum class Initial { straight, static_equilibrium };  // YAML: straight | static

struct Rod {
  rod::ModelKind model = rod::ModelKind::cosserat;
  double length = 0.0;
  rod::Section section;
  rod::Material material;
  Vector6 reference_twist = rod::RodModel::straight_twist();
  /// rest_strain.spans: the rest strain piecewise over spans (empty: reference_twist along the
  /// whole rod).
  std::vector<rod::RestSpan> rest_spans;
  int rest_spans_line = 0, rest_spans_column = 0;  ///< where the scene gives them (1-based)

  rod::RodModel to_model() const {
    if (!rest_spans.empty()) return {length, section, material, model, rest_spans};
    return {length, section, material, model, reference_twist};
  }
};

struct Base {
  lie::SE3 pose;
};

struct Wrench {
  VectorSchedule moment{Vector3::Zero()};
  VectorSchedule force{Vector3::Zero()};
  Frame frame = Frame::body;
};

struct FreeTip {
  Wrench wrench;
};
struct ClampedTip {
  lie::SE3 pose;
};
using Tip = std::variant<FreeTip, ClampedTip>;

struct Drag {
  double fluid_density = 0.0;
  Vector6 laminar = Vector6::Zero();    ///< D_lam diagonal (3.11)
  Vector6 turbulent = Vector6::Zero();  ///< D_turb diagonal (3.12)
};

struct Buoyancy {
  double fluid_density = 0.0;  ///< gravity acts on rho - fluid_density (2.36)
};

/// A uniform distributed wrench per unit length (loads.distributed).
struct DistributedWrench {
  VectorSchedule moment{Vector3::Zero()};
  VectorSchedule force{Vector3::Zero()};
  Frame frame = Frame::world;
};

struct Loads {
  std::optional<Vector3> gravity;
  std::optional<Drag> drag;
  std::optional<Buoyancy> buoyancy;
  std::optional<DistributedWrench> distributed;
};

/// Where an actuator sits in the section: a constant offset [x, y, 0], or a routing
/// [[s, x, y], ...] interpolated linearly in s.
struct Offset {
  std::vector<std::pair<double, Vector2>> points;  ///< one point: constant
  Vector2 at(double s) const;
};

struct Span {
  double s0 = 0.0, s1 = 0.0;
};

struct Cable {
  Offset offset;
  std::optional<ScalarSchedule> tension;       ///< [N]; exactly one of tension, displacement
  std::optional<ScalarSchedule> displacement;  ///< [m], cable pulled in (2.47)
  std::optional<Span> span;
  std::optional<std::pair<double, double>> limits;  ///< input range for the workspace
};

struct Fluidic {
  Offset offset;
  double chamber_radius = 0.0;
  std::optional<ScalarSchedule> pressure;  ///< [Pa]; exactly one of pressure, volume
  std::optional<ScalarSchedule> volume;    ///< [m^3]
  std::optional<Span> span;
  std::optional<std::pair<double, double>> limits;
};

struct MuscleLaw {
  std::string type = "linear";  ///< force = gain q - stiffness (Delta - Delta*) / Delta*
  double gain = 0.0;
  double stiffness = 0.0;
};

struct Muscle {
  Offset offset;
  rod::Section section;
  rod::Material material;
  ScalarSchedule input{0.0};  ///< q
  MuscleLaw law;
  std::optional<Span> span;
  std::optional<std::pair<double, double>> limits;
};

using Actuator = std::variant<Cable, Fluidic, Muscle>;

struct Dynamics {
  std::optional<double> t_end;
  std::optional<double> dt;  ///< nullopt: auto
  Initial initial = Initial::straight;
  int output_every = 1;
  std::optional<std::string> scheme;
};

struct Solver {
  std::string scheme = "chebyshev";
  int nodes = 24;
  double tol = 1e-10;
  int max_iterations = 50;
  std::optional<double> alpha;  ///< `bdf-alpha`: alpha in [-0.5, 0]; nullopt: the scheme's default
  /// `implicit-midpoint`, `bdf-alpha`: the march's spatial grid, "euler" (the thesis) or
  /// "staggered"; nullopt: euler
  std::optional<std::string> grid;
  /// `variational`: "verlet" (second order) or "symplectic-euler" (the thesis); nullopt: verlet
  std::optional<std::string> variational_step;
};

enum class ControlTask { reach, hold, track };  // YAML: reach | hold | track

/// A circle traced at constant speed (control.trajectory.circle); evaluated by
/// rodlab/scene/trajectory.hpp.
struct CircleTrajectory {
  Vector3 center = Vector3::Zero();   ///< [m], world frame
  double radius = 0.0;                ///< [m], > 0
  double period = 0.0;                ///< [s] per lap, > 0
  double laps = 1.0;                  ///< > 0; fractional laps stop part-way round
  Vector3 normal = Vector3::UnitZ();  ///< unit normal of the circle's plane (normalised on load)
};

/// control.trajectory: the path a `track` task follows.
struct Trajectory {
  CircleTrajectory circle;
};

/// control.weights: the dimensionless weights of the controllers' cost (docs/scene-reference.md
/// "control"): positions are scaled by the rod length L, inputs by their limits' range.
struct ControlWeights {
  double input_rate = 1e-3;  ///< on ||(u_k - u_k-1) / (u_max - u_min)||^2
  double input = 0.0;        ///< on ||(u_k - u_min) / (u_max - u_min)||^2
  double terminal = 1.0;     ///< on the last step's ||p - p_des||^2 / L^2 (stage steps weigh 1)
};

/// The schemes a controller can predict with for a plant of another scheme (control.model_scheme):
/// those whose tangent coordinates are their whole state (bdf-alpha's history x_(i-1), x_dot_i is
/// not; ida has no plant); docs/control.md "Model and plant".
inline constexpr std::string_view kModelSchemes[] = {"implicit-midpoint",
                                                     "implicit-midpoint-collocation", "variational"};

/// control: the task and settings of `rodlab control`; command-line options win.
struct Control {
  ControlTask task = ControlTask::reach;  ///< default: track with a trajectory, else reach
  std::vector<Vector3> targets;           ///< [m], world frame; empty: drawn from the workspace
  std::optional<Trajectory> trajectory;   ///< at most one of targets and trajectory
  int horizon = 10;                       ///< control steps predicted
  /// Solver iterations per control step of a predictive controller (nlsq-mpc: Levenberg-
  /// Marquardt iterations per plan; ilqr: iLQR iterations); empty: the controller's default.
  /// 1 is the real-time iteration: one iteration per step, warm-started from the shifted plan.
  std::optional<int> iterations;
  /// The dynamics scheme the controller predicts with (its model), when it differs from the
  /// plant's (--scheme): the model takes the plant's state through their tangent coordinates at
  /// every control step (docs/control.md "Model and plant"); empty: the plant's own scheme.
  std::optional<std::string> model_scheme;
  double dt_control = 0.05;               ///< [s] between control updates
  double threshold = 0.05;                ///< success: tip error below threshold * L
  int max_steps = 100;                    ///< control steps per reach or hold episode
  int hold_steps = 10;                    ///< hold: error below the threshold over the last ones
  /// reach: the episode ends at the first step within the threshold; false: it runs max_steps,
  /// so that min_error is the closest approach (the thesis' "best tip error", 4.4.3)
  bool stop_at_success = true;
  ControlWeights weights;
  unsigned seed = 1;                      ///< for drawing targets
  int target_count = 10;                  ///< targets drawn when none are listed
};

/// learning.ddpg: DDPG's hyper-parameters (solvers/learning/ddpg.hpp holds the defaults, each
/// written once there; empty: the default). docs/scene-reference.md "learning".
struct LearningDdpg {
  std::optional<std::vector<int>> actor_hidden, critic_hidden;  ///< hidden layer sizes
  std::optional<std::string> activation;                        ///< tanh | relu (hidden layers)
  std::optional<double> actor_learning_rate, critic_learning_rate, gamma, tau;
  std::optional<int> batch_size, buffer_capacity, warmup, updates_per_step;
  std::optional<double> noise_theta, noise_sigma, final_layer_scale;
  std::optional<std::string> precision;  ///< float64 | float32 (the networks' arithmetic)
};

/// learning.gps: Guided Policy Search (solvers/learning/gps.hpp holds the defaults).
struct LearningGps {
  std::optional<int> conditions, samples_per_condition, steps;
  std::optional<std::vector<int>> policy_hidden;
  std::optional<std::string> activation;  ///< tanh | relu (hidden layers)
  std::optional<double> policy_learning_rate;
  std::optional<int> policy_epochs, batch_size;
  std::optional<double> kl_step, min_step_mult, max_step_mult, entropy;
  std::optional<double> initial_action, initial_variance, noise_smoothing;
  std::optional<int> prior_clusters, prior_trajectories;
  std::optional<bool> sample_on_policy, redraw_conditions;
  /// the cost (solvers/learning/tip_cost.hpp)
  std::optional<double> cost_alpha, cost_quadratic, cost_velocity, cost_action, cost_bound;
  std::optional<double> cost_running, cost_final, cost_log;
};

/// learning: the settings of `rodlab train` (solvers/learning/rod_environment.hpp and
/// goal_pool.hpp hold the defaults; empty: the default).
struct Learning {
  std::optional<double> beta;             ///< (4.40)
  std::optional<int> max_steps;           ///< control steps of a reach episode
  std::optional<int> state_nodes;         ///< the state of K nodes in the observation
  std::optional<double> track_duration;   ///< [s] of a random path
  std::optional<double> track_end_speed;  ///< [m/s] bound of its end velocities
  std::optional<int> dynamic_holds;       ///< inputs of the dynamic-workspace run (reach goals)
  std::optional<int> static_points;       ///< static-workspace samples (track goals)
  LearningDdpg ddpg;
  LearningGps gps;
};

struct Scene {
  std::string schema = kSceneSchema;
  std::string name;
  Rod rod;
  Base base;
  Tip tip = FreeTip{};
  Loads loads;
  std::vector<Actuator> actuators;
  std::optional<Dynamics> dynamics;
  Solver solver;
  std::optional<Control> control;
  std::optional<Learning> learning;
  std::string source_path;  ///< the file it was read from

  bool tip_clamped() const { return std::holds_alternative<ClampedTip>(tip); }
};

}  // namespace rodlab::scene
