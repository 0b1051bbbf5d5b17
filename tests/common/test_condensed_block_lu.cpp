#define BOOST_TEST_MODULE condensed_block_lu
#include <boost/test/unit_test.hpp>

// The condensed block LU (solvers/common/condensed_block_lu.hpp) and the KINSOL linear solver
// built on it (NewtonLinearSolver::condensed_rod_blocks, condensed_block_solver.cpp), against a
// dense LU with partial pivoting (Eigen::PartialPivLU) of the same matrix: block-tridiagonal
// matrices whose first L rows of each block involve that block's unknowns alone, at several
// (L, C), with coupling of the strength of the rod's Newton matrix and stronger; the refusals
// (a local row reaching another block, a singular pivot block, a pattern outside the band); and
// KINSOL solving a linear system through it, including the KLU fallback.

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "../../solvers/common/condensed_block_lu.hpp"
#include "rodlab/solvers/common/kinsol_solver.hpp"

namespace {

using rodlab::solvers::CondensedBlockLU;
using Dense = Eigen::MatrixXd;
using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor>;

/// A random matrix of `blocks` blocks of L + C unknowns: local rows see their own block only
/// (a diagonal `shift` on the local part), coupled rows the neighbours with weight `coupling`
/// (diagonal `shift` too).
Dense random_matrix(int L, int C, int blocks, double shift, double coupling, unsigned seed) {
  const int B = L + C, n = B * blocks;
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Dense A = Dense::Zero(n, n);
  for (int k = 0; k < blocks; ++k)
    for (int r = 0; r < B; ++r) {
      const int row = B * k + r;
      for (int j = std::max(0, k - 1); j <= std::min(blocks - 1, k + 1); ++j) {
        if (r < L && j != k) continue;
        for (int c = 0; c < B; ++c) A(row, B * j + c) = (j == k ? 1.0 : coupling) * u(gen);
      }
      A(row, row) += shift;
    }
  return A;
}

/// The full band of blocks and, after them, a border of `tail` whole rows and columns, as a CSC
/// pattern (structurally wider than the values, like the rod's).
Sparse band_pattern(const Dense& A, int B, int tail = 0) {
  const int n = static_cast<int>(A.rows()), banded = n - tail;
  std::vector<Eigen::Triplet<double>> t;
  for (int col = 0; col < n; ++col)
    for (int row = 0; row < n; ++row)
      if (row >= banded || col >= banded || std::abs(row / B - col / B) <= 1)
        t.emplace_back(row, col, A(row, col));
  Sparse S(n, n);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

/// The normwise backward error |A x - b| / (|A| |x| + |b|) of the condensed solve (Frobenius
/// norms) of A, blocks and a border of `tail` rows; *factored says whether factor() accepted A.
/// A backward-stable solve gives a few eps.
template <int L, int C>
double backward_error(const Dense& A, bool* factored, int tail = 0) {
  constexpr int B = L + C;
  Sparse S = band_pattern(A, B, tail);
  CondensedBlockLU<L, C> lu((static_cast<int>(A.rows()) - tail) / B, tail);
  BOOST_REQUIRE(lu.map_pattern(S.outerIndexPtr(), S.innerIndexPtr()));
  *factored = lu.factor(S.valuePtr());
  if (!*factored) return 0.0;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  Eigen::VectorXd x = b;
  lu.solve(x.data());
  return (A * x - b).norm() / (A.norm() * x.norm() + b.norm());
}

}  // namespace

BOOST_AUTO_TEST_CASE(solves_like_a_dense_lu) {
  // Normwise backward errors. Measured: 1.2e-17 .. 1.4e-14, the largest where the diagonal is
  // weakest (shift 0.5, coupling 1: no pivoting across blocks lets the Schur blocks grow); Eigen's
  // dense partial-pivoting LU of the same (7, 6) matrices 1.4e-17 .. 2.9e-17.
  struct Case {
    double shift, coupling;
  };
  for (const Case c : {Case{4.0, 0.3}, Case{2.0, 1.0}, Case{0.5, 1.0}}) {
    for (unsigned seed = 1; seed <= 3; ++seed) {
      bool factored = false;
      const double s = c.shift, w = c.coupling;
      const double e1 = backward_error<1, 1>(random_matrix(1, 1, 9, s, w, seed), &factored);
      BOOST_TEST(factored);
      const double e2 = backward_error<2, 3>(random_matrix(2, 3, 7, s, w, seed), &factored);
      BOOST_TEST(factored);
      const double e3 = backward_error<7, 6>(random_matrix(7, 6, 12, s, w, seed), &factored);
      BOOST_TEST(factored);
      const Dense A = random_matrix(7, 6, 12, s, w, seed);
      const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
      const Eigen::VectorXd x = A.partialPivLu().solve(b);
      const double dense = (A * x - b).norm() / (A.norm() * x.norm() + b.norm());
      BOOST_TEST_MESSAGE("shift " << c.shift << ", coupling " << c.coupling << ", seed " << seed
                                  << ": " << e1 << ", " << e2 << ", " << e3 << " (dense LU "
                                  << dense << ")");
      BOOST_TEST(e1 <= 1e-13);
      BOOST_TEST(e2 <= 1e-13);
      BOOST_TEST(e3 <= 1e-13);
    }
  }
  // One block: the condensation alone.
  bool factored = false;
  const double single = backward_error<7, 6>(random_matrix(7, 6, 1, 3.0, 1.0, 5), &factored);
  BOOST_TEST(single <= 1e-15);
  BOOST_TEST(factored);
}

BOOST_AUTO_TEST_CASE(solves_a_bordered_matrix_like_a_dense_lu) {
  // `tail` rows after the blocks that see every column up to their own (ida's ledger rows:
  // dense in the nodes, lower triangular among themselves), their columns in no block row.
  // Measured: backward errors 1.8e-17 .. 3.3e-17.
  for (const int tail : {1, 2, 3}) {
    Dense A = random_matrix(7, 6, 6, 4.0, 0.3, 17 + tail);
    const int n = static_cast<int>(A.rows());
    Dense bordered = Dense::Zero(n + tail, n + tail);
    bordered.topLeftCorner(n, n) = A;
    std::mt19937 gen(5);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (int r = 0; r < tail; ++r) {
      for (int col = 0; col < n + r; ++col) bordered(n + r, col) = u(gen);
      bordered(n + r, n + r) = 2.0 + u(gen);
    }
    bool factored = false;
    const double error = backward_error<7, 6>(bordered, &factored, tail);
    BOOST_REQUIRE(factored);
    BOOST_TEST_MESSAGE("tail " << tail << ": backward error " << error);
    BOOST_TEST(error <= 1e-15);
    // A block row that sees a tail column, or a tail row above its diagonal: refused.
    const Sparse S = band_pattern(bordered, 13, tail);
    for (const auto& [row, col] : {std::pair{3, n}, std::pair{n, n + tail - 1}}) {
      if (row == n && tail == 1) continue;
      Sparse wrong = S;
      wrong.coeffRef(row, col) = 0.5;
      CondensedBlockLU<7, 6> refused(6, tail);
      BOOST_REQUIRE(refused.map_pattern(wrong.outerIndexPtr(), wrong.innerIndexPtr()));
      BOOST_TEST(!refused.factor(wrong.valuePtr()), "row " << row << ", column " << col);
    }
  }
}

BOOST_AUTO_TEST_CASE(refuses_what_it_cannot_solve) {
  // A local row reaching another block: the condensation would be wrong, so factor() refuses.
  Dense A = random_matrix(2, 3, 4, 4.0, 0.3, 7);
  bool factored = true;
  Dense reaching = A;
  reaching(5 + 1, 5 * 2 + 3) = 0.25;  // block 1's second local row sees block 2
  backward_error<2, 3>(reaching, &factored);
  BOOST_TEST(!factored);
  // A singular local block (its first local row zero within the block).
  Dense singular_local = A;
  singular_local.row(5).setZero();
  backward_error<2, 3>(singular_local, &factored);
  BOOST_TEST(!factored);
  // A singular Schur pivot block: the coupled rows of block 0 copies of each other.
  Dense singular_pivot = A;
  singular_pivot.row(3) = singular_pivot.row(2);
  singular_pivot.row(4) = singular_pivot.row(2);
  backward_error<2, 3>(singular_pivot, &factored);
  BOOST_TEST(!factored);
  // Not a number.
  Dense nan = A;
  nan(7, 7) = std::nan("");
  backward_error<2, 3>(nan, &factored);
  BOOST_TEST(!factored);
  // A pattern entry outside the tridiagonal band of blocks.
  Sparse S = band_pattern(A, 5);
  S.coeffRef(0, 15) = 1.0;  // block 0 row, block 3 column
  S.makeCompressed();
  CondensedBlockLU<2, 3> lu(4);
  BOOST_TEST(!lu.map_pattern(S.outerIndexPtr(), S.innerIndexPtr()));
}

BOOST_AUTO_TEST_CASE(kinsol_solves_through_it_and_falls_back_to_klu) {
  // F(x) = A x - b with A of the rod's block shape (13 = 7 + 6, 5 blocks): KINSOL's Newton step
  // is exact, so one iteration solves it to the linear solver's rounding. Then the same with a
  // local row reaching the next block: the condensed solver refuses the matrix and KLU solves it.
  using rodlab::solvers::KinsolSolver;
  using rodlab::solvers::KluReuse;
  using rodlab::solvers::KluOrder;
  using rodlab::solvers::NewtonLinearSolver;
  for (const bool reaching : {false, true}) {
    Dense A = random_matrix(7, 6, 5, 4.0, 0.5, 11);
    if (reaching) A(13 + 2, 26 + 8) = 0.5;
    const Sparse pattern = band_pattern(A, 13);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), 1.0, -1.0);
    KinsolSolver solver(pattern, KluReuse::factors, KluOrder::fill_reducing,
                        NewtonLinearSolver::condensed_rod_blocks);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(A.rows());
    rodlab::solvers::KinsolOptions o;
    o.fnormtol = 1e-12;
    o.line_search = false;
    const auto stats = solver.solve(
        x, [&](const auto& u, auto F) { F = A * u - b; },
        [&](const auto&, const auto&, Sparse& J) {
          for (int col = 0; col < J.outerSize(); ++col)
            for (Sparse::InnerIterator it(J, col); it; ++it) it.valueRef() = A(it.row(), col);
        },
        o);
    const double error = (x - A.partialPivLu().solve(b)).norm();
    BOOST_TEST_MESSAGE((reaching ? "KLU fallback" : "condensed")
                       << ": " << stats.nonlinear_iterations << " iteration(s), error " << error);
    BOOST_TEST(stats.converged);
    BOOST_TEST(stats.nonlinear_iterations <= 2);  // exact Newton steps (a wrong solve iterates)
    BOOST_TEST(error <= 1e-12);
  }
  // A pattern outside the band, or no kept KLU to fall back on: refused at construction.
  Dense A = random_matrix(7, 6, 3, 4.0, 0.5, 3);
  Sparse wide = band_pattern(A, 13);
  wide.coeffRef(0, 38) = 1.0;
  BOOST_CHECK_THROW(KinsolSolver(wide, KluReuse::factors, KluOrder::fill_reducing,
                                 NewtonLinearSolver::condensed_rod_blocks),
                    std::invalid_argument);
  BOOST_CHECK_THROW(KinsolSolver(band_pattern(A, 13), KluReuse::none, KluOrder::fill_reducing,
                                 NewtonLinearSolver::condensed_rod_blocks),
                    std::invalid_argument);
}
