#pragma once
// What `rodlab static` and `rodlab dynamic` do with a result: write it to --out (atomically,
// JSON or CSV by extension), print a summary, and choose the exit status.
#include <filesystem>
#include <optional>
#include <string>

#include "rodlab/result/dynamic_result.hpp"
#include "rodlab/result/static_result.hpp"

namespace rodlab::cli {

std::string summarize(const result::StaticResult& result);
std::string summarize(const result::DynamicResult& result);

/// Writes (if `out`), prints the summary (and where the ParaView files went, if `vtk`), returns
/// kSolved or kNotConverged.
int deliver(const result::StaticResult& result, const std::optional<std::filesystem::path>& out,
            const std::optional<std::filesystem::path>& vtk = std::nullopt);
int deliver(const result::DynamicResult& result, const std::optional<std::filesystem::path>& out,
            const std::optional<std::filesystem::path>& vtk = std::nullopt);

}  // namespace rodlab::cli
