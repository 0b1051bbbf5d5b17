#include "rodlab/solvers/learning/mlp_json.hpp"

#include <cmath>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {
namespace {

using Json = nlohmann::ordered_json;  // writes the format's key order
constexpr const char* kSchema = "rodlab.mlp/1";

template <class Scalar>
constexpr const char* scalar_name() {
  return std::is_same_v<Scalar, double> ? "float64" : "float32";
}

/// obj[key] (obj an object at `where`), or a throw naming where.key.
const Json& field(const Json& obj, const char* key, const std::string& where) {
  RODLAB_THROW_UNLESS(obj.is_object(), "mlp file: {} must be an object",
                      where.empty() ? "the document" : where);
  const auto it = obj.find(key);
  RODLAB_THROW_UNLESS(it != obj.end(), "mlp file: missing field {}{}",
                      where.empty() ? "" : where + ".", key);
  return *it;
}

const std::string& string_field(const Json& obj, const char* key) {
  const Json& value = field(obj, key, "");
  RODLAB_THROW_UNLESS(value.is_string(), "mlp file: {} must be a string", key);
  return value.get_ref<const std::string&>();
}

Activation activation_field(const Json& obj, const char* key) {
  const std::string& name = string_field(obj, key);
  for (Activation f : {Activation::identity, Activation::tanh, Activation::relu})
    if (name == activation_name(f)) return f;
  RODLAB_THROW_UNLESS(false, "mlp file: {} is '{}' (expected identity, tanh or relu)", key, name);
  return Activation::identity;  // not reached
}

/// An array of `count` entries at `where`; `expected` says where the count comes from.
const Json& array_of(const Json& value, std::size_t count, const std::string& where,
                     const std::string& expected) {
  RODLAB_THROW_UNLESS(value.is_array(), "mlp file: {} must be an array", where);
  RODLAB_THROW_UNLESS(value.size() == count, "mlp file: {} has {} {}, expected {} ({})", where,
                      value.size(), value.size() == 1 ? "entry" : "entries", count, expected);
  return value;
}

template <class Scalar>
Scalar number(const Json& value, const std::string& where) {
  RODLAB_THROW_UNLESS(value.is_number(), "mlp file: {} must be a number", where);
  const auto x = static_cast<Scalar>(value.get<double>());
  RODLAB_THROW_UNLESS(std::isfinite(x), "mlp file: {} is out of range ({})", where,
                      value.get<double>());
  return x;
}

std::vector<int> sizes_field(const Json& doc) {
  const Json& sizes = field(doc, "sizes", "");
  RODLAB_THROW_UNLESS(sizes.is_array() && sizes.size() >= 2,
                      "mlp file: sizes must be an array of at least two layer sizes");
  std::vector<int> out;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    RODLAB_THROW_UNLESS(sizes[i].is_number_integer() && sizes[i].get<long long>() >= 1 &&
                            sizes[i].get<long long>() <= 1'000'000,
                        "mlp file: sizes[{}] must be an integer in [1, 10^6]", i);
    out.push_back(sizes[i].get<int>());
  }
  return out;
}

/// Throws unless layers[l] holds W as sizes[l+1] rows of sizes[l] entries and b of sizes[l+1]
/// (checked before the network is made, so that its size is bounded by the file's).
void check_layer_shape(const Json& layer, std::size_t l, const std::vector<int>& sizes) {
  const std::string where = rodlab::format("layers[{}]", l);
  const auto rows = static_cast<std::size_t>(sizes[l + 1]);
  const auto cols = static_cast<std::size_t>(sizes[l]);
  const std::string rows_from = rodlab::format("sizes[{}]", l + 1);
  const Json& W = array_of(field(layer, "W", where), rows, where + ".W", rows_from);
  for (std::size_t i = 0; i < rows; ++i)
    array_of(W[i], cols, rodlab::format("{}.W[{}]", where, i), rodlab::format("sizes[{}]", l));
  array_of(field(layer, "b", where), rows, where + ".b", rows_from);
}

