#pragma once
// Central differences for the tests/lie Jacobian checks.
//
// Every Jacobian in rodlab::lie is "right-trivialised" (manif's convention): for f: G -> H,
//   f(g exp(d)) = f(g) exp(J d + O(|d|^2)),
// so its finite-difference estimate perturbs the input on the right, g exp(h e_j), and measures
// the output as the tangent f(g)^-1 f(g exp(h e_j)) = exp(.), i.e. with right_minus below.
// Vector-valued inputs and outputs are just the special case "+ d" and "- f(x)".
#include <Eigen/Core>

namespace rodlab::lie::testing {

/// Step of the central differences: truncation h^2 |f'''| / 6 ~ 1e-12 against rounding
/// eps |f| / h ~ 2e-10 |f|; tolerances of the FD checks are ~1e-7 relative.
inline constexpr double kFdStep = 1e-6;

/// Central-difference Jacobian at 0 of a map Matrix<N,1> -> Matrix<M,1>:
/// column j = (f(h e_j) - f(-h e_j)) / (2h).
template <int M, int N, class F>
Eigen::Matrix<double, M, N> central_jacobian(const F& f, double h = kFdStep) {
  Eigen::Matrix<double, M, N> J;
  for (int j = 0; j < N; ++j) {
    Eigen::Matrix<double, N, 1> d = Eigen::Matrix<double, N, 1>::Zero();
    d(j) = h;
    const Eigen::Matrix<double, M, 1> plus = f(d);
    const Eigen::Matrix<double, M, 1> minus = f(Eigen::Matrix<double, N, 1>(-d));
    J.col(j) = (plus - minus) / (2.0 * h);
  }
  return J;
}

/// Central difference of a scalar function.
template <class F>
double central_derivative(const F& f, double t, double h) {
  return (f(t + h) - f(t - h)) / (2.0 * h);
}

/// a (-) b = log(b^-1 a): the tangent at b that reaches a, for SO3 or SE3.
template <class Group>
auto right_minus(const Group& a, const Group& b) {
  return (b.inverse() * a).log();
}

}  // namespace rodlab::lie::testing
