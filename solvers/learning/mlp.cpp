#include "rodlab/solvers/learning/mlp.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

/// A double in [0, 1) from the top 53 bits of one mt19937_64 draw: specified bit for bit,
/// unlike std::uniform_real_distribution.
double unit_uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

/// The half-width r of the uniform initial weights of a layer followed by f: He et al. 2015
/// for relu, Glorot & Bengio 2010 (eq. 16) otherwise.
double initial_weight_bound(Activation f, int fan_in, int fan_out) {
  return f == Activation::relu ? std::sqrt(6.0 / fan_in) : std::sqrt(6.0 / (fan_in + fan_out));
}

}  // namespace

template <class Scalar>
Mlp<Scalar>::Mlp(const MlpConfig& config)
    : sizes_(config.sizes), hidden_(config.hidden), output_(config.output) {
  RODLAB_THROW_UNLESS(sizes_.size() >= 2,
                      "mlp: sizes must list the input and output sizes at least (got {} entries)",
                      sizes_.size());
  int widest_hidden = 0;
  Eigen::Index count = 0;
  for (std::size_t i = 0; i < sizes_.size(); ++i) {
    RODLAB_THROW_UNLESS(sizes_[i] >= 1, "mlp: sizes[{}] must be >= 1 (got {})", i, sizes_[i]);
    if (i > 0 && i + 1 < sizes_.size()) widest_hidden = std::max(widest_hidden, sizes_[i]);
    if (i > 0) {
      offsets_.push_back(count);
      count += Eigen::Index{sizes_[i]} * (sizes_[i - 1] + 1);  // W_l and b_l
    }
  }
  RODLAB_THROW_UNLESS(std::isfinite(config.final_layer_scale) && config.final_layer_scale >= 0.0,
                      "mlp: final_layer_scale must be >= 0 (got {:g})", config.final_layer_scale);
  parameters_.resize(count);
  scratch_[0].resize(widest_hidden);
  scratch_[1].resize(widest_hidden);
  initialise(config.seed, config.final_layer_scale);
}

template <class Scalar>
void Mlp<Scalar>::initialise(std::uint64_t seed, double final_layer_scale) {
  std::mt19937_64 rng(seed);
  for (int l = 0; l < layer_count(); ++l) {
    const bool scaled_output = l + 1 == layer_count() && final_layer_scale > 0.0;
    const double r = scaled_output ? final_layer_scale
                                   : initial_weight_bound(activation(l), sizes_[l], sizes_[l + 1]);
    auto W = weight(l);
    for (Eigen::Index i = 0; i < W.size(); ++i)  // column-major: the parameter order
      W.data()[i] = static_cast<Scalar>(r * (2.0 * unit_uniform(rng) - 1.0));
    auto b = bias(l);
    for (Eigen::Index i = 0; i < b.size(); ++i)
      b[i] = scaled_output ? static_cast<Scalar>(r * (2.0 * unit_uniform(rng) - 1.0)) : Scalar(0);
  }
}

template <class Scalar>
bool Mlp<Scalar>::same_shape(const Mlp& other) const {
  return sizes_ == other.sizes_ && hidden_ == other.hidden_ && output_ == other.output_;
}

template <class Scalar>
Eigen::Map<typename Mlp<Scalar>::Matrix> Mlp<Scalar>::weight(int layer) {
  return {parameters_.data() + offsets_[layer], sizes_[layer + 1], sizes_[layer]};
}

template <class Scalar>
Eigen::Map<const typename Mlp<Scalar>::Matrix> Mlp<Scalar>::weight(int layer) const {
  return {parameters_.data() + offsets_[layer], sizes_[layer + 1], sizes_[layer]};
}

template <class Scalar>
Eigen::Map<typename Mlp<Scalar>::Vector> Mlp<Scalar>::bias(int layer) {
  return {parameters_.data() + offsets_[layer] + Eigen::Index{sizes_[layer + 1]} * sizes_[layer],
          sizes_[layer + 1]};
}

template <class Scalar>
Eigen::Map<const typename Mlp<Scalar>::Vector> Mlp<Scalar>::bias(int layer) const {
  return {parameters_.data() + offsets_[layer] + Eigen::Index{sizes_[layer + 1]} * sizes_[layer],
          sizes_[layer + 1]};
}

