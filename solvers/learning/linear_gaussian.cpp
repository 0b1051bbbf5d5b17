#include "rodlab/solvers/learning/linear_gaussian.hpp"

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {

LinearGaussianController LinearGaussianController::constant(int steps, int n,
                                                            const Eigen::VectorXd& k0,
                                                            double variance) {
  RODLAB_THROW_UNLESS(steps >= 1 && n >= 0 && k0.size() >= 1 && variance > 0.0,
                      "linear-Gaussian controller: expected steps >= 1, actions >= 1 and a "
                      "positive variance (got {}, {}, {:g})",
                      steps, k0.size(), variance);
  const auto m = k0.size();
  LinearGaussianController p;
  p.K.assign(steps, Eigen::MatrixXd::Zero(m, n));
  p.k.assign(steps, k0);
  p.covariance.resize(steps);
  p.cholesky.resize(steps);
  p.precision.resize(steps);
  for (int t = 0; t < steps; ++t) p.set_covariance(t, variance * Eigen::MatrixXd::Identity(m, m));
  return p;
}

void LinearGaussianController::set_covariance(int t, const Eigen::MatrixXd& S) {
  const Eigen::MatrixXd sym = 0.5 * (S + S.transpose());
  Eigen::LLT<Eigen::MatrixXd> llt(sym);
  RODLAB_THROW_UNLESS(llt.info() == Eigen::Success && sym.allFinite(),
                      "linear-Gaussian controller: the covariance of step {} is not positive "
                      "definite",
                      t);
  covariance[t] = sym;
  cholesky[t] = llt.matrixL();
  precision[t] = llt.solve(Eigen::MatrixXd::Identity(S.rows(), S.cols()));
}

}  // namespace rodlab::solvers::learning
