// The neural-network layer (solvers/learning: mlp, activation, loss, adam, regression, mlp_json):
// backpropagation against central finite differences (parameters and inputs; double and float),
// Adam against closed forms (its first step, a linear least-squares fit) and on a small fit of
// sin x, initialisation and seeds, the file format's round trip and its errors, and the
// allocation-free paths.
#define BOOST_TEST_MODULE learning_mlp
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "allocation_counter.hpp"
#include "rodlab/solvers/learning/adam.hpp"
#include "rodlab/solvers/learning/loss.hpp"
#include "rodlab/solvers/learning/mlp.hpp"
#include "rodlab/solvers/learning/mlp_json.hpp"
#include "rodlab/solvers/learning/regression.hpp"

namespace learning = rodlab::solvers::learning;
using learning::Activation;
using learning::Mlp;
using learning::MlpConfig;

namespace {

template <class S>
using Mat = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <class S>
using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;

/// Entries uniform in [-1, 1) from a fixed seed.
template <class S>
Mat<S> uniform(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Mat<S> out(rows, cols);
  for (Eigen::Index k = 0; k < out.size(); ++k)
    out.data()[k] = static_cast<S>(2.0 * static_cast<double>(rng() >> 11) * 0x1.0p-53 - 1.0);
  return out;
}

template <class S>
Mlp<S> network(std::vector<int> sizes, Activation hidden, Activation output,
               std::uint64_t seed = 7) {
  return Mlp<S>(MlpConfig{.sizes = std::move(sizes), .hidden = hidden, .output = output,
                          .seed = seed});
}

template <class S>
S loss(const Mlp<S>& net, const Mat<S>& x, const Mat<S>& t) {
  learning::MlpWorkspace<S> ws;
  return learning::mse_loss(net.forward(x, ws), t);
}

/// dL/dtheta and dL/dx by backpropagation.
template <class S>
void backprop(const Mlp<S>& net, const Mat<S>& x, const Mat<S>& t, Vec<S>& gradient,
              Mat<S>& dloss_dx) {
  learning::MlpWorkspace<S> ws;
  Mat<S> dloss_dy;
  learning::mse_loss(net.forward(x, ws), t, &dloss_dy);
  gradient = Vec<S>::Zero(net.parameter_count());
  net.backward(ws, dloss_dy, &gradient, &dloss_dx);
}

/// Central differences (L(theta + h e_k) - L(theta - h e_k)) / 2h over every parameter.
template <class S>
Vec<S> fd_parameter_gradient(Mlp<S> net, const Mat<S>& x, const Mat<S>& t, S h) {
  Vec<S> out(net.parameter_count());
  for (Eigen::Index k = 0; k < out.size(); ++k) {
    const S theta = net.parameters()[k];
    net.parameters()[k] = theta + h;
    const S plus = loss(net, x, t);
    net.parameters()[k] = theta - h;
    const S minus = loss(net, x, t);
    net.parameters()[k] = theta;
    out[k] = (plus - minus) / (2 * h);
  }
  return out;
}

/// Central differences over every input entry.
template <class S>
Mat<S> fd_input_gradient(const Mlp<S>& net, Mat<S> x, const Mat<S>& t, S h) {
  Mat<S> out(x.rows(), x.cols());
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const S xk = x.data()[k];
    x.data()[k] = xk + h;
    const S plus = loss(net, x, t);
    x.data()[k] = xk - h;
    const S minus = loss(net, x, t);
    x.data()[k] = xk;
    out.data()[k] = (plus - minus) / (2 * h);
  }
  return out;
}

/// max_k |a_k - b_k| / max_k |b_k|: the error relative to the gradient's scale (a component
/// near zero is held to the same absolute accuracy as the largest one).
template <class Derived, class OtherDerived>
double relative_error(const Eigen::MatrixBase<Derived>& a,
                      const Eigen::MatrixBase<OtherDerived>& b) {
  return static_cast<double>((a - b).cwiseAbs().maxCoeff()) /
         static_cast<double>(b.cwiseAbs().maxCoeff());
}

