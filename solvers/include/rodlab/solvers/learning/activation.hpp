#pragma once
// The activation functions of the dense layers (mlp.hpp) and their derivatives, written in terms
// of the activation's output a = f(z) so that the backward pass needs no stored pre-activation:
//   identity: f(z) = z,                f'(z) = 1
//   tanh:     f(z) = tanh z,           f'(z) = 1 - tanh^2 z = 1 - a^2
//   relu:     f(z) = max(z, 0),        f'(z) = 1 for z > 0, else 0 (a > 0 <=> z > 0; at the
//                                      kink z = 0 the derivative is taken as 0, as in PyTorch)
// Names in files and options: "identity", "tanh", "relu".
#include <string>
#include <string_view>

#include <Eigen/Core>

namespace rodlab::solvers::learning {

enum class Activation { identity, tanh, relu };

/// "identity", "tanh" or "relu".
const char* activation_name(Activation f);

/// The activation called `name`; throws std::invalid_argument naming the known ones otherwise.
Activation parse_activation(std::string_view name);

/// z <- f(z), elementwise, in place. z is a matrix, a vector or a block of one; it is taken by
/// const reference and written through const_cast so that a temporary block can be passed
/// (Eigen's documented idiom, "Writing Functions Taking Eigen Types as Parameters").
template <class Derived>
void activate_in_place(Activation f, const Eigen::MatrixBase<Derived>& z_out) {
  auto& z = const_cast<Eigen::MatrixBase<Derived>&>(z_out).derived();
  using Scalar = typename Derived::Scalar;
  switch (f) {
    case Activation::identity: break;
    case Activation::tanh: z.array() = z.array().tanh(); break;
    case Activation::relu: z.array() = z.array().max(Scalar(0)); break;
  }
}

/// delta <- delta .* f'(z), elementwise, with f'(z) from a = f(z) (the table above): the chain
/// rule through the activation, dL/dz = dL/da .* f'(z).
/// delta is written as z is above.
template <class Derived, class OtherDerived>
void multiply_by_derivative(Activation f, const Eigen::MatrixBase<OtherDerived>& a,
                            const Eigen::MatrixBase<Derived>& delta_out) {
  auto& delta = const_cast<Eigen::MatrixBase<Derived>&>(delta_out).derived();
  using Scalar = typename Derived::Scalar;
  switch (f) {
    case Activation::identity: break;
    case Activation::tanh: delta.array() *= Scalar(1) - a.array().square(); break;
    case Activation::relu:
      delta.array() = (a.array() > Scalar(0)).select(delta.array(), Scalar(0));
      break;
  }
}

}  // namespace rodlab::solvers::learning
