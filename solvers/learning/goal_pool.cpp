#include "rodlab/solvers/learning/goal_pool.hpp"

#include <algorithm>
#include <random>

#include "rodlab/check.hpp"
#include "rodlab/solvers/control/dynamic_targets.hpp"
#include "rodlab/solvers/control/inverse_statics.hpp"
#include "rodlab/solvers/control/static_targets.hpp"

namespace rodlab::solvers::learning {

GoalPool make_goal_pool(const scene::Scene& scene, const EnvironmentOptions& e,
                        const GoalPoolOptions& o) {
  const double threshold = e.threshold * scene.rod.length;
  // the statics of the static workspace and of reach-one's check, on the plant's nodes
  control::InverseStaticsOptions is;
  is.statics.nodes = e.plant.solver.nodes;
  is.tolerance = threshold;
  GoalPool pool;
  if (e.task == LearningTask::track) {
    pool.points = control::sample_static_targets(scene, is.statics, o.static_points,
                                                 static_cast<unsigned>(o.seed))
                      .tips;
    RODLAB_THROW_UNLESS(pool.points.size() >= 2,
                        "learning: the static workspace gave {} points (2 needed)",
                        pool.points.size());
    return pool;
  }
  control::DynamicTargetOptions d;
  d.solver = e.plant.solver;
  d.dt_control = e.plant.dt_control;
  d.holds = o.dynamic_holds;
  d.exclude_radius = threshold;
  d.seed = static_cast<unsigned>(o.seed);
  auto tips = control::dynamic_workspace_tips(scene, d);
  if (e.task == LearningTask::reach_any) {
    pool.points = std::move(tips);
    return pool;
  }
  // reach-one: the first candidate in a seeded order that the rod cannot hold
  std::mt19937_64 rng(o.seed);
  std::shuffle(tips.begin(), tips.end(), rng);
  control::InverseStatics statics(scene, is);
  for (const auto& tip : tips) {
    const auto r = statics.solve(tip);
    if (r.converged && !r.reached) {
      pool.points = {tip};
      pool.beyond_static = r.error;
      return pool;
    }
  }
  throw std::invalid_argument(
      "learning: reach-one: no tip of the dynamic workspace lies outside the static workspace "
      "(more than the success threshold from every quasi-static tip)");
}

}  // namespace rodlab::solvers::learning
