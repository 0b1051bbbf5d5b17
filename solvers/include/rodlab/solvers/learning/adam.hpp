#pragma once
// Adam (Kingma & Ba 2015, Algorithm 1, with its bias correction) over a flat parameter vector:
// an Mlp's parameters() and the gradient backward() accumulates (mlp.hpp). At step t, with the
// gradient g (plus lambda theta when weight_decay lambda > 0),
//   m <- beta1 m + (1 - beta1) g,        v <- beta2 v + (1 - beta2) g .* g,
//   m_hat = m / (1 - beta1^t),           v_hat = v / (1 - beta2^t),
//   theta <- theta - alpha m_hat ./ (sqrt(v_hat) + epsilon).
// weight_decay is an L2 penalty (lambda / 2) |theta|^2 added to the loss, so lambda theta joins g
// before the moments (DDPG's critic: lambda = 1e-2, Lillicrap et al. 2016, section 7); it is not
// AdamW's decoupled decay. A step does not allocate.
#include <Eigen/Core>

namespace rodlab::solvers::learning {

struct AdamOptions {
  double learning_rate = 1e-3;  ///< alpha (Kingma & Ba's default); may change between steps
  double beta1 = 0.9;           ///< the first moment's decay
  double beta2 = 0.999;         ///< the second moment's decay
  double epsilon = 1e-8;
  double weight_decay = 0.0;  ///< lambda of the L2 penalty; 0: off
};

template <class Scalar = double>
class Adam {
 public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;

  /// Moments for `parameter_count` parameters, zero. Throws std::invalid_argument for a
  /// learning rate or epsilon <= 0, a beta outside [0, 1) or a negative weight decay.
  explicit Adam(Eigen::Index parameter_count, const AdamOptions& options = {});

  /// One update of `parameters` from `gradient` (both of size parameter_count; throws
  /// std::invalid_argument otherwise, or when options() were set out of range).
  void step(Eigen::Ref<Vector> parameters, const Eigen::Ref<const Vector>& gradient);

  /// The options; a learning-rate schedule sets options().learning_rate between steps.
  AdamOptions& options() { return options_; }
  const AdamOptions& options() const { return options_; }
  long step_count() const { return t_; }  ///< t: steps taken since construction or reset()
  void reset();                           ///< m = v = 0, t = 0

 private:
  AdamOptions options_;
  Vector m_, v_;
  long t_ = 0;
};

extern template class Adam<double>;
extern template class Adam<float>;

}  // namespace rodlab::solvers::learning