/// The smallest |z| over every pre-activation z_l = W_l a_l + b_l of the batch (a relu kink
/// within the finite-difference step would spoil the comparison).
template <class S>
double smallest_preactivation(const Mlp<S>& net, const Mat<S>& x) {
  learning::MlpWorkspace<S> ws;
  net.forward(x, ws);
  double smallest = std::numeric_limits<double>::infinity();
  for (int l = 0; l < net.layer_count(); ++l) {
    const Mat<S> z = (net.weight(l) * ws.activations[l]).colwise() + net.bias(l);
    smallest = std::min(smallest, static_cast<double>(z.cwiseAbs().minCoeff()));
  }
  return smallest;
}

struct GradientCase {
  Activation hidden, output;
};
constexpr GradientCase kGradientCases[] = {{Activation::tanh, Activation::identity},
                                           {Activation::tanh, Activation::tanh},
                                           {Activation::relu, Activation::identity},
                                           {Activation::relu, Activation::tanh}};

/// Both gradients of the MSE of a 3-6-5-2 network on a batch of 4 against central differences
/// with step h; returns the larger relative error after checking the relu kinks are clear.
template <class S>
double gradient_check(const GradientCase& c, S h, double kink_margin) {
  const Mlp<S> net = network<S>({3, 6, 5, 2}, c.hidden, c.output, 13);
  const Mat<S> x = uniform<S>(3, 4, 1), t = uniform<S>(2, 4, 2);
  BOOST_TEST_REQUIRE(smallest_preactivation(net, x) > kink_margin);
  Vec<S> gradient;
  Mat<S> dloss_dx;
  backprop(net, x, t, gradient, dloss_dx);
  const double parameter_error = relative_error(gradient, fd_parameter_gradient(net, x, t, h));
  const double input_error = relative_error(dloss_dx, fd_input_gradient(net, x, t, h));
  BOOST_TEST_MESSAGE(learning::activation_name(c.hidden)
                     << "/" << learning::activation_name(c.output) << ": parameters "
                     << parameter_error << ", inputs " << input_error);
  return std::max(parameter_error, input_error);
}

}  // namespace

// Reference: central differences with h = 1e-6 (truncation h^2 |L'''| ~ 1e-12, rounding
// eps |L| / h ~ 1e-10: measured 1.6e-10 .. 3.4e-10). Tolerance: 1e-6 relative to the largest
// component, for dL/dtheta and dL/dx, tanh and relu hidden layers, identity and tanh outputs.
// Every pre-activation is at least 1e-4 from the relu kink, which a step of 1e-6 cannot cross.
BOOST_AUTO_TEST_CASE(double_gradients_match_finite_differences) {
  for (const auto& c : kGradientCases) BOOST_TEST(gradient_check<double>(c, 1e-6, 1e-4) < 1e-6);
}

// The same in float, h = 3e-3: the rounding of the float loss, about eps_f |L| / h = 6e-8 |L| /
// 3e-3 = 2e-5 |L|, and the truncation h^2 |L'''| / 6 ~ 1e-6 stay near 1e-4 of the gradient's
// scale (measured 2.3e-5 .. 1.1e-4 here; h = 1e-3 gives up to 3e-4 and h = 3e-4 up to 9e-4 as
// rounding takes over). Tolerance: 1e-3 relative. The relu kinks are kept 1e-2 away (the
// smallest |z| is 1.5e-2), more than a step of 3e-3 moves a pre-activation here.
BOOST_AUTO_TEST_CASE(float_gradients_match_finite_differences) {
  for (const auto& c : kGradientCases) BOOST_TEST(gradient_check<float>(c, 3e-3f, 1e-2) < 1e-3);
}

