#pragma once
// A network as a JSON document, readable with Python's json module and numpy alone
// (docs/learning.md "File format"):
//   {"schema": "rodlab.mlp/1", "scalar": "float64" | "float32", "sizes": [n_0, ..., n_L],
//    "hidden_activation": "tanh", "output_activation": "identity",
//    "layers": [{"W": [[row 0], ..., [row n_(l+1) - 1]], "b": [...]}, ...]}
// W_l row by row (n_(l+1) rows of n_l numbers: numpy's np.array(W) is out x in), b_l of n_(l+1)
// numbers; a layer computes f(W x + b) (mlp.hpp). Numbers are written as the shortest decimal
// that reads back to the same double (nlohmann::json's dump), so a float64 network round-trips
// bit for bit; a float32 network writes its values widened to double (exact) and reads them
// back exactly. Writing the file (atomically) is the caller's: rodlab::io::write_file_atomically.
#include <string>
#include <string_view>

#include "rodlab/solvers/learning/mlp.hpp"

namespace rodlab::solvers::learning {

/// The document, compact (one line) with a final newline. Throws std::invalid_argument when a
/// parameter is not finite (JSON has no NaN or infinity: a diverged network is not saved).
template <class Scalar>
std::string to_json(const Mlp<Scalar>& net);

/// The network of a document. Mlp<double> reads float64 and float32 files (widening is exact);
/// Mlp<float> reads float32 files only (narrowing would not round-trip). Throws
/// std::invalid_argument naming the offending field ("mlp file: layers[1].W has 3 rows,
/// expected 4 (sizes[2])") for text that is not JSON, a missing field, a wrong type, a schema
/// other than rodlab.mlp/1, an unknown scalar or activation, or sizes that do not match.
template <class Scalar>
Mlp<Scalar> from_json(std::string_view text);

extern template std::string to_json<double>(const Mlp<double>&);
extern template std::string to_json<float>(const Mlp<float>&);
extern template Mlp<double> from_json<double>(std::string_view);
extern template Mlp<float> from_json<float>(std::string_view);

}  // namespace rodlab::solvers::learning
