#pragma once
// Guided Policy Search, the mirror-descent variant MDGPS (Montgomery & Levine 2016, "Guided
// policy search via approximate mirror descent", Algorithm 2 with samples from the local
// controllers; Levine & Abbeel 2014 for the local dynamics and the KL-bounded LQG; thesis 4.3.2,
// Algorithm 6; docs/learning.md "GPS"). M conditions (an episode seed each: the same start and
// goal every time), T steps per trajectory. Per iteration:
//
//   1. sample N trajectories per condition from its linear-Gaussian controller p_c (in
//      parallel on the environments; noise smoothed in time, from the seed);
//   2. fit linear-Gaussian dynamics per condition with a Gaussian-mixture prior fitted on the
//      recent trajectories of all conditions (linear_gaussian_dynamics.hpp);
//   3. expand the cost about every sample and average (a quadratic per condition and step);
//   4. linearise the neural policy pi_theta(a | o) = N(mu_theta(o), S_pi) about the samples:
//      K_pi,t = mean_i dmu/do (o_i,t) J, k_pi,t = mean_i mu - K_pi,t mean_i x (J = do/dx,
//      trajectory_environment.hpp). The reference code regresses the policy's outputs on the
//      states with a prior instead: our network's Jacobian is exact and cheap;
//   5. adjust each condition's step (the reference's "classic" rule: the predicted against the
//      actual improvement of the previous step, multiplier in [min, max]);
//   6. C-step: p_c <- argmin E[l] s.t. KL(p_c || pi_lin,c) <= kl_step x step_mult x T
//      (trajectory_optimizer.hpp);
//   7. S-step: fit mu_theta to the new controllers' means K_t x + k_t at the samples'
//      observations, each weighted by the controller's precision S_t^-1 (minibatch Adam), and
//      set S_pi = diag(1 / mean diag S_t^-1).
//
// Before the first C-step the policy is fitted to the initial controllers (step 7 first).
//
// On-policy sampling (sample_on_policy; Montgomery & Levine 2016, section 4.2, "sampling from
// the policy"): step 1 samples pi_theta itself, a = mu_theta(o) + S_pi^(1/2) noise, and the
// local controllers only carry the C-step's result to the S-step. Nothing then ties a condition
// to the previous iteration, so with redraw_conditions every iteration draws new conditions
// (new goals): the policy meets M new targets per iteration instead of the same M throughout,
// which is what "reach any point" asks of it. The step adjustment (5) compares a condition with
// its previous iteration, so redrawn conditions keep kl_step fixed. Every
// random draw comes from the seed: the same seed and number of environments give the same
// policy bit for bit (the trajectories are assigned to environments in a fixed order).
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rodlab/solvers/learning/activation.hpp"
#include "rodlab/solvers/learning/adam.hpp"
#include "rodlab/solvers/learning/linear_gaussian.hpp"
#include "rodlab/solvers/learning/linear_gaussian_dynamics.hpp"
#include "rodlab/solvers/learning/mlp.hpp"
#include "rodlab/solvers/learning/trajectory_environment.hpp"
#include "rodlab/solvers/learning/trajectory_optimizer.hpp"

