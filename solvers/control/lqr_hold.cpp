#include "rodlab/solvers/control/lqr_hold.hpp"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "rodlab/check.hpp"
#include "rodlab/solvers/control/linearisation.hpp"
#include "rodlab/solvers/control/lqr.hpp"
#include "rodlab/solvers/statics/workspace.hpp"

namespace rodlab::solvers::control {

Eigen::VectorXd HoldGain::control(const Plant& plant, const Eigen::VectorXd& u_ref) const {
  Eigen::VectorXd x(plant.state_size());
  plant.read_state(std::span<double>(x.data(), x.size()));
  const Eigen::VectorXd u = u_ref - K * (x - x_star - steady * (u_ref - u_star));
  return u.cwiseMax(plant.lower()).cwiseMin(plant.upper());
}

HoldGain hold_gain(const scene::Scene& scene, const PlantOptions& options,
                   const Eigen::VectorXd& u_star, const LqrWeights& weights) {
  // the scene with u* as its inputs, started in its equilibrium on the plant's grid
  scene::Scene held = scene;
  const auto inputs = statics::workspace_inputs(held);
  RODLAB_THROW_UNLESS(static_cast<int>(inputs.size()) == u_star.size(),
                      "lqr: expected {} inputs, got {}", inputs.size(), u_star.size());
  for (std::size_t k = 0; k < inputs.size(); ++k) *inputs[k].value = scene::ScalarSchedule(u_star[k]);
  PlantOptions po = options;
  po.solver.initial = scene::Initial::static_equilibrium;
  Plant plant(held, po);

  HoldGain out;
  out.u_star = plant.input();
  out.x_star.resize(plant.state_size());
  plant.read_state(std::span<double>(out.x_star.data(), out.x_star.size()));
  out.tip_star = plant.tip();
  Linearisation lin(plant);
  Eigen::MatrixXd A, B, C, D;
  const auto status = lin.jacobians(plant, A, B, C, D);
  if (!status.ok) {
    out.reason = "lqr: the linearisation at the equilibrium failed: " + status.reason;
    return out;
  }
  // the cost of the header as x^T Q x + u^T R u + 2 x^T N u, the cross term removed by
  // u = v - R^-1 N^T x (the standard reduction): A' = A - B R^-1 N^T, Q' = Q - N R^-1 N^T
  const double L2 = plant.length() * plant.length();
  const Eigen::VectorXd range = (plant.upper() - plant.lower()).cwiseMax(1e-300);
  Eigen::MatrixXd Q = C.transpose() * C / L2;
  Q.diagonal() += weights.state * plant.state_scale().cwiseInverse().cwiseAbs2();
  Eigen::MatrixXd R = D.transpose() * D / L2;
  R.diagonal() += weights.input * range.cwiseInverse().cwiseAbs2();
  const Eigen::MatrixXd N = C.transpose() * D / L2;
  const Eigen::MatrixXd RiNt = R.ldlt().solve(N.transpose());
  const DareSolution dare = solve_dare(A - B * RiNt, B, Q - N * RiNt, R);
  if (!dare.converged) {
    out.reason = "lqr: the Riccati equation did not converge";
    return out;
  }
  out.K = dare.K + RiNt;
  const int n = plant.state_size();
  out.steady = (Eigen::MatrixXd::Identity(n, n) - A).partialPivLu().solve(B);
  out.spectral_radius = (A - B * out.K).eigenvalues().cwiseAbs().maxCoeff();
  out.ok = true;
  return out;
}

}  // namespace rodlab::solvers::control