// backward adds to the gradient: twice is exactly 2x once (powers of two are exact); without a
// gradient vector it still returns dL/dx, equal to the one computed with it.
BOOST_AUTO_TEST_CASE(backward_accumulates_and_input_gradient_alone) {
  const Mlp<double> net = network<double>({3, 4, 2}, Activation::tanh, Activation::identity);
  const Mat<double> x = uniform<double>(3, 5, 3), t = uniform<double>(2, 5, 4);
  learning::MlpWorkspace<double> ws;
  Mat<double> dloss_dy, dx_with, dx_alone;
  learning::mse_loss(net.forward(x, ws), t, &dloss_dy);
  Vec<double> once = Vec<double>::Zero(net.parameter_count());
  net.backward(ws, dloss_dy, &once, &dx_with);
  Vec<double> twice = once;
  net.backward(ws, dloss_dy, &twice);
  BOOST_TEST((twice - 2.0 * once).cwiseAbs().maxCoeff() == 0.0);
  net.backward(ws, dloss_dy, nullptr, &dx_alone);
  BOOST_TEST((dx_alone - dx_with).cwiseAbs().maxCoeff() == 0.0);
}

// Adam's first step (Kingma & Ba 2015, Algorithm 1): with m_hat = g and v_hat = g^2 after the
// bias correction, theta moves by -alpha g / (|g| + eps) (closed form), to the rounding of theta
// (1e-15 absolute for |theta| <= 2); without the correction it would move by
// -alpha (1 - beta1) / sqrt(1 - beta2) g / |g|, 3.2 times as far.
BOOST_AUTO_TEST_CASE(adam_first_step_is_the_bias_corrected_sign) {
  learning::Adam<double> adam(3, learning::AdamOptions{.learning_rate = 0.01});
  Vec<double> theta(3), g(3);
  theta << 1.0, -2.0, 0.5;
  g << 0.3, -4.0, 1e-3;
  const Vec<double> before = theta;
  adam.step(theta, g);
  for (int k = 0; k < 3; ++k) {
    const double expected = -0.01 * g[k] / (std::abs(g[k]) + 1e-8);
    BOOST_TEST(std::abs((theta[k] - before[k]) - expected) < 1e-15);
  }
  BOOST_TEST(adam.step_count() == 1);
}

// A linear network (no hidden layer, identity output) fitted by full-batch Adam (learning rate
// 1e-2, 3000 steps) to noise-free data from y = A x + c: the least-squares optimum is (A, c)
// itself (closed form), recovered to 1e-6 in every entry (measured 2e-15; it stays below 4e-15
// up to 8000 steps).
BOOST_AUTO_TEST_CASE(adam_recovers_a_linear_map) {
  Mat<double> A(2, 3);
  A << 0.5, -1.0, 2.0,  //
      1.5, 0.25, -0.75;
  Vec<double> c(2);
  c << 0.3, -0.2;
  const Mat<double> X = uniform<double>(3, 40, 5);
  const Mat<double> Y = (A * X).colwise() + c;
  Mlp<double> net = network<double>({3, 2}, Activation::identity, Activation::identity);
  learning::Adam<double> adam(net.parameter_count(), {.learning_rate = 1e-2});
  learning::fit_regression(net, adam, X, Y, {.epochs = 3000, .batch_size = 40, .seed = 1});
  const double error = std::max((net.weight(0) - A).cwiseAbs().maxCoeff(),
                                (net.bias(0) - c).cwiseAbs().maxCoeff());
  BOOST_TEST_MESSAGE("linear map error " << error);
  BOOST_TEST(error < 1e-6);
}

// A 1-16-16-1 tanh network fitted to y = sin x at 256 points of [-pi, pi] by minibatch Adam
// (batch 32, 400 epochs, seed 3): the mean squared error over the points falls below 1e-3
// (measured 7.6e-5; the best constant, 0, has MSE 0.5).
BOOST_AUTO_TEST_CASE(a_tanh_network_fits_sin) {
  const int n = 256;
  Mat<double> X(1, n), Y(1, n);
  for (int j = 0; j < n; ++j) {
    X(0, j) = -std::numbers::pi + 2.0 * std::numbers::pi * j / (n - 1);
    Y(0, j) = std::sin(X(0, j));
  }
  Mlp<double> net = network<double>({1, 16, 16, 1}, Activation::tanh, Activation::identity, 3);
  learning::Adam<double> adam(net.parameter_count(), {.learning_rate = 1e-2});
  const auto fit =
      learning::fit_regression(net, adam, X, Y, {.epochs = 400, .batch_size = 32, .seed = 3});
  const double mse = loss(net, X, Y);
  BOOST_TEST_MESSAGE("sin fit: first epoch " << fit.epoch_loss.front() << ", last "
                                             << fit.epoch_loss.back() << ", final MSE " << mse);
  BOOST_TEST(fit.epoch_loss.size() == 400u);
  BOOST_TEST(mse < 1e-3);
}

