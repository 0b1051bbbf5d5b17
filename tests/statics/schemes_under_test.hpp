#pragma once
// The statics schemes every cross-scheme test in tests/statics runs: all statics entries of the
// scheme catalogue (rodlab::solvers::all_schemes()). A new statics scheme is covered by every
// test here once it is in the catalogue and the registry.
//
// The catalogue's order string is parsed into what the tests assert:
//   "1", "2", "4"  -> design order p; observed orders must be within 0.15 of p
//   ">=4"          -> at least 4; observed orders must be >= 4 - 0.15 (or at rounding level)
//   "spectral"     -> no algebraic order; errors must fall below a spectral threshold
#include <cmath>
#include <string>
#include <vector>

#include "rodlab/solvers/schemes.hpp"

namespace rodlab::testing::statics {

struct SchemeUnderTest {
  std::string name;
  std::string order;         ///< the catalogue's order string
  double design_order = 0;   ///< p (a lower bound for ">=p"); 0 for "spectral"
  bool at_least = false;     ///< order ">=p"
  bool spectral = false;     ///< order "spectral"
  bool implicit = false;
};

inline SchemeUnderTest describe(const solvers::SchemeInfo& info) {
  SchemeUnderTest s;
  s.name = std::string(info.name);
  s.order = std::string(info.order);
  s.implicit = info.implicit;
  if (s.order == "spectral") {
    s.spectral = true;
  } else if (s.order.rfind(">=", 0) == 0) {
    s.at_least = true;
    s.design_order = std::stod(s.order.substr(2));
  } else {
    s.design_order = std::stod(s.order);
  }
  return s;
}

/// The statics schemes, in catalogue order.
inline std::vector<SchemeUnderTest> statics_schemes_under_test() {
  std::vector<SchemeUnderTest> out;
  for (const auto& info : solvers::all_schemes())
    if (info.problem == solvers::Problem::statics) out.push_back(describe(info));
  return out;
}

/// Their names only.
inline std::vector<std::string> statics_scheme_names() {
  std::vector<std::string> names;
  for (const auto& s : statics_schemes_under_test()) names.push_back(s.name);
  return names;
}

/// Global dense schemes (spectral) cost O(N^3) per Newton step (chebyshev: ~2-16 s at N = 200
/// against milliseconds for shooting), and converge spectrally, so the unit tests cap their
/// grids at kSpectralMaxNodes.
inline constexpr int kSpectralMaxNodes = 51;

/// The grid for a scheme: spectral schemes drop the N above `spectral_max`.
inline std::vector<int> grid_for(const SchemeUnderTest& s, const std::vector<int>& grid,
                                 int spectral_max = kSpectralMaxNodes) {
  std::vector<int> out;
  for (const int n : grid)
    if (!s.spectral || n <= spectral_max) out.push_back(n);
  return out;
}

/// One N for a scheme: spectral schemes at most `spectral_max`.
inline int nodes_cap(const SchemeUnderTest& s, int n, int spectral_max = kSpectralMaxNodes) {
  return s.spectral && n > spectral_max ? spectral_max : n;
}

/// Effective order used to size grids: p, or a generous 6 for spectral schemes.
inline double effective_order(const SchemeUnderTest& s) { return s.spectral ? 6.0 : s.design_order; }

/// Nodes so that an error C (h/L)^p stays below `target` (relative), between lo and hi. For
/// spectral schemes, `spectral_nodes`.
inline int nodes_for(const SchemeUnderTest& s, double C, double target, int lo = 11, int hi = 4001,
                     int spectral_nodes = 33) {
  if (s.spectral) return spectral_nodes;
  const double steps = std::ceil(std::pow(C / target, 1.0 / s.design_order));
  const int n = static_cast<int>(steps) + 1;
  return n < lo ? lo : (n > hi ? hi : n);
}

}  // namespace rodlab::testing::statics
