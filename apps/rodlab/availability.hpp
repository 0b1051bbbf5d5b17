#pragma once
// The one place that decides whether a feature can run yet. Schemes carry the issue that
// brings them in the catalogue (solvers::SchemeInfo::arrives, empty once implemented);
// features that are not a scheme are listed here.
#include <string_view>

#include "rodlab/solvers/schemes.hpp"

namespace rodlab::cli {

/// Throws NotAvailable("not available yet; it arrives with <arrives>") unless `arrives` is
/// empty. main.cpp prefixes "rodlab <command>: ".
void require_available(std::string_view arrives);
inline void require_available(const solvers::SchemeInfo& scheme) {
  require_available(scheme.arrives);
}

}  // namespace rodlab::cli