// The seed alone fixes the initial parameters and the training: the same seed gives
// bit-identical parameters and outputs (also after a fit with the same shuffle seed), another
// seed different ones; a float network is the double network of its seed rounded to float.
BOOST_AUTO_TEST_CASE(seeds_fix_everything) {
  const auto make = [](std::uint64_t seed) {
    return network<double>({4, 8, 8, 2}, Activation::relu, Activation::tanh, seed);
  };
  Mlp<double> a = make(42), b = make(42);
  const Mlp<double> other = make(43);
  BOOST_TEST(std::memcmp(a.parameters().data(), b.parameters().data(),
                         sizeof(double) * a.parameter_count()) == 0);
  BOOST_TEST((a.parameters() - other.parameters()).cwiseAbs().maxCoeff() > 0.1);
  const Mat<double> X = uniform<double>(4, 20, 8), Y = uniform<double>(2, 20, 9);
  learning::MlpWorkspace<double> wa, wb;
  BOOST_TEST((a.forward(X, wa) - b.forward(X, wb)).cwiseAbs().maxCoeff() == 0.0);
  learning::Adam<double> adam_a(a.parameter_count()), adam_b(b.parameter_count());
  learning::fit_regression(a, adam_a, X, Y, {.epochs = 5, .batch_size = 6, .seed = 2});
  learning::fit_regression(b, adam_b, X, Y, {.epochs = 5, .batch_size = 6, .seed = 2});
  BOOST_TEST(std::memcmp(a.parameters().data(), b.parameters().data(),
                         sizeof(double) * a.parameter_count()) == 0);
  const Mlp<float> f = network<float>({4, 8, 8, 2}, Activation::relu, Activation::tanh, 42);
  BOOST_TEST((f.parameters() - make(42).parameters().cast<float>()).cwiseAbs().maxCoeff() == 0.0f);
}

// Initial weights: within Glorot's bound sqrt(6 / (fan_in + fan_out)) for tanh and identity
// layers and He's sqrt(6 / fan_in) for relu layers, filling it (max |W| > 0.95 of the bound on a
// 64 x 64 layer: 4096 uniform draws reach it with probability 1 - 0.95^4096), biases zero;
// final_layer_scale 3e-3 puts the output layer's W and b in [-3e-3, 3e-3].
BOOST_AUTO_TEST_CASE(initialisation_bounds) {
  for (Activation hidden : {Activation::tanh, Activation::relu}) {
    const Mlp<double> net = network<double>({10, 64, 64, 4}, hidden, Activation::identity);
    for (int l = 0; l < net.layer_count(); ++l) {
      const double fan_in = net.sizes()[l], fan_out = net.sizes()[l + 1];
      const double bound = net.activation(l) == Activation::relu
                               ? std::sqrt(6.0 / fan_in)
                               : std::sqrt(6.0 / (fan_in + fan_out));
      const double largest = net.weight(l).cwiseAbs().maxCoeff();
      BOOST_TEST(largest <= bound);
      if (l == 1) BOOST_TEST(largest > 0.95 * bound);
      BOOST_TEST(net.bias(l).cwiseAbs().maxCoeff() == 0.0);
    }
  }
  const Mlp<double> ddpg(MlpConfig{.sizes = {10, 64, 64, 4}, .hidden = Activation::relu,
                                   .output = Activation::tanh, .seed = 1,
                                   .final_layer_scale = 3e-3});
  BOOST_TEST(ddpg.weight(2).cwiseAbs().maxCoeff() <= 3e-3);
  BOOST_TEST(ddpg.bias(2).cwiseAbs().maxCoeff() <= 3e-3);
  BOOST_TEST(ddpg.bias(2).cwiseAbs().maxCoeff() > 0.0);
  BOOST_TEST(ddpg.weight(0).cwiseAbs().maxCoeff() > 0.1);  // the other layers as before
}

