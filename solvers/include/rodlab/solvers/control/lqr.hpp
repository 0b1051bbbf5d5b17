#pragma once
// The linear-quadratic regulator of a discrete system x+ = A x + B u with the cost
// sum_i (x_i^T Q x_i + u_i^T R u_i) + x_N^T Q_end x_N (thesis 4.2.2, (4.22)-(4.32); docs/control.md).
//
// Finite horizon, corrected: the thesis' (4.30) lacks the minus sign (Algorithm 3 has it). Its
// backward loop, i = N-1 .. 1, ends at S_1, which is what u_0 needs for N inputs u_0..u_(N-1):
// consistent (control-notes.md calls it off by one; checked here against the stacked QP). The
// loop below goes on to S_0, the cost to go of the whole horizon. Here
//   S_N = Q_end;  for i = N-1 .. 0:  K_i = (R + B^T S_(i+1) B)^-1 B^T S_(i+1) A,
//                                    S_i = Q + A^T S_(i+1) (A - B K_i)          (4.31)-(4.32)
//   u_i = -K_i x_i                                                              (4.30) with its sign
// Infinite horizon (reach and hold at an equilibrium): S solves the discrete algebraic Riccati
// equation S = Q + A^T S A - A^T S B (R + B^T S B)^-1 B^T S A, by the structure-preserving
// doubling algorithm (Chu, Fan, Lin & Wang 2004), which converges quadratically where the
// Riccati iteration crawls (a lightly damped rod has eigenvalues of A near the unit circle).
#include <vector>

#include <Eigen/Core>

namespace rodlab::solvers::control {

struct FiniteHorizonLqr {
  std::vector<Eigen::MatrixXd> K;  ///< K_0 .. K_(N-1): u_i = -K_i x_i
  std::vector<Eigen::MatrixXd> S;  ///< S_0 .. S_N: the cost to go x^T S_i x
};

/// Throws std::invalid_argument for mismatched sizes or N < 1.
FiniteHorizonLqr finite_horizon_lqr(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                    const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
                                    const Eigen::MatrixXd& Q_end, int N);

struct DareSolution {
  bool converged = false;
  int iterations = 0;
  Eigen::MatrixXd S;  ///< the stabilising solution
  Eigen::MatrixXd K;  ///< u = -K x
};

/// The DARE's stabilising solution (A, B stabilisable; Q >= 0 with (A, Q) detectable; R > 0).
DareSolution solve_dare(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                        const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
                        int max_iterations = 60, double tol = 1e-13);

}  // namespace rodlab::solvers::control
