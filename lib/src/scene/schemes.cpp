#include "rodlab/scene/schemes.hpp"

#include <array>

namespace rodlab::scene {

std::span<const SchemeInfo> all_schemes() { return kSchemeCatalogue; }

const SchemeInfo& scheme_info(SchemeId id) { return kSchemeCatalogue[static_cast<int>(id)]; }

std::optional<SchemeInfo> find_scheme(std::string_view name) {
  for (const auto& s : kSchemeCatalogue)
    if (s.name == name) return s;
  return std::nullopt;
}

std::string scheme_names(Problem problem) {
  std::string out;
  for (const auto& s : kSchemeCatalogue) {
    if (s.problem != problem) continue;
    if (!out.empty()) out += ", ";
    out += s.name;
  }
  return out;
}

std::string_view to_string(Problem problem) {
  return problem == Problem::statics ? "statics" : "dynamics";
}

}  // namespace rodlab::scene