namespace rodlab::solvers::learning {

/// Conditions per iteration for track, whose trajectories are a whole path (80 steps of a 4 s
/// path at dt_c = 0.05 s): measured (seed 1, 50 400 samples), the middle circle at 1.92 % of L
/// with 10, 2.71 % with 30 (docs/learning.md).
inline constexpr int kGpsTrackConditions = 10;

struct GpsOptions {
  int conditions = 30;            ///< M per iteration (the reference MDGPS example: 4)
  int samples_per_condition = 3;  ///< N (the example: 5)
  int steps = 20;                 ///< T control steps per trajectory (1 s at dt_c = 0.05 s)
  std::vector<int> policy_hidden{64, 64};
  Activation hidden = Activation::relu;
  double policy_learning_rate = 1e-3;
  int policy_epochs = 50;  ///< S-step epochs over the iteration's samples
  int batch_size = 64;
  double kl_step = 0.5;        ///< epsilon per step (the bound is kl_step x step_mult x T)
  double min_step_mult = 0.5;  ///< the reference example's
  double max_step_mult = 3.0;
  double initial_action = 0.0;    ///< the first controllers' mean action
  double initial_variance = 0.1;  ///< their action variance
  /// Variance [steps^2] of the Gaussian filter smoothing the exploration noise in time
  /// (rescaled to unit variance); 0: white noise.
  double noise_smoothing = 2.0;
  bool sample_on_policy = true;   ///< step 1 samples the policy, not the local controllers
  bool redraw_conditions = true;  ///< new conditions every iteration (needs sample_on_policy)
  DynamicsFitOptions dynamics;
  KlStepOptions kl;
  std::uint64_t seed = 1;
};

/// What one iteration measured on its samples (the local controllers').
struct GpsIteration {
  long samples = 0;  ///< environment steps so far, this iteration's included
  int trajectories = 0, failed = 0;
  double mean_cost = 0.0;          ///< per trajectory (GPS's cost)
  double mean_return = 0.0;        ///< per trajectory: the sum of the environment's rewards
  double success_rate = 0.0;       ///< of the iteration's trajectories
  double mean_min_error = 0.0;     ///< [the environment's error unit] best along a trajectory
  double mean_final_error = 0.0;
  double mean_kl = 0.0, mean_step_mult = 0.0;
  double policy_loss = 0.0;  ///< the S-step's last epoch
  double wall_time_s = 0.0;
  std::string first_failure;
};

struct GpsLog {
  std::vector<GpsIteration> iterations;
  long samples = 0;
  double wall_time_s = 0.0;
};

class Gps {
 public:
  /// Throws std::invalid_argument for bad sizes or options.
  Gps(int state_size, int observation_size, int action_size, const GpsOptions& options);

  /// Trains on `envs` (all alike; they step in parallel, one thread each) with the conditions
  /// `condition_seeds` (episode seeds; at least one) until `samples` environment steps are
  /// used (whole iterations: an iteration needs M N T). `progress` is called after each
  /// iteration.
  GpsLog train(std::span<TrajectoryEnvironment* const> envs,
               std::span<const std::uint64_t> condition_seeds, long samples,
               const std::function<void(const GpsIteration&)>& progress = {});

  /// The policy's mean action for an observation (no clipping).
  void act(std::span<const double> observation, std::span<double> action);
  Mlp<double>& policy() { return policy_; }
  const Eigen::VectorXd& policy_variance() const { return policy_variance_; }
  /// The local controllers after training (one per condition).
  const std::vector<LinearGaussianController>& controllers() const { return controllers_; }
  const GpsOptions& options() const { return options_; }

  struct Sample;  ///< one trajectory (gps.cpp)

 private:
  struct Condition;

  std::vector<Sample> collect(std::span<TrajectoryEnvironment* const> envs,
                              std::span<const std::uint64_t> seeds, int iteration);
  /// One trajectory from the local controller p, or from the policy if p is null.
  Sample rollout(TrajectoryEnvironment& env, std::uint64_t episode_seed,
                 const LinearGaussianController* p, std::uint64_t noise_seed) const;
  /// pi_theta linearised about a condition's samples (step 4).
  LinearGaussianController linearise_policy(const std::vector<const Sample*>& samples,
                                            const Eigen::MatrixXd& J);
  /// Steps 2-6 for one condition; nullopt (the controller kept) with fewer than 2 samples.
  std::optional<KlStep> improve(Condition& c, const std::vector<const Sample*>& samples,
                                const DynamicsFitter& fitter, const Eigen::MatrixXd& J);
  /// Step 5: the KL multiplier from the previous step's predicted and actual improvement.
  void adjust_step(Condition& c, const LinearGaussianController& policy,
                   const std::vector<const Sample*>& samples) const;
  /// The iteration's statistics over its trajectories.
  static GpsIteration summarise(const std::vector<Sample>& all);
  /// The S-step (7) on every valid sample, towards `controllers`; returns the last epoch's loss.
  double fit_policy(const std::vector<std::vector<const Sample*>>& by_condition,
                    const std::vector<LinearGaussianController>& controllers);

  GpsOptions options_;
  int n_, n_obs_, m_;
  Mlp<double> policy_;
  Adam<double> adam_;
  Eigen::VectorXd policy_variance_;
  std::vector<LinearGaussianController> controllers_;
  std::uint64_t fits_ = 0;  ///< S-steps so far (their shuffle seeds)
};

}  // namespace rodlab::solvers::learning
