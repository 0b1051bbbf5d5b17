#include "rodlab/solvers/statics/result_builder.hpp"

#include <algorithm>
#include <cmath>

namespace rodlab::solvers::statics {

void fill_static_result(const StaticProblem& problem, std::span<const double> s,
                        std::span<const SE3> g, std::span<const Vector6> Lambda,
                        result::StaticResult& out) {
  out.nodes = static_cast<int>(s.size());
  out.centerline.resize(s.size());
  out.max_det_deviation = 0.0;
  out.max_orthogonality_error = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    out.centerline[i] = {s[i], g[i], problem.strain(Lambda[i])};
    const lie::Matrix3 R = g[i].rotation_matrix();
    out.max_det_deviation = std::max(out.max_det_deviation, std::abs(R.determinant() - 1.0));
    out.max_orthogonality_error =
        std::max(out.max_orthogonality_error, (R.transpose() * R - lie::Matrix3::Identity()).norm());
  }
  // lambda(0): for a Cosserat rod K (xi(0) - xi*); for a Kirchhoff rod its force part is the
  // constraint force that keeps nu = nu*.
  out.base_wrench = Lambda.empty() ? Vector6::Zero() : Vector6(Lambda.front());
}

}  // namespace rodlab::solvers::statics