// target <- tau source + (1 - tau) target, entry by entry as written (exact); tau = 1 and
// copy_parameters_from copy; a network of another shape or tau outside [0, 1] is refused.
BOOST_AUTO_TEST_CASE(soft_update_and_copy) {
  const Mlp<double> source = network<double>({3, 5, 2}, Activation::relu, Activation::identity, 1);
  Mlp<double> target = network<double>({3, 5, 2}, Activation::relu, Activation::identity, 2);
  const Vec<double> before = target.parameters();
  target.soft_update_from(source, 0.01);
  const Vec<double> expected = 0.01 * source.parameters() + (1.0 - 0.01) * before;
  BOOST_TEST((target.parameters() - expected).cwiseAbs().maxCoeff() == 0.0);
  target.soft_update_from(source, 1.0);
  BOOST_TEST((target.parameters() - source.parameters()).cwiseAbs().maxCoeff() == 0.0);
  Mlp<double> copy = network<double>({3, 5, 2}, Activation::relu, Activation::identity, 3);
  copy.copy_parameters_from(source);
  BOOST_TEST((copy.parameters() - source.parameters()).cwiseAbs().maxCoeff() == 0.0);
  Mlp<double> wider = network<double>({3, 6, 2}, Activation::relu, Activation::identity);
  BOOST_CHECK_THROW(wider.soft_update_from(source, 0.1), std::invalid_argument);
  BOOST_CHECK_THROW(wider.copy_parameters_from(source), std::invalid_argument);
  Mlp<double> tanh_net = network<double>({3, 5, 2}, Activation::tanh, Activation::identity);
  BOOST_CHECK_THROW(tanh_net.copy_parameters_from(source), std::invalid_argument);
  BOOST_CHECK_THROW(target.soft_update_from(source, 1.5), std::invalid_argument);
}

// Save and load: the parameters come back bit for bit (memcmp), for double (with hard values
// planted: 0.1, 1/3, the next double after 1, the smallest subnormal, the largest double, -0)
// and float; a float32 file reads into a double network exactly; the loaded network's outputs
// are the saved one's (0 difference).
BOOST_AUTO_TEST_CASE(save_and_load_round_trip_bit_for_bit) {
  Mlp<double> net = network<double>({3, 7, 2}, Activation::tanh, Activation::tanh, 5);
  auto theta = net.parameters();
  theta[0] = 0.1;
  theta[1] = 1.0 / 3.0;
  theta[2] = std::nextafter(1.0, 2.0);
  theta[3] = std::numeric_limits<double>::denorm_min();
  theta[4] = std::numeric_limits<double>::max();
  theta[5] = -0.0;
  const std::string text = learning::to_json(net);
  const Mlp<double> back = learning::from_json<double>(text);
  BOOST_TEST(back.same_shape(net));
  BOOST_TEST(std::memcmp(back.parameters().data(), net.parameters().data(),
                         sizeof(double) * net.parameter_count()) == 0);
  theta[4] = 0.25;  // a finite output for the comparison below
  const Mlp<double> reloaded = learning::from_json<double>(learning::to_json(net));
  const Mat<double> x = uniform<double>(3, 6, 6);
  learning::MlpWorkspace<double> w1, w2;
  BOOST_TEST((reloaded.forward(x, w1) - net.forward(x, w2)).cwiseAbs().maxCoeff() == 0.0);

  const Mlp<float> f = network<float>({2, 9, 9, 3}, Activation::relu, Activation::identity, 6);
  const std::string ftext = learning::to_json(f);
  const Mlp<float> fback = learning::from_json<float>(ftext);
  BOOST_TEST(std::memcmp(fback.parameters().data(), f.parameters().data(),
                         sizeof(float) * f.parameter_count()) == 0);
  const Mlp<double> widened = learning::from_json<double>(ftext);
  BOOST_TEST((widened.parameters() - f.parameters().cast<double>()).cwiseAbs().maxCoeff() == 0.0);
}

