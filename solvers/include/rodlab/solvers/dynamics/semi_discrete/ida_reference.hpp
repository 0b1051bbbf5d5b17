#pragma once
// `ida`: the dynamics reference. Method of lines in s, integrated in time by SUNDIALS IDA
// (variable-order BDF, error control at rtol = atol = 1e-10 by default) with the KLU sparse
// linear solver (common/ida_solver.hpp).
//
// Semi-discretisation (semi_discrete_rod.hpp, shared with implicit-midpoint-collocation): the
// time-continuous limit of `variational` (variational.hpp), so the two agree at equal N as
// dt -> 0. Unknowns per node j >= 1, 13 of them: the position p_j (world), a quaternion q_j and
// the body velocity eta_j, then the two ledger unknowns. The system is an ODE written as IDA's
// residual F = y' - f(t, y); the Newton matrix cj I - df/dy is block tridiagonal in the nodes
// (13 x 13 blocks) plus two dense ledger rows, formed analytically where the derivation covers
// the scene (SemiDiscreteRod::analytic_jacobian()), else by finite differences with three node
// colours (j mod 3), then factorised by KLU.
//
// Energy ledger: kinetic, strain and gravity energies come from energy.hpp; `dissipated`
// (viscous power sum_j ds xi_dot^T V xi_dot, drag power -w_j drag . eta_j) and `work_in` (tip
// wrench, distributed wrench, actuator and cable-entry power) are two extra differential
// unknowns D' = P_diss(y), W' = P_in(y) integrated by IDA under the same error control (plain
// IDA has no quadrature facility; that is IDAS). Their rows of the Newton matrix are formed
// the same way (the powers are sums of per-segment and per-node terms, which the colouring of
// the finite differences keeps apart). The semi-discrete balance T + U + P + D - W = const is exact, so
// Energy::total() drifts only by the integration error.
//
// Absolute tolerances per component (atol is the option; SemiDiscreteRod::tolerance_scale()):
//   position [m]: atol;  quaternion [1]: atol;
//   angular velocity [rad/s]: atol * omega_1;  linear velocity [m/s]: atol * L * omega_1;
//   dissipated and work_in [J]: atol * E_bend,
// with omega_1 = 2 pi f_1 the first (Euler-Bernoulli, free tip) bending frequency and
// E_bend = 1/2 EI (pi / 2L)^2 L the strain energy of a quarter-circle bend (the characteristic
// velocity and energy of the rod's gross motion).
//
// Consistent initial conditions: the run starts at rest from the given node poses, so y'0 =
// f(0, y0) is computed directly (p' = q' = 0, eta' = M^-1 (...), no IDACalcIC); this holds on
// stiff rods too (the system is an ODE; there is no algebraic part to make consistent).
// Stiff rods: a release excites the rotation-shear mode sqrt(G A / rho I) (2 MHz on a 1 mm steel
// wire) above the tolerances, which IDA resolves; the step budget scales with the interval and
// that frequency (kIdaStepsPerRadian below), docs/dynamics.md "ida on stiff rods".
// Muscles: their lengths Delta are algebraic unknowns after D and W, with the residual
// (Delta - L(y)) / L (index 1; initial values the lengths of the initial poses; their Jacobian
// row is dense over the poses and their column dense over the velocities, so the Newton matrix
// stays sparse). Kirchhoff rods and length control (cable displacement, chamber volume: index
// 3 as they stand) are integrated in the stabilised index-2 (Gear-Gupta-Leimkuhler) form of
// semi_discrete_rod.hpp: constraint and actuator forces and multipliers as algebraic unknowns
// (IDASetId, IDASetSuppressAlg), consistent initial values by projection, and a restart at every
// kink of a length schedule (docs/dynamics.md "`ida`: Kirchhoff rods and length control").
#include <memory>
#include <span>

#include "rodlab/solvers/common/newton_linear_solver.hpp"
#include "rodlab/solvers/dynamics/dynamic_problem.hpp"
#include "rodlab/solvers/dynamics/stepper.hpp"

namespace rodlab::solvers::dynamics {

struct IdaOptions {
  int nodes = 20;
  double rtol = 1e-10, atol = 1e-10;  ///< IDA's tolerances (atol scaled per component, above)
  /// Internal IDA steps per step() call; 0: the budget scales with the interval (below). The
  /// run's wall-time guard (common/deadline.hpp) is checked in every residual evaluation.
  long max_steps = 0;
  /// The corrected grid (solver.grid: corrected; SemiDiscreteRod's corrected_grid): the problem
  /// is to carry the grid's model (corrected_grid_problem); Cosserat rods without actuators.
  bool corrected_grid = false;
  /// The Newton systems' linear solver where the pattern allows it (Cosserat rods without
  /// actuator unknowns, newton_linear_solver.hpp; else KLU).
  NewtonLinearSolver linear_solver = NewtonLinearSolver::condensed_rod_blocks;
};

/// The step budget of a step() call over `interval` seconds at max_steps = 0:
/// max(kIdaMinStepBudget, kIdaStepsPerRadian * interval * omega_max), with omega_max the highest
/// frequency of the semi-discrete rod (time_step.hpp). Error control resolves an undamped mode
/// at h omega of order 0.1-1 (measured on the steel guidewire of docs/dynamics.md: 2.5 steps
/// per radian of its 2 MHz rotation-shear mode), so a stiff rod gets the steps its fastest mode
/// needs while a stalled integration (h -> 0) still stops.
inline constexpr long kIdaMinStepBudget = 100000;
inline constexpr double kIdaStepsPerRadian = 20.0;
/// IDASolve is called for at most this many internal steps at a time (the budget is counted
/// over the calls).
inline constexpr long kIdaChunkSteps = 20000;

/// Starts at rest from the node poses g0 (base first, options.nodes of them). step(t, dt)
/// integrates to t + dt with the stop time there (a failed IDASolve is a failed StepStatus with
/// IDA's flag name and time; `iterations` counts IDA's Newton iterations in the step). A call
/// whose t is not the time reached restarts IDA there from the current state.
std::unique_ptr<Stepper> make_ida(const DynamicProblem& problem, const IdaOptions& options,
                                  std::span<const SE3> g0);

/// The same from a RestState (the form of make_variational): only the poses are used, since
/// the segment strains are log(g_j^-1 g_(j+1)) / ds of the poses.
std::unique_ptr<Stepper> make_ida(const DynamicProblem& problem, const IdaOptions& options,
                                  const RestState& initial);

}  // namespace rodlab::solvers::dynamics
