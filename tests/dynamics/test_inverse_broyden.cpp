#define BOOST_TEST_MODULE inverse_broyden
#include <boost/test/unit_test.hpp>

// Multiple shooting's Newton model (solvers/dynamics/shooting/inverse_broyden.hpp): KLU's factors
// of a sparse Jacobian and Broyden's updates of the inverse in product form. Reference: the dense
// inverse H updated by Sherman-Morrison, H += (s - H y) s^T H / (s^T H y) (the model multiple
// shooting used before, the same iterates in exact arithmetic), on a block-bidiagonal system of
// multiple shooting's shape with a nonlinearity; the secant condition H y = s after every update;
// a copy's steps against the original's; the request for a fresh Jacobian after kMaxUpdates; and
// a singular or non-finite Jacobian refused.

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "../../solvers/dynamics/shooting/inverse_broyden.hpp"

namespace {

using rodlab::solvers::dynamics::InverseBroyden;
using Vector = Eigen::VectorXd;

constexpr int kJoin = 18;

/// Multiple shooting's Jacobian shape for M intervals, in its staircase row order: the jump at
/// start i (rows 18 (i - 1)) on the unknowns of intervals i - 1 and i, the tip's 6 rows on the
/// last interval's; random entries with a dominant -1 on each start's own jump (the jump is
/// end - start) and a near identity on the previous interval's end (well conditioned at every
/// M, as multiple shooting's joins are).
InverseBroyden::Jacobian shooting_matrix(int M, std::mt19937& rng) {
  std::uniform_real_distribution<double> entry(-0.5, 0.5);
  auto start_at = [](int i) { return i == 0 ? 0 : 6 + kJoin * (i - 1); };
  auto count = [](int i) { return i == 0 ? 6 : kJoin; };
  const int n = 6 + kJoin * (M - 1);
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < M; ++i) {
    for (int k = start_at(i); k < start_at(i) + count(i); ++k) {
      if (i >= 1)
        for (int r = 0; r < kJoin; ++r)
          t.emplace_back(kJoin * (i - 1) + r, k, r == k - start_at(i) ? -1.0 : 0.1 * entry(rng));
      const int end = i + 1 < M ? kJoin * i : kJoin * (M - 1);
      for (int r = 0; r < (i + 1 < M ? kJoin : 6); ++r)
        t.emplace_back(end + r, k, (r == k - start_at(i) ? 1.0 : 0.0) + 0.1 * entry(rng));
    }
  }
  InverseBroyden::Jacobian J(n, n);
  J.setFromTriplets(t.begin(), t.end());
  J.makeCompressed();
  return J;
}

/// F(x) = z + 0.3 sin(z) - b with z = A x: a nonlinear system with A's pattern, its Jacobian
/// diag(1 + 0.3 cos z) A.
struct System {
  InverseBroyden::Jacobian A;
  Vector b;
  Vector operator()(const Vector& x) const {
    const Vector z = A * x;
    return z + 0.3 * z.array().sin().matrix() - b;
  }
  Eigen::MatrixXd jacobian(const Vector& x) const {
    const Vector z = A * x;
    return (1.0 + 0.3 * z.array().cos()).matrix().asDiagonal() * Eigen::MatrixXd(A);
  }
};

System make_system(int M, unsigned seed) {
  std::mt19937 rng(seed);
  System f{shooting_matrix(M, rng), Vector()};
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  f.b = Vector::NullaryExpr(f.A.rows(), [&] { return entry(rng); });
  return f;
}

/// Loads the dense Jacobian of f at x into the model's sparse pattern (f.A's).
bool load(InverseBroyden& model, const System& f, const Vector& x) {
  const Eigen::MatrixXd J = f.jacobian(x);
  model.jacobian() = f.A;
  for (int k = 0; k < J.cols(); ++k)
    for (InverseBroyden::Jacobian::InnerIterator it(model.jacobian(), k); it; ++it)
      it.valueRef() = J(it.row(), k);
  return model.refresh();
}

}  // namespace

BOOST_AUTO_TEST_CASE(iterates_match_the_dense_inverse_update) {
  // M = 2, 5: the dense form (n = 24, 78); 7, 12, 32: the sparse form (n = 114, 204, 564)
  for (const int M : {2, 5, 7, 12, 32}) {
    const System f = make_system(M, 17u + M);
    const int n = static_cast<int>(f.A.rows());
    Vector x = Vector::Zero(n), x_dense = x;
    InverseBroyden model;
    BOOST_REQUIRE(load(model, f, x));
    Eigen::MatrixXd H = f.jacobian(x).inverse();
    Vector r = f(x), r_dense = r;
    double worst = 0.0, first = 1.0;
    for (int k = 0; k < 20 && r.lpNorm<Eigen::Infinity>() > 1e-13; ++k) {
      const Vector s = model.step(r);
      const Vector s_dense = -H * r_dense;
      // the steps' gap against the first step (late steps are within rounding of r)
      if (k == 0) first = s_dense.lpNorm<Eigen::Infinity>();
      worst = std::max(worst, (s - s_dense).lpNorm<Eigen::Infinity>() / first);
      x += s;
      x_dense += s_dense;
      const Vector r_new = f(x), r_new_dense = f(x_dense);
      model.update(s, r, r_new);
      const Vector Hy = H * (r_new_dense - r_dense);
      H += (s_dense - Hy) * (s_dense.transpose() * H) / s_dense.dot(Hy);
      r = r_new;
      r_dense = r_new_dense;
    }
    BOOST_TEST_MESSAGE("M = " << M << ": worst relative step gap " << worst << ", residual "
                              << r.lpNorm<Eigen::Infinity>());
    // Broyden converges superlinearly on this system (|r| 1 -> 1e-13 in 9 steps); the sparse
    // form's steps agree with the dense inverse's to rounding (measured up to 2.4e-15 of the
    // first step at M = 32; 0 where both are dense)
    BOOST_TEST(worst < 1e-13);
    BOOST_TEST(r.lpNorm<Eigen::Infinity>() <= 1e-13);
  }
}

