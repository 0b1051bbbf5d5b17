#include "rodlab/solvers/learning/activation.hpp"

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {

const char* activation_name(Activation f) {
  switch (f) {
    case Activation::identity: return "identity";
    case Activation::tanh: return "tanh";
    case Activation::relu: return "relu";
  }
  return "unknown";
}

Activation parse_activation(std::string_view name) {
  for (Activation f : {Activation::identity, Activation::tanh, Activation::relu})
    if (name == activation_name(f)) return f;
  RODLAB_THROW_UNLESS(false, "activation: unknown '{}' (expected identity, tanh or relu)", name);
  return Activation::identity;  // not reached
}

}  // namespace rodlab::solvers::learning
