#pragma once
// Supervised regression of a network to data by minibatch Adam on the mean squared error
// (loss.hpp, adam.hpp): Guided Policy Search's fit of a policy to its controllers' actions.
// Each epoch visits every sample once, in an order shuffled from the seed (Fisher-Yates with
// std::mt19937_64, each draw reduced modulo the range rather than by
// std::uniform_int_distribution, so the order is the same with every standard library), in
// minibatches of batch_size; the last minibatch of an epoch holds the remainder when the sample
// count is not a multiple. One Adam step per minibatch. After the first epoch the loop does not
// allocate.
//
// With weights, sample j's error is weighted by a symmetric positive definite matrix P_j (GPS:
// the precision of the controller whose action is the target, Levine & Abbeel 2014):
//   L = 1 / (m N) sum_j (y_j - t_j)^T P_j (y_j - t_j),   dL/dy_j = 2 P_j (y_j - t_j) / (m N),
// which is the mean squared error for P_j = I.
#include <cstdint>
#include <span>
#include <vector>

#include "rodlab/solvers/learning/adam.hpp"
#include "rodlab/solvers/learning/mlp.hpp"

namespace rodlab::solvers::learning {

struct RegressionOptions {
  int epochs = 100;
  int batch_size = 64;
  std::uint64_t seed = 0;  ///< the shuffle
};

/// Per-sample weight matrices: sample j uses precision[index[j]] (output_size square).
struct RegressionWeights {
  std::span<const Eigen::MatrixXd> precision;
  std::span<const int> index;  ///< one per sample
};

struct RegressionResult {
  /// Per epoch: the mean squared error over the epoch's samples, each minibatch's loss taken
  /// before its step (the running training loss, not a separate evaluation).
  std::vector<double> epoch_loss;
};

/// Fits `net` to the inputs X (input_size x N) and targets Y (output_size x N) with `adam`
/// (sized for net's parameters; its moments carry over between calls). Throws
/// std::invalid_argument for mismatched sizes, N = 0, epochs < 0 or batch_size < 1, or weights
/// of the wrong count or size.
template <class Scalar>
RegressionResult fit_regression(Mlp<Scalar>& net, Adam<Scalar>& adam,
                                const Eigen::Ref<const typename Mlp<Scalar>::Matrix>& X,
                                const Eigen::Ref<const typename Mlp<Scalar>::Matrix>& Y,
                                const RegressionOptions& options,
                                const RegressionWeights* weights = nullptr);

extern template RegressionResult fit_regression<double>(
    Mlp<double>&, Adam<double>&, const Eigen::Ref<const Mlp<double>::Matrix>&,
    const Eigen::Ref<const Mlp<double>::Matrix>&, const RegressionOptions&,
    const RegressionWeights*);
extern template RegressionResult fit_regression<float>(
    Mlp<float>&, Adam<float>&, const Eigen::Ref<const Mlp<float>::Matrix>&,
    const Eigen::Ref<const Mlp<float>::Matrix>&, const RegressionOptions&,
    const RegressionWeights*);

}  // namespace rodlab::solvers::learning