template <class Scalar>
const typename Mlp<Scalar>::Matrix& Mlp<Scalar>::forward(const Eigen::Ref<const Matrix>& x,
                                                          Workspace& ws) const {
  RODLAB_THROW_UNLESS(x.rows() == input_size() && x.cols() >= 1,
                      "mlp: forward expected an input batch with {} rows and >= 1 column (got "
                      "{}x{})",
                      input_size(), x.rows(), x.cols());
  const Eigen::Index n = x.cols();
  const auto L = static_cast<std::size_t>(layer_count());
  ws.activations.resize(L + 1);  // allocates on first use only
  ws.deltas.resize(L);
  ws.activations[0].resize(input_size(), n);  // no-op at the same size
  ws.activations[0] = x;
  for (int l = 0; l < layer_count(); ++l) {
    Matrix& a = ws.activations[l + 1];
    a.resize(sizes_[l + 1], n);
    a.noalias() = weight(l) * ws.activations[l];  // z_l = W_l a_l + b_l 1^T
    a.colwise() += bias(l);
    activate_in_place(activation(l), a);  // a_(l+1) = f_l(z_l)
  }
  return ws.activations[L];
}

template <class Scalar>
void Mlp<Scalar>::backward(Workspace& ws, const Eigen::Ref<const Matrix>& dloss_doutput,
                           Vector* gradient, Matrix* dloss_dinput) const {
  const auto L = static_cast<std::size_t>(layer_count());
  RODLAB_THROW_UNLESS(ws.activations.size() == L + 1 && ws.deltas.size() == L,
                      "mlp: backward needs the workspace of a forward pass of this network");
  const Eigen::Index n = ws.activations[L].cols();
  RODLAB_THROW_UNLESS(ws.activations[L].rows() == output_size() &&
                          dloss_doutput.rows() == output_size() && dloss_doutput.cols() == n,
                      "mlp: backward expected dLoss/dy {}x{} (the last forward's output), got "
                      "{}x{}",
                      output_size(), n, dloss_doutput.rows(), dloss_doutput.cols());
  RODLAB_THROW_UNLESS(gradient == nullptr || gradient->size() == parameter_count(),
                      "mlp: backward expected a gradient of size {} (got {})", parameter_count(),
                      gradient == nullptr ? 0 : gradient->size());
  for (int l = layer_count() - 1; l >= 0; --l) {
    Matrix& delta = ws.deltas[l];
    if (l == layer_count() - 1)
      delta = dloss_doutput;
    else
      delta.noalias() = weight(l + 1).transpose() * ws.deltas[l + 1];  // W^T delta
    multiply_by_derivative(activation(l), ws.activations[l + 1], delta);  // .* f'_l(z_l)
    if (gradient != nullptr) {
      Eigen::Map<Matrix> dW(gradient->data() + offsets_[l], sizes_[l + 1], sizes_[l]);
      Eigen::Map<Vector> db(dW.data() + dW.size(), sizes_[l + 1]);
      dW.noalias() += delta * ws.activations[l].transpose();  // dLoss/dW_l = delta_l a_l^T
      db += delta.rowwise().sum();                            // dLoss/db_l = delta_l 1
    }
  }
  if (dloss_dinput != nullptr) {
    dloss_dinput->resize(input_size(), n);
    dloss_dinput->noalias() = weight(0).transpose() * ws.deltas[0];  // dLoss/dx = W_0^T delta_0
  }
}

template <class Scalar>
void Mlp<Scalar>::infer(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) {
  RODLAB_THROW_UNLESS(x.size() == input_size() && y.size() == output_size(),
                      "mlp: infer expected x of size {} and y of size {} (got {} and {})",
                      input_size(), output_size(), x.size(), y.size());
  const Scalar* in = x.data();
  for (int l = 0; l < layer_count(); ++l) {
    const Eigen::Map<const Vector> a(in, sizes_[l]);
    Scalar* out = l + 1 == layer_count() ? y.data() : scratch_[l % 2].data();
    Eigen::Map<Vector> z(out, sizes_[l + 1]);
    z.noalias() = weight(l) * a;
    z += bias(l);
    activate_in_place(activation(l), z);
    in = out;
  }
}

template <class Scalar>
void Mlp<Scalar>::copy_parameters_from(const Mlp& source) {
  RODLAB_THROW_UNLESS(same_shape(source),
                      "mlp: copy_parameters_from needs a network of the same sizes and "
                      "activations");
  parameters_ = source.parameters_;
}

template <class Scalar>
void Mlp<Scalar>::soft_update_from(const Mlp& source, Scalar tau) {
  RODLAB_THROW_UNLESS(same_shape(source),
                      "mlp: soft_update_from needs a network of the same sizes and activations");
  RODLAB_THROW_UNLESS(tau >= Scalar(0) && tau <= Scalar(1),
                      "mlp: soft_update_from needs tau in [0, 1] (got {:g})", tau);
  parameters_ = tau * source.parameters_ + (Scalar(1) - tau) * parameters_;
}

template class Mlp<double>;
template class Mlp<float>;

}  // namespace rodlab::solvers::learning
