#include "rodlab/solvers/learning/adam.hpp"

#include <cmath>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

void check_options(const AdamOptions& o) {
  RODLAB_THROW_UNLESS(o.learning_rate > 0.0 && std::isfinite(o.learning_rate),
                      "adam: learning_rate must be > 0 (got {:g})", o.learning_rate);
  RODLAB_THROW_UNLESS(o.beta1 >= 0.0 && o.beta1 < 1.0, "adam: beta1 must be in [0, 1) (got {:g})",
                      o.beta1);
  RODLAB_THROW_UNLESS(o.beta2 >= 0.0 && o.beta2 < 1.0, "adam: beta2 must be in [0, 1) (got {:g})",
                      o.beta2);
  RODLAB_THROW_UNLESS(o.epsilon > 0.0, "adam: epsilon must be > 0 (got {:g})", o.epsilon);
  RODLAB_THROW_UNLESS(o.weight_decay >= 0.0, "adam: weight_decay must be >= 0 (got {:g})",
                      o.weight_decay);
}

}  // namespace

template <class Scalar>
Adam<Scalar>::Adam(Eigen::Index parameter_count, const AdamOptions& options)
    : options_(options),
      m_(Vector::Zero(parameter_count)),
      v_(Vector::Zero(parameter_count)) {
  check_options(options_);
}

template <class Scalar>
void Adam<Scalar>::step(Eigen::Ref<Vector> parameters, const Eigen::Ref<const Vector>& gradient) {
  RODLAB_THROW_UNLESS(parameters.size() == m_.size() && gradient.size() == m_.size(),
                      "adam: expected {} parameters and gradient entries (got {} and {})",
                      m_.size(), parameters.size(), gradient.size());
  check_options(options_);
  ++t_;
  const auto b1 = static_cast<Scalar>(options_.beta1), b2 = static_cast<Scalar>(options_.beta2);
  const auto lambda = static_cast<Scalar>(options_.weight_decay);
  const auto g = gradient.array() + lambda * parameters.array();  // + d/dtheta (lambda/2)|theta|^2
  m_.array() = b1 * m_.array() + (Scalar(1) - b1) * g;
  v_.array() = b2 * v_.array() + (Scalar(1) - b2) * g.square();
  // The bias corrections 1 - beta^t, in double: beta^t underflows to 0, never to a negative.
  const auto c1 = static_cast<Scalar>(1.0 - std::pow(options_.beta1, static_cast<double>(t_)));
  const auto c2 = static_cast<Scalar>(1.0 - std::pow(options_.beta2, static_cast<double>(t_)));
  const auto alpha = static_cast<Scalar>(options_.learning_rate);
  const auto epsilon = static_cast<Scalar>(options_.epsilon);
  parameters.array() -= alpha * (m_.array() / c1) / ((v_.array() / c2).sqrt() + epsilon);
}

template <class Scalar>
void Adam<Scalar>::reset() {
  m_.setZero();
  v_.setZero();
  t_ = 0;
}

template class Adam<double>;
template class Adam<float>;

}  // namespace rodlab::solvers::learning
