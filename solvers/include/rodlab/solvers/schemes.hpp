#pragma once
// The catalogue of schemes, with the names fixed by the interface spec (section 2).
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace rodlab::solvers {

enum class Problem { statics, dynamics };

struct SchemeInfo {
  std::string_view name;
  Problem problem;
  std::string_view order;   ///< design order: statics "1", "2", "4", ">=4", "spectral"; dynamics "p (t) / q (s)"
  bool implicit;            ///< implicit in the marching direction (s for statics, t for dynamics)
  bool reference;           ///< the SUNDIALS reference of its problem class
  std::string_view method;  ///< one-line description
  std::string_view arrives; ///< empty if implemented; otherwise the issue that brings it
};

/// All schemes, statics first, in the order of the spec's tables.
std::span<const SchemeInfo> all_schemes();

/// The scheme of that name, or nullopt.
std::optional<SchemeInfo> find_scheme(std::string_view name);

/// "a, b, c": the names of the schemes for a problem (for error messages).
std::string scheme_names(Problem problem);

std::string_view to_string(Problem problem);

}  // namespace rodlab::solvers
