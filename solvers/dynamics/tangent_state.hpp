#pragma once
// The tangent coordinates of a state on the staggered grid (stepper.hpp, docs/control.md "The
// state"), shared by the steppers that support control: the segment strains xi_j - xi*
// (j = 0..N-2; Kirchhoff rods: the angular part only, nu = nu* is held) followed by the node
// velocities eta_j (j = 1..N-1; the base is fixed). Private to solvers/dynamics.
#include <span>
#include <vector>

#include "rodlab/check.hpp"
#include "rodlab/lie/se3.hpp"
#include "rodlab/rod/rod_model.hpp"

namespace rodlab::solvers::dynamics {

class StaggeredTangent {
 public:
  /// xi* of each segment from the model (rest-strain spans: the span that holds it).
  StaggeredTangent(int nodes, const rod::RodModel& model)
      : nodes_(nodes), strain_dim_(model.is_kirchhoff() ? 3 : 6), xi_star_(nodes - 1) {
    const double ds = model.length() / (nodes - 1);
    for (int j = 0; j + 1 < nodes; ++j) xi_star_[j] = model.xi_star((j + 0.5) * ds);
  }

  int size() const { return (nodes_ - 1) * (strain_dim_ + 6); }

  /// x from the segment strains xi (N - 1) and node velocities eta (N).
  void read(std::span<const lie::Vector6> xi, std::span<const lie::Vector6> eta,
            std::span<double> x) const {
    check(x.size());
    std::size_t i = 0;
    for (int j = 0; j + 1 < nodes_; ++j)
      for (int c = 0; c < strain_dim_; ++c) x[i++] = xi[j][c] - xi_star_[j][c];
    for (int j = 1; j < nodes_; ++j)
      for (int c = 0; c < 6; ++c) x[i++] = eta[j][c];
  }

  /// A value per coordinate in this layout: `angular` and `linear` for the strains' angular and
  /// linear parts, `spin` and `velocity` for the velocities' (sizes for finite differences).
  void fill(double angular, double linear, double spin, double velocity,
            std::span<double> out) const {
    check(out.size());
    std::size_t i = 0;
    for (int j = 0; j + 1 < nodes_; ++j)
      for (int c = 0; c < strain_dim_; ++c) out[i++] = c < 3 ? angular : linear;
    for (int j = 1; j < nodes_; ++j)
      for (int c = 0; c < 6; ++c) out[i++] = c < 3 ? spin : velocity;
  }

  /// The index of tangent coordinate i in the full layout: six per segment strain (j = 0..N-2),
  /// then six per node velocity (j = 1..N-1).
  int full_index(int i) const {
    const int strains = (nodes_ - 1) * strain_dim_;
    return i < strains ? 6 * (i / strain_dim_) + i % strain_dim_ : 6 * (nodes_ - 1) + (i - strains);
  }

  /// T = d p_tip / dx (3 x size(); the velocities' columns are zero) of the poses
  /// g_(j+1) = g_j exp(ds xi_j): moving xi_j by d moves segment j's transform by
  /// exp(ds xi_j) exp(dexp_{-ds xi_j} ds d) (the right Jacobian), hence the tip by
  /// g_tip exp(Ad_{P_j^-1} dexp_{-ds xi_j} ds d), P_j = g_(j+1)^-1 g_tip, and its position by
  /// R_tip times that twist's linear part.
  void tip_jacobian(std::span<const SE3> g, std::span<const lie::Vector6> xi, double ds,
                    Eigen::MatrixXd& T) const {
    T.setZero(3, size());
    const SE3& tip = g.back();
    const lie::Matrix3 R = tip.rotation_matrix();
    for (int j = 0; j + 1 < nodes_; ++j) {
      const SE3 P = g[j + 1].inverse() * tip;
      const lie::Matrix6 J = P.inverse().Ad() * lie::se3::dexp(-ds * xi[j]) * ds;
      const Eigen::Matrix<double, 3, 6> dp = R * J.bottomRows<3>();
      T.middleCols(j * strain_dim_, strain_dim_) = dp.leftCols(strain_dim_);
    }
  }

  /// xi += dx's strain part, eta += its velocity part.
  void add(std::span<const double> dx, std::span<lie::Vector6> xi,
           std::span<lie::Vector6> eta) const {
    check(dx.size());
    std::size_t i = 0;
    for (int j = 0; j + 1 < nodes_; ++j)
      for (int c = 0; c < strain_dim_; ++c) xi[j][c] += dx[i++];
    for (int j = 1; j < nodes_; ++j)
      for (int c = 0; c < 6; ++c) eta[j][c] += dx[i++];
  }

 private:
  void check(std::size_t got) const {
    RODLAB_THROW_UNLESS(static_cast<int>(got) == size(),
                        "tangent coordinates: expected {} values, got {}", size(), got);
  }

  int nodes_;
  int strain_dim_;
  std::vector<lie::Vector6> xi_star_;  ///< per segment
};

}  // namespace rodlab::solvers::dynamics
