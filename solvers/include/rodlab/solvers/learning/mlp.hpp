#pragma once
// A multilayer perceptron: dense layers with one activation for the hidden layers and one for
// the output layer (issue #15; docs/learning.md "Neural networks"). The layer of DDPG's actor and
// critic and of Guided Policy Search's policy regression.
//
// Layers l = 0 .. L-1 map a batch with one column per sample, a_0 = x, to
//   z_l = W_l a_l + b_l 1^T,   a_(l+1) = f_l(z_l),   y = a_L,
// with W_l of size sizes[l+1] x sizes[l] (out x in), f_l the hidden activation for l < L-1 and
// the output activation for l = L-1 (activation.hpp). The backward pass is backpropagation
// (Rumelhart, Hinton & Williams 1986): given G = dLoss/dy,
//   delta_(L-1) = G .* f'_(L-1),   delta_(l-1) = (W_l^T delta_l) .* f'_(l-1),
//   dLoss/dW_l = delta_l a_l^T,  dLoss/db_l = delta_l 1 (row sums),  dLoss/dx = W_0^T delta_0.
//
// Parameters: one flat vector, layer by layer, W_l (column-major, Eigen's order) then b_l.
// weight(l) and bias(l) are views into it; a gradient has the same layout, so Adam (adam.hpp),
// the soft update of a target network and copies work on the whole vector at once.
//
// Initialisation (from the seed alone, never the clock): std::mt19937_64, each draw turned into
// a double in [0, 1) from its top 53 bits (std::uniform_real_distribution is not specified bit
// for bit, this is: the same seed gives the same weights with every standard library), drawn in
// the parameter order above. W_l is uniform in [-r, r] with r from the activation that follows
// the layer: Glorot & Bengio 2010 (eq. 16), r = sqrt(6 / (fan_in + fan_out)), for tanh and
// identity; He et al. 2015 (the uniform form of Var W = 2 / fan_in), r = sqrt(6 / fan_in), for
// relu. Biases start at zero. final_layer_scale s > 0 replaces this for the output layer: its W
// and b are both uniform in [-s, s] (Lillicrap et al. 2016, DDPG, section 7: s = 3e-3, so that
// the initial policy and value outputs are near zero). float networks draw in double and round,
// so float and double networks of one seed agree to float rounding.
//
// The batch's activations live in an MlpWorkspace that the caller owns, not in the network
// (Pinocchio's model/data split): the forward pass is const on the network, one network can have
// several batches in flight (DDPG's critic evaluates the replay batch for its own update and
// (s, mu(s)) for the actor's), and target networks and copies carry no batch storage. The
// workspace's matrices are resized only when the batch size changes: at a fixed batch size
// forward and backward do not allocate. infer() is the allocation-free single-sample path for
// real-time control: it uses scratch vectors owned by the network (so it is not const, and one
// network must not infer on two threads at once).
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "rodlab/solvers/learning/activation.hpp"

namespace rodlab::solvers::learning {

/// A network's shape and how its parameters start.
struct MlpConfig {
  std::vector<int> sizes;                    ///< input, hidden..., output: >= 2 entries, all >= 1
  Activation hidden = Activation::tanh;      ///< every hidden layer
  Activation output = Activation::identity;  ///< the output layer
  std::uint64_t seed = 0;                    ///< the initial weights (see above)
  /// > 0: the output layer's W and b start uniform in [-s, s] (DDPG: 3e-3); 0: as the others.
  double final_layer_scale = 0.0;
};

/// What a batch forward pass keeps for the backward pass (see above for why it is separate).
template <class Scalar>
struct MlpWorkspace {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  std::vector<Matrix> activations;  ///< a_0 = the input batch .. a_L = the output batch
  std::vector<Matrix> deltas;       ///< delta_l = dLoss/dz_l, l = 0 .. L-1 (backward)
};

template <class Scalar = double>
class Mlp {
 public:
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  using Workspace = MlpWorkspace<Scalar>;

