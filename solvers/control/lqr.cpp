#include "rodlab/solvers/control/lqr.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

#include "rodlab/check.hpp"

namespace rodlab::solvers::control {
namespace {

void check_sizes(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& Q,
                 const Eigen::MatrixXd& R) {
  const auto n = A.rows(), m = B.cols();
  RODLAB_THROW_UNLESS(A.cols() == n && B.rows() == n && Q.rows() == n && Q.cols() == n &&
                          R.rows() == m && R.cols() == m,
                      "lqr: expected A {0}x{0}, B {0}x{1}, Q {0}x{0}, R {1}x{1}", n, m);
}

/// K = (R + B^T S B)^-1 B^T S A.
Eigen::MatrixXd gain(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, const Eigen::MatrixXd& R,
                     const Eigen::MatrixXd& S) {
  const Eigen::MatrixXd BtS = B.transpose() * S;
  return (R + BtS * B).ldlt().solve(BtS * A);
}

}  // namespace

FiniteHorizonLqr finite_horizon_lqr(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                    const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R,
                                    const Eigen::MatrixXd& Q_end, int N) {
  check_sizes(A, B, Q, R);
  RODLAB_THROW_UNLESS(N >= 1, "lqr: the horizon must be >= 1 (got {})", N);
  RODLAB_THROW_UNLESS(Q_end.rows() == A.rows() && Q_end.cols() == A.rows(),
                      "lqr: Q_end must be {0}x{0}", A.rows());
  FiniteHorizonLqr out;
  out.K.resize(N);
  out.S.resize(N + 1);
  out.S[N] = Q_end;  // (4.31)
  for (int i = N - 1; i >= 0; --i) {  // to S_0, the whole horizon's cost to go
    out.K[i] = gain(A, B, R, out.S[i + 1]);
    const Eigen::MatrixXd S = Q + A.transpose() * out.S[i + 1] * (A - B * out.K[i]);  // (4.32)
    out.S[i] = 0.5 * (S + S.transpose());
  }
  return out;
}

DareSolution solve_dare(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                        const Eigen::MatrixXd& Q, const Eigen::MatrixXd& R, int max_iterations,
                        double tol) {
  check_sizes(A, B, Q, R);
  const auto n = A.rows();
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  // SDA: A_0 = A, G_0 = B R^-1 B^T, H_0 = Q;  W = I + G_k H_k,
  //   A_(k+1) = A_k W^-1 A_k,  G_(k+1) = G_k + A_k W^-1 G_k A_k^T,  H_(k+1) = H_k + A_k^T H_k W^-1 A_k
  Eigen::MatrixXd Ak = A, Gk = B * R.ldlt().solve(B.transpose()), Hk = Q;
  DareSolution out;
  for (out.iterations = 1; out.iterations <= max_iterations; ++out.iterations) {
    const Eigen::PartialPivLU<Eigen::MatrixXd> W(I + Gk * Hk);
    const Eigen::MatrixXd WA = W.solve(Ak), WG = W.solve(Gk);
    const Eigen::MatrixXd H_next = Hk + Ak.transpose() * Hk * WA;
    Gk = Gk + Ak * WG * Ak.transpose();
    Ak = Ak * WA;
    const double change = (H_next - Hk).norm();
    Hk = 0.5 * (H_next + H_next.transpose());
    Gk = 0.5 * (Gk + Gk.transpose());
    if (change <= tol * std::max(1.0, Hk.norm())) {
      out.converged = Hk.allFinite();
      break;
    }
  }
  out.S = Hk;
  out.K = gain(A, B, R, Hk);
  return out;
}

}  // namespace rodlab::solvers::control
