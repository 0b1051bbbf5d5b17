#define BOOST_TEST_MODULE deadline_lu
#include <boost/test/unit_test.hpp>

// DeadlineLu (solvers/common/deadline_lu.hpp), the dense LU that polls the wall-time guard.
// Reference: Eigen::PartialPivLU of the same matrices. DeadlineLu runs Eigen's own blocked
// algorithm, so the factors, the permutation and the solutions must be equal bit for bit (sizes
// on both sides of Eigen's unblocked bound of 16 and of its block size rule, rows that need
// interchanges). And the guard: a deadline that has passed stops the factorisation before any
// work; one that passes during it stops it between blocks (the deadline is set to a third of the
// time the same factorisation took without one, so a check only at the start would not throw).

#include <chrono>
#include <random>
#include <thread>

#include <Eigen/Dense>

#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/common/deadline_lu.hpp"

namespace {

using rodlab::solvers::DeadlineLu;
using rodlab::solvers::DeadlineScope;
using rodlab::solvers::WallTimeExceeded;

Eigen::MatrixXd random_matrix(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(gen); });
  A.diagonal() *= 1e-3;  // small diagonal: most columns pivot
  return A;
}

}  // namespace

BOOST_AUTO_TEST_CASE(factors_and_solves_are_partial_pivlus_bit_for_bit) {
  for (const int n : {1, 2, 5, 16, 17, 40, 127, 144, 300, 701}) {
    const Eigen::MatrixXd A = random_matrix(n, 7u + n);
    const Eigen::PartialPivLU<Eigen::MatrixXd> reference(A);
    Eigen::MatrixXd factors = A;
    DeadlineLu lu;
    lu.compute(factors);
    BOOST_TEST((lu.matrixLU().array() == reference.matrixLU().array()).all(), "n = " << n);
    BOOST_TEST((lu.permutationP().indices().array() ==
                reference.permutationP().indices().array()).all(), "n = " << n);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
    Eigen::VectorXd x;
    lu.solve(b, x);
    const Eigen::VectorXd expected = reference.solve(b);
    BOOST_TEST((x.array() == expected.array()).all(), "n = " << n);
    BOOST_TEST((A * x - b).lpNorm<Eigen::Infinity>() <= 1e-9, "n = " << n);  // and it solves
  }
}

BOOST_AUTO_TEST_CASE(a_passed_deadline_stops_it_before_any_work) {
  Eigen::MatrixXd A = random_matrix(50, 3);
  const Eigen::MatrixXd before = A;
  const DeadlineScope scope(1e-9);
  std::this_thread::sleep_for(std::chrono::milliseconds(1));
  DeadlineLu lu;
  BOOST_CHECK_THROW(lu.compute(A), WallTimeExceeded);
  BOOST_TEST((A.array() == before.array()).all());
}

BOOST_AUTO_TEST_CASE(a_deadline_that_passes_during_it_stops_it_between_blocks) {
  const int n = 1500;  // 187 -> 176-column blocks: 9 checks
  const Eigen::MatrixXd A = random_matrix(n, 11);
  Eigen::MatrixXd factors = A;
  DeadlineLu lu;
  const auto start = std::chrono::steady_clock::now();
  lu.compute(factors);  // no deadline: runs to the end
  const double full =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  BOOST_TEST_MESSAGE("factorisation of " << n << " x " << n << ": " << full << " s");
  factors = A;
  const DeadlineScope scope(full / 3.0);
  BOOST_CHECK_THROW(lu.compute(factors), WallTimeExceeded);
}

// The solves read the matrix's storage, not the matrix object: a factorised matrix moved
// elsewhere (chebyshev's Collocation, with its Newton matrix, is moved into ChebyshevTracker and
// its factors reused) still solves, bit for bit as PartialPivLU, while the moved-from object is
// left empty.
BOOST_AUTO_TEST_CASE(solves_survive_a_move_of_the_factorised_matrix) {
  const Eigen::MatrixXd A = random_matrix(60, 5);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(60, 1.0, -3.0);
  const Eigen::VectorXd expected = A.partialPivLu().solve(b);
  Eigen::MatrixXd factors = A;
  DeadlineLu lu;
  lu.compute(factors);
  const Eigen::MatrixXd moved = std::move(factors);
  BOOST_TEST(factors.size() == 0);
  Eigen::VectorXd x;
  lu.solve(b, x);
  BOOST_TEST((x.array() == expected.array()).all());
  BOOST_TEST((lu.matrixLU().array() == moved.array()).all());
}
