#pragma once
// Shared by test_fixed_ends.cpp (unit) and test_fixed_ends_sweep.cpp (validation): the thesis's
// clamped-clamped problem (2.7.2, (2.113)-(2.115)) and the agreement check of a scheme's
// solution with a fine rkmk-rk4 reference.
//
// Both ends clamped, so the tip pose matches its target to the Newton tolerance for every
// scheme and N; what differs between schemes is the internal wrench, i.e. the shooting unknown
// Lambda(0), which determines the whole solution. The agreement measure is the base wrench made
// dimensionless by the problem's wrench scale (EI/L for moments, EI/L^2 for forces):
//     e = |(Lambda(0) - Lambda_ref(0)) ./ scale| / |Lambda_ref(0) ./ scale|,
// and the bound is e <= C (h/L)^p with C = 2, h/L = 1/(N-1). Measured max over N in 5..200 of
// e / (h/L)^p (Cosserat rod, target [0.1 L, 0, L], reference rk4 N = 1601): euler-explicit 0.15,
// euler-implicit 0.21, midpoint-explicit 1.04, midpoint-implicit 0.55, rk4 1.30 (at N = 5;
// 1.1 at N = 100).
#include <cmath>
#include <string>

#include "schemes_under_test.hpp"
#include "statics_support.hpp"

namespace rodlab::testing::statics {

inline constexpr double kFixedEndsC = 2.0;

/// Dimensionless relative difference of two base wrenches.
inline double base_wrench_error(const StaticProblem& problem, const StaticResult& r, const StaticResult& ref) {
  const Vector6& scale = problem.wrench_scale();
  return (r.base_wrench - ref.base_wrench).cwiseQuotient(scale).norm() / ref.base_wrench.cwiseQuotient(scale).norm();
}

/// The bound of fixed-ends agreement: error_bound (statics_support.hpp) with C = kFixedEndsC.
inline double agreement_bound(const SchemeUnderTest& s, int N, double C, double floor) {
  return error_bound(s, N, C, floor);
}

/// A result of N nodes: converged, tip at the target, base wrench within the bound. Returns
/// the base-wrench error (NaN if not converged).
inline double check_fixed_ends(const StaticProblem& problem, const SchemeUnderTest& s, const StaticResult& r,
                               const StaticResult& reference, double floor = 1e-9) {
  const int N = r.nodes;
  if (!check_result(r, N)) return std::nan("");
  const PoseError tip = pose_error(r.centerline.back().pose, problem.tip_target());
  BOOST_TEST(tip.max() <= 1e-11, describe(r) << ": tip off its target by " << tip.max());
  const double e = base_wrench_error(problem, r, reference);
  const double bound = agreement_bound(s, N, kFixedEndsC, floor);
  BOOST_TEST(e <= bound, describe(r) << ": base wrench differs from rk4 N=" << reference.nodes << " by " << e
                                     << " > C h^p = " << bound);
  return e;
}

}  // namespace rodlab::testing::statics
