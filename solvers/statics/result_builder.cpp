#include "rodlab/solvers/statics/result_builder.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rodlab/check.hpp"

namespace rodlab::solvers::statics {

void fill_static_result(const StaticProblem& problem, std::span<const double> s,
                        std::span<const SE3> g, std::span<const Vector6> Lambda,
                        result::StaticResult& out) {
  out.nodes = static_cast<int>(s.size());
  out.centerline.resize(s.size());
  out.max_det_deviation = 0.0;
  out.max_orthogonality_error = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    // The strain at a node uses the actuators active just after it (just before, at the tip).
    const double probe = i + 1 < s.size() ? 0.5 * (s[i] + s[i + 1]) : s[i] - 1e-12 * problem.length();
    const auto mask = problem.has_actuators() ? problem.active_mask(probe) : 0U;
    const double side = i + 1 < s.size() ? s[i] : s[i] - 1e-12 * problem.length();  // xi*(s)
    out.centerline[i] = {s[i], g[i], problem.strain(Lambda[i], mask ? s[i] : side, mask)};
    const lie::Matrix3 R = g[i].rotation_matrix();
    out.max_det_deviation = std::max(out.max_det_deviation, std::abs(R.determinant() - 1.0));
    out.max_orthogonality_error =
        std::max(out.max_orthogonality_error, (R.transpose() * R - lie::Matrix3::Identity()).norm());
  }
  // lambda(0) of the rod itself (the actuators' share removed): for a Cosserat rod
  // K (xi(0) - xi*); for a Kirchhoff rod its force part is the constraint force keeping nu = nu*.
  if (Lambda.empty()) {
    out.base_wrench = Vector6::Zero();
  } else {
    const double probe = s.size() > 1 ? 0.5 * (s[0] + s[1]) : 0.0;
    const auto mask = problem.has_actuators() ? problem.active_mask(probe) : 0U;
    out.base_wrench = problem.rod_wrench(Lambda.front(), out.centerline.front().twist, s[0], mask);
  }
}

void check_cables_taut(const StaticProblem& problem, result::StaticResult& out) {
  for (std::size_t k = 0; k < problem.actuators().size(); ++k) {
    const auto& a = problem.actuators()[k];
    if (a.kind != ActuatorKind::cable || !a.target_length) continue;
    const double T = problem.axial_force(static_cast<int>(k));
    if (T < 0.0 && out.converged) {
      out.converged = false;
      out.reason = rodlab::format(
          "cable {} would need a compressive force ({:g} N) to reach its displacement: it goes "
          "slack",
          k, T);
    }
  }
}

}  // namespace rodlab::solvers::statics