/// W_l and b_l from layers[l] (its shape checked).
template <class Scalar>
void read_layer(const Json& layer, int l, Mlp<Scalar>& net) {
  auto weight = net.weight(l);
  auto bias = net.bias(l);
  for (Eigen::Index i = 0; i < weight.rows(); ++i)
    for (Eigen::Index j = 0; j < weight.cols(); ++j)
      weight(i, j) = number<Scalar>(layer["W"][i][j],
                                    rodlab::format("layers[{}].W[{}][{}]", l, i, j));
  for (Eigen::Index i = 0; i < bias.size(); ++i)
    bias[i] = number<Scalar>(layer["b"][i], rodlab::format("layers[{}].b[{}]", l, i));
}

}  // namespace

template <class Scalar>
std::string to_json(const Mlp<Scalar>& net) {
  const auto theta = net.parameters();
  for (Eigen::Index k = 0; k < theta.size(); ++k)
    RODLAB_THROW_UNLESS(std::isfinite(theta[k]),
                        "mlp: cannot save a network with a non-finite parameter (index {})", k);
  Json layers = Json::array();
  for (int l = 0; l < net.layer_count(); ++l) {
    const auto W = net.weight(l);
    const auto b = net.bias(l);
    Json rows = Json::array();
    for (Eigen::Index i = 0; i < W.rows(); ++i) {
      Json row = Json::array();
      for (Eigen::Index j = 0; j < W.cols(); ++j) row.push_back(static_cast<double>(W(i, j)));
      rows.push_back(std::move(row));
    }
    Json bias = Json::array();
    for (Eigen::Index i = 0; i < b.size(); ++i) bias.push_back(static_cast<double>(b[i]));
    layers.push_back(Json{{"W", std::move(rows)}, {"b", std::move(bias)}});
  }
  const Json doc{{"schema", kSchema},
                 {"scalar", scalar_name<Scalar>()},
                 {"sizes", net.sizes()},
                 {"hidden_activation", activation_name(net.hidden_activation())},
                 {"output_activation", activation_name(net.output_activation())},
                 {"layers", std::move(layers)}};
  return doc.dump() + "\n";  // shortest round-trip numbers
}

template <class Scalar>
Mlp<Scalar> from_json(std::string_view text) {
  Json doc;
  try {
    doc = Json::parse(text);
  } catch (const Json::parse_error& e) {
    RODLAB_THROW_UNLESS(false, "mlp file: not JSON ({})", e.what());
  }
  const std::string& schema = string_field(doc, "schema");
  RODLAB_THROW_UNLESS(schema == kSchema, "mlp file: schema is '{}', expected '{}'", schema,
                      kSchema);
  const std::string& scalar = string_field(doc, "scalar");
  RODLAB_THROW_UNLESS(scalar == "float64" || scalar == "float32",
                      "mlp file: scalar is '{}', expected float64 or float32", scalar);
  constexpr bool is_double = std::is_same_v<Scalar, double>;
  RODLAB_THROW_UNLESS(scalar == "float32" || is_double,
                      "mlp file: scalar is float64, which a float32 network cannot hold exactly");
  MlpConfig config;
  config.sizes = sizes_field(doc);
  config.hidden = activation_field(doc, "hidden_activation");
  config.output = activation_field(doc, "output_activation");
  const Json& layers = array_of(field(doc, "layers", ""), config.sizes.size() - 1, "layers",
                                "one per pair of consecutive sizes");
  for (std::size_t l = 0; l < layers.size(); ++l) check_layer_shape(layers[l], l, config.sizes);
  Mlp<Scalar> net(config);
  for (int l = 0; l < net.layer_count(); ++l) read_layer(layers[l], l, net);
  return net;
}

template std::string to_json<double>(const Mlp<double>&);
template std::string to_json<float>(const Mlp<float>&);
template Mlp<double> from_json<double>(std::string_view);
template Mlp<float> from_json<float>(std::string_view);

}  // namespace rodlab::solvers::learning