BOOST_AUTO_TEST_CASE(each_update_meets_the_secant_condition) {
  const System f = make_system(8, 5u);  // the sparse form
  const int n = static_cast<int>(f.A.rows());
  Vector x = Vector::Zero(n);
  InverseBroyden model;
  BOOST_REQUIRE(load(model, f, x));
  Vector r = f(x);
  for (int k = 0; k < 6; ++k) {
    const Vector s = 0.5 * model.step(r);  // a halved step, as after backtracking
    const Vector r_new = f(x + s);
    model.update(s, r, r_new);
    // H_(k+1) y = s: the updated step from r_new minus the one from r is -(H y) = -s ...
    InverseBroyden probe = model;  // (a copy: refactorised, the same H)
    const Vector Hy = probe.step(r) - probe.step(r_new);
    BOOST_TEST((Hy - s).lpNorm<Eigen::Infinity>() <= 1e-11 * s.lpNorm<Eigen::Infinity>());
    x += s;
    r = r_new;
  }
}

BOOST_AUTO_TEST_CASE(a_copy_steps_as_the_original) {
  const System f = make_system(8, 9u);  // the sparse form (the dense form is plain data)
  Vector x = Vector::Zero(f.A.rows());
  InverseBroyden model;
  BOOST_REQUIRE(load(model, f, x));
  Vector r = f(x);
  for (int k = 0; k < 3; ++k) {
    const Vector s = model.step(r);
    x += s;
    const Vector r_new = f(x);
    model.update(s, r, r_new);
    r = r_new;
  }
  InverseBroyden copy(model), assigned;
  assigned = model;
  const Vector probe = Vector::LinSpaced(f.A.rows(), -1.0, 1.0);
  const Vector s = model.step(probe);
  BOOST_TEST((copy.step(probe) - s).lpNorm<Eigen::Infinity>() == 0.0);
  BOOST_TEST((assigned.step(probe) - s).lpNorm<Eigen::Infinity>() == 0.0);
}

BOOST_AUTO_TEST_CASE(asks_for_a_fresh_jacobian_when_full) {
  const System f = make_system(8, 3u);  // the sparse form (the dense one is never full)
  Vector x = Vector::Zero(f.A.rows());
  InverseBroyden model;
  BOOST_REQUIRE(load(model, f, x));
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> entry(-1.0, 1.0);
  int taken = 0;
  for (; taken < InverseBroyden::kMaxUpdates; ++taken) {
    const Vector s = 1e-3 * Vector::NullaryExpr(x.size(), [&] { return entry(rng); });
    const Vector r = f(x), r_new = f(x + s);
    x += s;
    if (!model.update(s, r, r_new)) break;
  }
  BOOST_TEST(taken == InverseBroyden::kMaxUpdates - 1);  // the kMaxUpdates-th update says full
  // the dense form takes every update
  const System small = make_system(2, 3u);
  Vector y = Vector::Zero(small.A.rows());
  InverseBroyden dense;
  BOOST_REQUIRE(load(dense, small, y));
  int kept = 0;
  for (int k = 0; k < 2 * InverseBroyden::kMaxUpdates; ++k) {
    const Vector s = 1e-3 * Vector::NullaryExpr(y.size(), [&] { return entry(rng); });
    kept += dense.update(s, small(y), small(y + s));
    y += s;
  }
  BOOST_TEST(kept == 2 * InverseBroyden::kMaxUpdates);
  BOOST_REQUIRE(load(model, f, x));  // a fresh Jacobian takes updates again
  const Vector r = f(x), s = model.step(r);
  BOOST_TEST(model.update(s, r, f(x + s)));
}

BOOST_AUTO_TEST_CASE(refuses_a_singular_or_non_finite_jacobian) {
  for (const int M : {2, 8}) {  // the dense and the sparse form
  const System f = make_system(M, 4u);
  InverseBroyden model;
  model.jacobian() = f.A;
  // a column of zeros: singular
  for (InverseBroyden::Jacobian::InnerIterator it(model.jacobian(), 7); it; ++it)
    it.valueRef() = 0.0;
  BOOST_TEST(!model.refresh());
  model.jacobian() = f.A;
  model.jacobian().valuePtr()[3] = std::nan("");
  BOOST_TEST(!model.refresh());
  model.jacobian() = f.A;
  BOOST_TEST(model.refresh());
  }
}
