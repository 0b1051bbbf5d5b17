// A tendon path's unit wrench c(xi) = [r x t; t] and its Jacobian (lib/include/rodlab/loads/
// tendon.hpp): the closed-form dc/dxi (unit_wrench_jacobian, add_wrench) against central
// differences of c, on a constant offset and on a routed one (r' != 0), and add_wrench's
// accumulation F c, F dc/dxi.
#define BOOST_TEST_MODULE rod_tendon_path
#include <boost/test/unit_test.hpp>

#include "rodlab/loads/tendon.hpp"

using rodlab::loads::TendonPath;
using Matrix6 = Eigen::Matrix<double, 6, 6>;
using rodlab::lie::Vector6;

namespace {

/// Central differences of c at xi (step 1e-6: error ~1e-12 of c's curvature scale).
Matrix6 differenced(const TendonPath& p, double s, const Vector6& xi) {
  Matrix6 J;
  for (int k = 0; k < 6; ++k) {
    Vector6 up = xi, down = xi;
    up[k] += 1e-6;
    down[k] -= 1e-6;
    J.col(k) = (p.unit_wrench(s, up) - p.unit_wrench(s, down)) / 2e-6;
  }
  return J;
}

}  // namespace

// A bent, twisted, sheared and stretched strain, on a cable at 4 mm and on one routed from
// (4, 0) mm to (0, 3) mm over the rod: the Jacobian agrees with differences to 1e-8 of its size.
BOOST_AUTO_TEST_CASE(jacobian_matches_differences) {
  Vector6 xi;
  xi << 3.0, -5.0, 1.5, 0.02, -0.01, 1.03;  // [omega; nu], 1/m
  const TendonPath straight({{0.0, Eigen::Vector2d(0.004, 0.0)}}, 0.0, 0.1);
  const TendonPath routed({{0.0, Eigen::Vector2d(0.004, 0.0)}, {0.1, Eigen::Vector2d(0.0, 0.003)}},
                          0.0, 0.1);
  for (const TendonPath* p : {&straight, &routed}) {
    const Matrix6 J = p->unit_wrench_jacobian(0.05, xi);
    const Matrix6 D = differenced(*p, 0.05, xi);
    BOOST_TEST((J - D).norm() < 1e-8 * D.norm());
    // add_wrench accumulates F c and F dc/dxi onto what is there
    Vector6 w = Vector6::Ones();
    Matrix6 A = Matrix6::Identity();
    p->add_wrench(0.05, xi, 0.3, w, A);
    BOOST_TEST((w - Vector6::Ones() - 0.3 * p->unit_wrench(0.05, xi)).norm() < 1e-15);
    BOOST_TEST((A - Matrix6::Identity() - 0.3 * J).norm() < 1e-14 * J.norm());
  }
}