namespace {

/// The message of the std::invalid_argument that from_json<S>(text) throws ("" if none).
template <class S>
std::string load_error(const std::string& text) {
  try {
    learning::from_json<S>(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

/// `text` with the first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  BOOST_TEST_REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

// Bad files throw std::invalid_argument naming the field: wrong schema, wrong scalar, float64
// into a float network, unknown activation, sizes that disagree with a W row, a missing field,
// a wrong type, not JSON.
BOOST_AUTO_TEST_CASE(bad_files_name_the_field) {
  const Mlp<double> net = network<double>({2, 3, 1}, Activation::tanh, Activation::identity);
  const std::string good = learning::to_json(net);
  const auto contains = [](const std::string& message, const std::string& part) {
    BOOST_TEST_MESSAGE(message);
    return message.find(part) != std::string::npos;
  };
  BOOST_TEST(contains(load_error<double>(replaced(good, "rodlab.mlp/1", "rodlab.mlp/2")),
                      "schema is 'rodlab.mlp/2'"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "float64", "float16")), "scalar"));
  BOOST_TEST(contains(load_error<float>(good), "scalar is float64"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "\"tanh\"", "\"sigmoid\"")),
                      "hidden_activation is 'sigmoid'"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "[2,3,1]", "[2,4,1]")),
                      "layers[0].W has 3 entries, expected 4 (sizes[1])"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "[2,3,1]", "[3,3,1]")),
                      "layers[0].W[0] has 2 entries, expected 3 (sizes[0])"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "[2,3,1]", "[2,3,1,1]")),
                      "layers has 2 entries, expected 3"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "\"b\":", "\"bias\":")),
                      "missing field layers[0].b"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "\"b\":[", "\"b\":[\"x\",")),
                      "layers[0].b has 4 entries"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "\"b\":[0.0", "\"b\":[\"0\"")),
                      "layers[0].b[0] must be a number"));
  BOOST_TEST(contains(load_error<double>(replaced(good, "\"sizes\"", "\"size\"")),
                      "missing field sizes"));
  BOOST_TEST(contains(load_error<double>(good.substr(0, good.size() / 2)), "not JSON"));
  BOOST_TEST(contains(load_error<double>("[1, 2]"), "the document must be an object"));
  Mlp<double> diverged = net;
  diverged.parameters()[1] = std::numeric_limits<double>::quiet_NaN();
  BOOST_CHECK_THROW(learning::to_json(diverged), std::invalid_argument);
}

// infer() against the batch forward pass of the same sample: equal to rounding (the
// matrix-vector and matrix-matrix products may sum in different orders; tolerance 4 eps of the
// output's scale, double and float; measured 0, bit for bit, with Eigen 3.4 here).
BOOST_AUTO_TEST_CASE(infer_equals_the_batch_forward_pass) {
  Mlp<double> net = network<double>({10, 64, 64, 4}, Activation::relu, Activation::tanh);
  Mlp<float> fnet = network<float>({10, 64, 64, 4}, Activation::tanh, Activation::identity);
  const Mat<double> x = uniform<double>(10, 1, 12);
  learning::MlpWorkspace<double> ws;
  learning::MlpWorkspace<float> fws;
  Vec<double> y(4);
  Vec<float> fy(4);
  net.infer(x.col(0), y);
  fnet.infer(x.col(0).cast<float>(), fy);
  const double error = (y - net.forward(x, ws).col(0)).cwiseAbs().maxCoeff();
  const double ferror = (fy - fnet.forward(x.cast<float>(), fws).col(0)).cwiseAbs().maxCoeff();
  BOOST_TEST_MESSAGE("infer - forward: double " << error << ", float " << ferror);
  BOOST_TEST(error <= 4 * std::numeric_limits<double>::epsilon());
  BOOST_TEST(ferror <= 4 * std::numeric_limits<float>::epsilon() * fy.cwiseAbs().maxCoeff());
  BOOST_CHECK_THROW(net.infer(Vec<double>::Zero(9), y), std::invalid_argument);
}

