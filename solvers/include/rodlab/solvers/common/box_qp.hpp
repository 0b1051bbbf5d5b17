#pragma once
// A convex quadratic program with box constraints, solved exactly by a primal active-set method:
//     min_x  1/2 x^T H x + g^T x   s.t.  lo <= x <= hi,
// H symmetric positive definite, at most kMaxBoxQpSize unknowns (fixed-capacity Eigen storage:
// no heap allocation). The step subproblem of bounded Gauss-Newton (control/inverse_statics:
// H = J^T J + mu I, g = J^T r). From a feasible x (clamped), each pass solves the free unknowns'
// Newton system with the others fixed at their bounds, walks towards it until a bound blocks
// (which then joins the active set), and at a stationary point releases the active unknown
// whose multiplier has the wrong sign. Finite termination (no cycling for strictly convex
// problems); at most `max_passes` passes.
#include <Eigen/Core>

namespace rodlab::solvers {

inline constexpr int kMaxBoxQpSize = 16;
using BoxQpVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxBoxQpSize, 1>;
using BoxQpMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxBoxQpSize, kMaxBoxQpSize>;

struct BoxQpResult {
  bool converged = false;  ///< KKT conditions hold (to rounding) at x
  int passes = 0;
};

/// x: start on entry (clamped into the box), solution on return. Throws std::invalid_argument
/// for inconsistent sizes, more than kMaxBoxQpSize unknowns, or lo > hi.
BoxQpResult solve_box_qp(const BoxQpMatrix& H, const BoxQpVector& g, const BoxQpVector& lo,
                         const BoxQpVector& hi, BoxQpVector& x, int max_passes = 100);

}  // namespace rodlab::solvers
