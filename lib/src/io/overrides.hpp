#pragma once
// --set KEY=VALUE overrides applied to the YAML tree before checking (private to rodlab::io).
#include <yaml-cpp/yaml.h>

#include <span>
#include <string>
#include <vector>

#include "rodlab/io/scene_loader.hpp"
#include "yaml_checker.hpp"

namespace rodlab::io::detail {

/// "--set KEY=VALUE", the source that diagnostics about an override name.
std::string override_source(const Override& o);

/// Applies the overrides in order to `root` (a map). An override that cannot be applied adds a
/// diagnostic and changes nothing it has not already created. Returns, for every field an
/// override set or created, its normalised dotted path and the override's source, in order.
std::vector<OverrideOrigin> apply_overrides(YAML::Node& root, std::span<const Override> overrides,
                                            std::vector<SceneDiagnostic>& diagnostics);

}  // namespace rodlab::io::detail