  /// Throws std::invalid_argument for fewer than two sizes, a size < 1 or a negative or
  /// non-finite final_layer_scale.
  explicit Mlp(const MlpConfig& config);

  int input_size() const { return sizes_.front(); }
  int output_size() const { return sizes_.back(); }
  int layer_count() const { return static_cast<int>(sizes_.size()) - 1; }  ///< L
  const std::vector<int>& sizes() const { return sizes_; }
  Activation hidden_activation() const { return hidden_; }
  Activation output_activation() const { return output_; }
  /// f_l: the hidden activation for l < L-1, the output activation for l = L-1.
  Activation activation(int layer) const { return layer + 1 < layer_count() ? hidden_ : output_; }
  /// Same sizes and activations (what copies and soft updates require).
  bool same_shape(const Mlp& other) const;

  Eigen::Index parameter_count() const { return parameters_.size(); }
  Eigen::Map<Vector> parameters() { return {parameters_.data(), parameters_.size()}; }
  Eigen::Map<const Vector> parameters() const { return {parameters_.data(), parameters_.size()}; }
  Eigen::Map<Matrix> weight(int layer);  ///< W_l, a view into parameters()
  Eigen::Map<const Matrix> weight(int layer) const;
  Eigen::Map<Vector> bias(int layer);  ///< b_l, a view into parameters()
  Eigen::Map<const Vector> bias(int layer) const;
  /// Where W_l starts in the flat vector (b_l follows it): the same in a gradient.
  Eigen::Index weight_offset(int layer) const { return offsets_[layer]; }

  /// The output batch y (output_size x N) of an input batch x (input_size x N, N >= 1); `ws`
  /// keeps what backward needs. The reference stays valid until ws is used again. Throws
  /// std::invalid_argument when x has the wrong number of rows or no columns.
  const Matrix& forward(const Eigen::Ref<const Matrix>& x, Workspace& ws) const;

  /// Backpropagates dLoss/dy (the shape of the last forward's output, same ws) through the
  /// batch of the last forward pass. `gradient` (size parameter_count(), if given): dLoss/dtheta
  /// is ADDED to it (zero it first for a fresh gradient). `dloss_dinput` (if given): set to
  /// dLoss/dx, input_size x N. Throws std::invalid_argument on mismatched sizes.
  void backward(Workspace& ws, const Eigen::Ref<const Matrix>& dloss_doutput, Vector* gradient,
                Matrix* dloss_dinput = nullptr) const;

  /// y = the network at one sample x, without allocating (x and y contiguous, sized
  /// input_size and output_size; throws std::invalid_argument otherwise).
  void infer(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y);

  /// theta <- theta_source. Throws std::invalid_argument unless same_shape(source).
  void copy_parameters_from(const Mlp& source);
  /// theta <- tau theta_source + (1 - tau) theta, the target-network update of DDPG
  /// (Lillicrap et al. 2016, Algorithm 1). tau in [0, 1]; throws std::invalid_argument unless
  /// same_shape(source) and tau is in range.
  void soft_update_from(const Mlp& source, Scalar tau);

 private:
  void initialise(std::uint64_t seed, double final_layer_scale);

  std::vector<int> sizes_;
  Activation hidden_, output_;
  std::vector<Eigen::Index> offsets_;  // where W_l starts in parameters_
  Vector parameters_;
  Vector scratch_[2];  // infer(): the hidden activations, alternately
};

extern template class Mlp<double>;
extern template class Mlp<float>;

/// The same network in another scalar type: shape, activations and parameters (float to double
/// is exact, double to float rounds).
template <class To, class From>
Mlp<To> converted(const Mlp<From>& network) {
  MlpConfig config;
  config.sizes = network.sizes();
  config.hidden = network.hidden_activation();
  config.output = network.output_activation();
  Mlp<To> out(config);
  out.parameters() = network.parameters().template cast<To>();
  return out;
}

}  // namespace rodlab::solvers::learning