// No heap allocation (malloc counted, allocation_counter.hpp): infer() once the network exists,
// and a training step (forward, MSE, backward, Adam) at a fixed batch size after the first.
BOOST_AUTO_TEST_CASE(steady_state_does_not_allocate) {
  if (!rodlab::test::AllocationCounter::available()) {
    BOOST_TEST_MESSAGE("allocation counting is off under AddressSanitizer: not checked");
    return;
  }
  Mlp<float> net = network<float>({10, 64, 64, 4}, Activation::relu, Activation::identity);
  const Vec<float> x = uniform<float>(10, 1, 1).col(0);
  Vec<float> y(4);
  const Mat<float> X = uniform<float>(10, 64, 2), T = uniform<float>(4, 64, 3);
  learning::MlpWorkspace<float> ws;
  Mat<float> dloss_dy;
  Vec<float> gradient(net.parameter_count());
  learning::Adam<float> adam(net.parameter_count());
  const auto train_step = [&] {
    learning::mse_loss(net.forward(X, ws), T, &dloss_dy);
    gradient.setZero();
    net.backward(ws, dloss_dy, &gradient);
    adam.step(net.parameters(), gradient);
  };
  train_step();  // sizes the workspace
  long infer_allocations = 0, step_allocations = 0;
  {
    rodlab::test::AllocationCounter counter;
    for (int i = 0; i < 100; ++i) net.infer(x, y);
    infer_allocations = counter.count();
  }
  {
    rodlab::test::AllocationCounter counter;
    for (int i = 0; i < 10; ++i) train_step();
    step_allocations = counter.count();
  }
  BOOST_TEST(infer_allocations == 0);
  BOOST_TEST(step_allocations == 0);
  {  // the counter itself sees allocations
    rodlab::test::AllocationCounter counter;
    Mat<float> fresh(100, 100);
    fresh.setZero();
    BOOST_TEST_REQUIRE(counter.count() >= 1);
  }
}

// Sizes and arguments are checked at every entry (Pinocchio's rule), with the numbers.
BOOST_AUTO_TEST_CASE(bad_arguments_are_refused) {
  BOOST_CHECK_THROW(Mlp<double>(MlpConfig{.sizes = {3}}), std::invalid_argument);
  BOOST_CHECK_THROW(Mlp<double>(MlpConfig{.sizes = {3, 0, 1}}), std::invalid_argument);
  BOOST_CHECK_THROW(Mlp<double>(MlpConfig{.sizes = {3, 1}, .final_layer_scale = -1.0}),
                    std::invalid_argument);
  const Mlp<double> net = network<double>({3, 4, 2}, Activation::tanh, Activation::identity);
  learning::MlpWorkspace<double> ws;
  BOOST_CHECK_THROW(net.forward(Mat<double>::Zero(2, 5), ws), std::invalid_argument);
  BOOST_CHECK_THROW(net.backward(ws, Mat<double>::Zero(2, 5), nullptr), std::invalid_argument);
  net.forward(Mat<double>::Zero(3, 5), ws);
  Vec<double> short_gradient(3);
  BOOST_CHECK_THROW(net.backward(ws, Mat<double>::Zero(2, 4), nullptr), std::invalid_argument);
  BOOST_CHECK_THROW(net.backward(ws, Mat<double>::Zero(2, 5), &short_gradient),
                    std::invalid_argument);
  BOOST_CHECK_THROW(learning::mse_loss(Mat<double>::Zero(2, 5), Mat<double>::Zero(2, 4)),
                    std::invalid_argument);
  BOOST_CHECK_THROW(learning::Adam<double>(3, {.beta2 = 1.0}), std::invalid_argument);
  BOOST_TEST((learning::parse_activation("relu") == Activation::relu));
  BOOST_CHECK_THROW(learning::parse_activation("sigmoid"), std::invalid_argument);
}
