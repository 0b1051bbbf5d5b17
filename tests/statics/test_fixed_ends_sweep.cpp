#define BOOST_TEST_MODULE statics_fixed_ends_sweep
#include <boost/test/unit_test.hpp>
// rodlab-test-labels: validation

#include <cmath>
#include <sstream>
#include <string>

#include "fixed_ends_support.hpp"

// Case 7, complete sweep (validation: ~1000 solves): the thesis's fixed-ends problem (2.7.2),
// Table 2.1 Cosserat rod, tip clamped at [0.1 L, 0, L], identity rotation. Every scheme, every N
// from 5 to 200: converged from the solver's own start, tip on the target, and base wrench
// within C (h/L)^p (C = 2) of rkmk-rk4 at N = 1601. The thesis's implicit midpoint failed at
// N = 15 only; here no (scheme, N) may fail. Prints, per scheme, the failures (if any), the
// largest iteration count and the largest e / (h/L)^p. Runtime ~4 min, nearly all of it the
// dense chebyshev Newton at large N (5 s at N = 200); the shooting schemes take ~3 s together.

namespace {

using namespace rodlab;
using namespace rodlab::testing::statics;
using rod::ModelKind;

}  // namespace

BOOST_AUTO_TEST_CASE(every_scheme_every_n_5_to_200) {
  const auto problem = fixed_ends(ModelKind::cosserat);
  const auto ref = solve(problem, "rkmk-rk4", 1601);
  BOOST_TEST_REQUIRE(check_result(ref, 1601));
  for (const auto& s : statics_schemes_under_test()) {
    int failures = 0, max_it = 0, max_it_N = 0;
    double worst_ratio = 0.0;
    int worst_N = 0;
    std::ostringstream failed;
    for (int N = 5; N <= 200; ++N) {
      const auto r = solve(problem, s.name, N);
      const double e = check_fixed_ends(problem, s, r, ref);
      if (!r.converged) {
        ++failures;
        failed << " " << N;
        continue;
      }
      if (r.iterations > max_it) {
        max_it = r.iterations;
        max_it_N = N;
      }
      if (e > 1e-9) {  // e / (h/L)^p, or e 2^N for spectral schemes (bounded by C = 2), above the floor
        const double ratio = s.spectral ? e * std::pow(2.0, N) : e / std::pow(1.0 / (N - 1), s.design_order);
        if (ratio > worst_ratio) {
          worst_ratio = ratio;
          worst_N = N;
        }
      }
    }
    BOOST_TEST(failures == 0, s.name << " failed at N =" << failed.str());
    BOOST_TEST_MESSAGE(s.name << ": " << 196 - failures << "/196 converged" << (failures ? ", failed at N =" : "")
                              << failed.str() << "; max iterations " << max_it << " (N = " << max_it_N
                              << "), max e/(h/L)^p (spectral: e 2^N) = " << worst_ratio << " (N = " << worst_N << ")");
  }
}
