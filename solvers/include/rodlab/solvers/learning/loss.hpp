#pragma once
// The mean squared error of a batch (one column per sample, as mlp.hpp), for supervised
// regression (Guided Policy Search's policy fit, DDPG's critic):
//   L = 1 / (m N) sum_ij (y_ij - t_ij)^2,        dL/dy = 2 (y - t) / (m N),
// the mean over all m N entries of an m x N batch (PyTorch's MSELoss, Keras' mse).
#include <Eigen/Core>

namespace rodlab::solvers::learning {

/// L of y against the targets t; dloss_dy (if given) is resized to y's shape (no allocation at
/// a fixed shape) and set to dL/dy. Throws std::invalid_argument when the shapes differ or the
/// batch is empty.
double mse_loss(const Eigen::Ref<const Eigen::MatrixXd>& y,
                const Eigen::Ref<const Eigen::MatrixXd>& t, Eigen::MatrixXd* dloss_dy = nullptr);
float mse_loss(const Eigen::Ref<const Eigen::MatrixXf>& y,
               const Eigen::Ref<const Eigen::MatrixXf>& t, Eigen::MatrixXf* dloss_dy = nullptr);

}  // namespace rodlab::solvers::learning
