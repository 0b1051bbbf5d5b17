#include "rodlab/solvers/learning/loss.hpp"

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

template <class Scalar>
using MatrixX = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

template <class Scalar>
Scalar mean_squared_error(const Eigen::Ref<const MatrixX<Scalar>>& y,
                          const Eigen::Ref<const MatrixX<Scalar>>& t, MatrixX<Scalar>* dloss_dy) {
  RODLAB_THROW_UNLESS(y.rows() == t.rows() && y.cols() == t.cols() && y.size() > 0,
                      "mse_loss: expected outputs and targets of one non-empty shape (got {}x{} "
                      "and {}x{})",
                      y.rows(), y.cols(), t.rows(), t.cols());
  const Scalar scale = Scalar(1) / static_cast<Scalar>(y.size());  // 1 / (m N)
  if (dloss_dy != nullptr) {
    dloss_dy->resize(y.rows(), y.cols());
    *dloss_dy = (Scalar(2) * scale) * (y - t);  // dL/dy = 2 (y - t) / (m N)
  }
  return scale * (y - t).squaredNorm();  // L = sum (y - t)^2 / (m N)
}

}  // namespace

double mse_loss(const Eigen::Ref<const Eigen::MatrixXd>& y,
                const Eigen::Ref<const Eigen::MatrixXd>& t, Eigen::MatrixXd* dloss_dy) {
  return mean_squared_error<double>(y, t, dloss_dy);
}

float mse_loss(const Eigen::Ref<const Eigen::MatrixXf>& y,
               const Eigen::Ref<const Eigen::MatrixXf>& t, Eigen::MatrixXf* dloss_dy) {
  return mean_squared_error<float>(y, t, dloss_dy);
}

}  // namespace rodlab::solvers::learning
