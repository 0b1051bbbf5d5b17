#include "rodlab/solvers/learning/regression.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <utility>

#include "rodlab/check.hpp"
#include "rodlab/solvers/learning/loss.hpp"

namespace rodlab::solvers::learning {
namespace {

/// Fisher-Yates (Knuth, TAOCP vol. 2, Algorithm P), each index drawn as rng() mod i: the modulo
/// bias, below i / 2^64, does not matter for shuffling training data.
void shuffle(std::vector<Eigen::Index>& order, std::mt19937_64& rng) {
  for (std::size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[rng() % i]);
}

/// The buffers of one minibatch size.
template <class Scalar>
struct Minibatch {
  typename Mlp<Scalar>::Matrix x, y, dloss_dy;
  typename Mlp<Scalar>::Vector error;  ///< the weighted loss's y_j - t_j
  MlpWorkspace<Scalar> ws;
};

}  // namespace

template <class Scalar>
RegressionResult fit_regression(Mlp<Scalar>& net, Adam<Scalar>& adam,
                                const Eigen::Ref<const typename Mlp<Scalar>::Matrix>& X,
                                const Eigen::Ref<const typename Mlp<Scalar>::Matrix>& Y,
                                const RegressionOptions& options,
                                const RegressionWeights* weights) {
  const Eigen::Index n = X.cols();
  RODLAB_THROW_UNLESS(X.rows() == net.input_size() && Y.rows() == net.output_size() &&
                          Y.cols() == n && n >= 1,
                      "fit_regression: expected inputs {}xN and targets {}xN, N >= 1 (got {}x{} "
                      "and {}x{})",
                      net.input_size(), net.output_size(), X.rows(), X.cols(), Y.rows(), Y.cols());
  RODLAB_THROW_UNLESS(options.epochs >= 0 && options.batch_size >= 1,
                      "fit_regression: expected epochs >= 0 and batch_size >= 1 (got {} and {})",
                      options.epochs, options.batch_size);
  RODLAB_THROW_UNLESS(
      !weights || (static_cast<Eigen::Index>(weights->index.size()) == n &&
                   std::all_of(weights->index.begin(), weights->index.end(),
                               [&](int i) {
                                 return i >= 0 &&
                                        static_cast<std::size_t>(i) < weights->precision.size() &&
                                        weights->precision[i].rows() == Y.rows() &&
                                        weights->precision[i].cols() == Y.rows();
                               })),
      "fit_regression: expected {} weight indices into {}x{} matrices", n, Y.rows(), Y.rows());
  std::mt19937_64 rng(options.seed);
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  Minibatch<Scalar> full, tail;  // one set of buffers per minibatch size: no reallocation
  typename Mlp<Scalar>::Vector gradient(net.parameter_count());
  RegressionResult result;
  result.epoch_loss.reserve(static_cast<std::size_t>(options.epochs));
  for (int epoch = 0; epoch < options.epochs; ++epoch) {
    shuffle(order, rng);
    double loss_sum = 0.0;
    for (Eigen::Index start = 0; start < n; start += options.batch_size) {
      const Eigen::Index size = std::min<Eigen::Index>(options.batch_size, n - start);
      Minibatch<Scalar>& b = size == options.batch_size ? full : tail;
      b.x.resize(X.rows(), size);
      b.y.resize(Y.rows(), size);
      for (Eigen::Index j = 0; j < size; ++j) {
        b.x.col(j) = X.col(order[start + j]);
        b.y.col(j) = Y.col(order[start + j]);
      }
      const auto& prediction = net.forward(b.x, b.ws);
      if (weights) {  // (y - t)^T P (y - t) / (m N) per sample, its gradient 2 P (y - t) / (m N)
        b.dloss_dy = prediction - b.y;
        const double scale = 1.0 / static_cast<double>(Y.rows() * size);
        for (Eigen::Index j = 0; j < size; ++j) {
          const auto P = weights->precision[weights->index[order[start + j]]].cast<Scalar>();
          b.error = b.dloss_dy.col(j);
          b.dloss_dy.col(j).noalias() = static_cast<Scalar>(2.0 * scale) * P * b.error;
          loss_sum += 0.5 * static_cast<double>(b.error.dot(b.dloss_dy.col(j))) * size;
        }
      } else {
        loss_sum += static_cast<double>(mse_loss(prediction, b.y, &b.dloss_dy)) * size;
      }
      gradient.setZero();
      net.backward(b.ws, b.dloss_dy, &gradient);
      adam.step(net.parameters(), gradient);
    }
    result.epoch_loss.push_back(loss_sum / n);
  }
  return result;
}

template RegressionResult fit_regression<double>(Mlp<double>&, Adam<double>&,
                                                 const Eigen::Ref<const Mlp<double>::Matrix>&,
                                                 const Eigen::Ref<const Mlp<double>::Matrix>&,
                                                 const RegressionOptions&,
                                                 const RegressionWeights*);
template RegressionResult fit_regression<float>(Mlp<float>&, Adam<float>&,
                                                const Eigen::Ref<const Mlp<float>::Matrix>&,
                                                const Eigen::Ref<const Mlp<float>::Matrix>&,
                                                const RegressionOptions&,
                                                const RegressionWeights*);

}  // namespace rodlab::solvers::learning
