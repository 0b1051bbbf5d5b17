#pragma once
// The content of `rodlab check`: what a user wants to know about a scene before running it.
#include <string>

#include "rodlab/rod/characteristics.hpp"
#include "rodlab/scene/scene.hpp"

#include "report.hpp"

namespace rodlab::cli {

inline constexpr const char* kCheckSchema = "rodlab.check/1";

/// `nodes_from` says where the node count came from ("--nodes" or "solver.nodes").
Report check_report(const scene::Scene& scene, const rod::Characteristics& c,
                    const std::string& nodes_from);

}  // namespace rodlab::cli
