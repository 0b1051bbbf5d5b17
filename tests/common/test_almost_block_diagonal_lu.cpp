#define BOOST_TEST_MODULE almost_block_diagonal_lu
#include <boost/test/unit_test.hpp>

// The almost block diagonal LU (solvers/common/almost_block_diagonal_lu.hpp) and the KINSOL
// linear solver built on it (NewtonLinearSolver::almost_block_diagonal), against Eigen's dense
// LU with partial pivoting (Eigen::PartialPivLU) of the same matrix: random staircase matrices
// (T rows on the first block, B rows on each pair of neighbouring blocks, B - T on the last) at
// several (B, T) and block counts, with the pivots in place and with zero diagonals that force
// interchanges; the pivots themselves, which must be dense partial pivoting's; a pattern with
// holes in the staircase; a border of dense rows and columns (kinsol's extra unknowns); the
// refusals (an entry outside the staircase, a singular matrix, a bordered matrix whose blocks are
// singular); and KINSOL solving linear systems through it, with the KLU fallback.

#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "../../solvers/common/almost_block_diagonal_lu.hpp"
#include "rodlab/solvers/common/kinsol_solver.hpp"

namespace {

using rodlab::solvers::AlmostBlockDiagonalLU;
using Dense = Eigen::MatrixXd;
using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor>;

/// The block columns row r of a staircase matrix with `blocks` blocks of B and T top rows may
/// have entries in: [first, last].
std::pair<int, int> row_blocks(int B, int T, int blocks, int r) {
  if (r < T) return {0, 0};
  const int interval = (r - T) / B;
  if (interval >= blocks - 1) return {blocks - 1, blocks - 1};
  return {interval, interval + 1};
}

/// A random staircase matrix, its entries uniform in [-1, 1]; `zero_diagonal` zeroes A(i, i),
/// so that no pivot can stay in place.
Dense random_staircase(int B, int T, int blocks, unsigned seed, bool zero_diagonal = false) {
  const int n = B * blocks;
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Dense A = Dense::Zero(n, n);
  for (int r = 0; r < n; ++r) {
    const auto [first, last] = row_blocks(B, T, blocks, r);
    for (int c = B * first; c < B * (last + 1); ++c) A(r, c) = u(gen);
    if (zero_diagonal) A(r, r) = 0.0;
  }
  return A;
}

/// The staircase as a CSC pattern with A's values; `holes` leaves out the structural zeros of A
/// (a pattern narrower than the staircase), otherwise every staircase position is in it.
Sparse staircase_pattern(const Dense& A, int B, int T, bool holes = false) {
  const int n = static_cast<int>(A.rows()), blocks = n / B;
  std::vector<Eigen::Triplet<double>> t;
  for (int r = 0; r < n; ++r) {
    const auto [first, last] = row_blocks(B, T, blocks, r);
    for (int c = B * first; c < B * (last + 1); ++c)
      if (!holes || A(r, c) != 0.0) t.emplace_back(r, c, A(r, c));
  }
  Sparse S(n, n);
  S.setFromTriplets(t.begin(), t.end());
  S.makeCompressed();
  return S;
}

/// [A E; F G]: A a random staircase, the border of m dense rows and columns.
Dense bordered(const Dense& A, int m, unsigned seed) {
  const int n = static_cast<int>(A.rows());
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Dense M = Dense::NullaryExpr(n + m, n + m, [&](Eigen::Index, Eigen::Index) { return u(gen); });
  M.topLeftCorner(n, n) = A;
  return M;
}

/// The staircase of M's first n_blocks unknowns, and its border rows and columns whole.
Sparse bordered_pattern(const Dense& M, int B, int T, int m) {
  const int n = static_cast<int>(M.rows()) - m;
  Sparse S = staircase_pattern(M.topLeftCorner(n, n), B, T);
  std::vector<Eigen::Triplet<double>> t;
  for (int c = 0; c < n; ++c)
    for (Sparse::InnerIterator it(S, c); it; ++it) t.emplace_back(it.row(), c, it.value());
  for (int r = 0; r < n + m; ++r)
    for (int c = 0; c < n + m; ++c)
      if (r >= n || c >= n) t.emplace_back(r, c, M(r, c));
  Sparse P(n + m, n + m);
  P.setFromTriplets(t.begin(), t.end());
  P.makeCompressed();
  return P;
}

/// Factorises A through its staircase pattern and returns the normwise backward error
/// |A x - b| / (|A| |x| + |b|) of the solve (Frobenius norms), and the largest relative
/// difference of the pivots from those of Eigen's dense partial-pivoting LU in *pivots.
template <int B, int T>
double backward_error(const Dense& A, double* pivots, bool holes = false) {
  const Sparse S = staircase_pattern(A, B, T, holes);
  AlmostBlockDiagonalLU<B, T> lu(static_cast<int>(A.rows()) / B);
  BOOST_REQUIRE(lu.accept_pattern(S.outerIndexPtr(), S.innerIndexPtr()));
  BOOST_REQUIRE(lu.factor(S.outerIndexPtr(), S.innerIndexPtr(), S.valuePtr()));
  const Eigen::PartialPivLU<Dense> dense(A);
  *pivots = 0.0;
  for (int i = 0; i < A.rows(); ++i) {
    const double d = dense.matrixLU()(i, i);
    *pivots = std::max(*pivots, std::abs(lu.pivot(i) - d) / std::abs(d));
  }
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(A.rows(), -1.0, 2.0);
  Eigen::VectorXd x = b;
  lu.solve(x.data());
  return (A * x - b).norm() / (A.norm() * x.norm() + b.norm());
}

}  // namespace

BOOST_AUTO_TEST_CASE(solves_like_a_dense_lu_with_its_pivots) {
  // Dense partial pivoting chooses among the same rows, so the pivots agree with Eigen's to
  // rounding (measured at most 6.6e-14 relative) and the backward errors are a few eps (measured:
  // see the log; Eigen's dense LU gives the same order).
  for (const bool zero_diagonal : {false, true})
    for (unsigned seed = 1; seed <= 3; ++seed)
      for (const int blocks : {1, 2, 9}) {
        double p1 = 0.0, p2 = 0.0, p3 = 0.0;
        const double e1 =
            backward_error<2, 1>(random_staircase(2, 1, blocks, seed, zero_diagonal), &p1);
        const double e2 =
            backward_error<5, 3>(random_staircase(5, 3, blocks, seed, zero_diagonal), &p2);
        const double e3 =
            backward_error<13, 7>(random_staircase(13, 7, blocks, seed, zero_diagonal), &p3);
        BOOST_TEST_MESSAGE("zero diagonal " << zero_diagonal << ", seed " << seed << ", "
                                            << blocks << " blocks: backward errors " << e1
                                            << ", " << e2 << ", " << e3 << "; pivots " << p1
                                            << ", " << p2 << ", " << p3);
        BOOST_TEST(e1 <= 1e-15);
        BOOST_TEST(e2 <= 1e-15);
        BOOST_TEST(e3 <= 1e-15);
        BOOST_TEST(std::max({p1, p2, p3}) <= 1e-10);
      }
}

BOOST_AUTO_TEST_CASE(a_pattern_with_holes_and_a_second_factorisation) {
  // A pattern narrower than the staircase: the panels' positions outside it must read as
  // zeros, also after a factorisation of other values has filled them.
  Dense A = random_staircase(13, 7, 6, 21);
  for (int r = 0; r < A.rows(); r += 3) A(r, (r * 7) % A.cols()) = 0.0;  // some holes
  const Sparse S = staircase_pattern(A, 13, 7, true);
  AlmostBlockDiagonalLU<13, 7> lu(6);
  BOOST_REQUIRE(lu.accept_pattern(S.outerIndexPtr(), S.innerIndexPtr()));
  for (const double scale : {1.0, -3.0}) {
    const Dense As = scale * A;
    const Sparse Ss = scale * S;
    BOOST_REQUIRE(lu.factor(Ss.outerIndexPtr(), Ss.innerIndexPtr(), Ss.valuePtr()));
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(As.rows(), 2.0, -1.0);
    Eigen::VectorXd x = b;
    lu.solve(x.data());
    const double error = (As * x - b).norm() / (As.norm() * x.norm() + b.norm());
    BOOST_TEST_MESSAGE("scale " << scale << ": backward error " << error);
    BOOST_TEST(error <= 1e-15);
  }
}

BOOST_AUTO_TEST_CASE(a_bordered_matrix_like_a_dense_lu) {
  // kinsol's extra unknowns: m dense rows and columns after the blocks, eliminated by block LU
  // on A's factors. Backward errors (measured 3.6e-17 .. 3.7e-16; Eigen's dense LU of the same
  // matrices 3.0e-17 .. 5.8e-17).
  for (const int m : {1, 2, 5})
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const Dense M = bordered(random_staircase(13, 7, 7, seed, true), m, 40 + seed);
      const Sparse S = bordered_pattern(M, 13, 7, m);
      AlmostBlockDiagonalLU<13, 7> lu(7, m);
      BOOST_REQUIRE(lu.accept_pattern(S.outerIndexPtr(), S.innerIndexPtr()));
      BOOST_REQUIRE(lu.factor(S.outerIndexPtr(), S.innerIndexPtr(), S.valuePtr()));
      const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(M.rows(), -1.0, 2.0);
      Eigen::VectorXd x = b;
      lu.solve(x.data());
      const double error = (M * x - b).norm() / (M.norm() * x.norm() + b.norm());
      const Eigen::VectorXd xd = M.partialPivLu().solve(b);
      const double dense = (M * xd - b).norm() / (M.norm() * xd.norm() + b.norm());
      BOOST_TEST_MESSAGE("border " << m << ", seed " << seed << ": backward error " << error
                                   << " (dense LU " << dense << ")");
      BOOST_TEST(error <= 1e-14);
    }
  // A singular while the bordered matrix is not (a block column of A zero, the border's rows
  // holding it): refused, for the caller's KLU.
  Dense M = bordered(random_staircase(13, 7, 4, 5), 2, 9);
  M.block(0, 13, 52, 1).setZero();
  BOOST_REQUIRE(std::abs(M.partialPivLu().determinant()) > 1e-6);
  const Sparse S = bordered_pattern(M, 13, 7, 2);
  AlmostBlockDiagonalLU<13, 7> lu(4, 2);
  BOOST_REQUIRE(lu.accept_pattern(S.outerIndexPtr(), S.innerIndexPtr()));
  BOOST_TEST(!lu.factor(S.outerIndexPtr(), S.innerIndexPtr(), S.valuePtr()));
}

BOOST_AUTO_TEST_CASE(refuses_what_it_cannot_solve) {
  const Dense A = random_staircase(5, 3, 4, 7);
  const Sparse S = staircase_pattern(A, 5, 3);
  // Entries outside the staircase: a top row on block 1, an interval row on a block two
  // away, a tip row on the block before the last.
  for (const auto& [row, col] : {std::pair{1, 6}, std::pair{4, 12}, std::pair{18, 10}}) {
    Sparse wide = S;
    wide.coeffRef(row, col) = 1.0;
    wide.makeCompressed();
    AlmostBlockDiagonalLU<5, 3> lu(4);
    BOOST_TEST(!lu.accept_pattern(wide.outerIndexPtr(), wide.innerIndexPtr()),
               "row " << row << ", column " << col);
  }
  // A column whose border row comes before its block rows (factor() scatters the border rows
  // last): refused; the same column in CSC order is accepted.
  {
    const Dense M = bordered(random_staircase(5, 3, 3, 2), 1, 3);
    const Sparse P = bordered_pattern(M, 5, 3, 1);
    std::vector<int> outer(P.outerIndexPtr(), P.outerIndexPtr() + P.cols() + 1);
    std::vector<int> inner(P.innerIndexPtr(), P.innerIndexPtr() + P.nonZeros());
    AlmostBlockDiagonalLU<5, 3> sorted(3, 1);
    BOOST_TEST(sorted.accept_pattern(outer.data(), inner.data()));
    std::swap(inner[outer[0]], inner[outer[1] - 1]);  // column 0: the border row first
    AlmostBlockDiagonalLU<5, 3> unsorted(3, 1);
    BOOST_TEST(!unsorted.accept_pattern(outer.data(), inner.data()));
  }
  // Singular: a block column without non-zeros, and two equal rows.
  for (const bool equal_rows : {false, true}) {
    Sparse singular = S;
    if (equal_rows) {
      const Dense B = [&] {
        Dense M = A;
        M.row(5) = M.row(4);
        return M;
      }();
      singular = staircase_pattern(B, 5, 3);
    } else {
      singular = staircase_pattern(A, 5, 3);
      for (Sparse::InnerIterator it(singular, 7); it; ++it) it.valueRef() = 0.0;
    }
    AlmostBlockDiagonalLU<5, 3> lu(4);
    BOOST_REQUIRE(lu.accept_pattern(singular.outerIndexPtr(), singular.innerIndexPtr()));
    BOOST_TEST(!lu.factor(singular.outerIndexPtr(), singular.innerIndexPtr(), singular.valuePtr()),
               (equal_rows ? "equal rows" : "zero column"));
    BOOST_TEST(!lu.factored());
  }
}

BOOST_AUTO_TEST_CASE(kinsol_solves_through_it) {
  // F(x) = A x - b with A of kinsol statics' shape (13 = 7 + 6, 8 blocks), zero diagonal:
  // KINSOL's Newton step is exact, so one iteration solves it to the linear solver's rounding.
  using rodlab::solvers::KinsolSolver;
  using rodlab::solvers::KluOrder;
  using rodlab::solvers::KluReuse;
  using rodlab::solvers::NewtonLinearSolver;
  const Dense A = random_staircase(13, 7, 8, 11, true);
  const Sparse pattern = staircase_pattern(A, 13, 7);
  rodlab::solvers::KinsolOptions o;
  o.fnormtol = 1e-12;
  o.line_search = false;
  o.max_newton_step = 1e12;  // KINSOL's default bound scales with |x0| = 0; here |x| = 52
  // F(x) = M x - c from x = 0 through `solver`; returns x and its error against the dense LU.
  auto run = [&](KinsolSolver& solver, const Dense& M, double* error) {
    const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(M.rows(), 1.0, -1.0);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(M.rows());
    const auto stats = solver.solve(
        x, [&](const auto& u, auto F) { F = M * u - c; },
        [&](const auto&, const auto&, Sparse& J) {
          for (int col = 0; col < J.outerSize(); ++col)
            for (Sparse::InnerIterator it(J, col); it; ++it) it.valueRef() = M(it.row(), col);
        },
        o);
    BOOST_TEST(stats.converged, stats.flag_name << ": " << stats.message);
    BOOST_TEST(stats.nonlinear_iterations <= 2);  // exact Newton steps (a wrong solve iterates)
    *error = (x - M.partialPivLu().solve(c)).norm() / x.norm();
    return x;
  };
  KinsolSolver solver(pattern, KluReuse::analysis, KluOrder::natural,
                      NewtonLinearSolver::almost_block_diagonal);
  double error = 0.0;
  const Eigen::VectorXd x = run(solver, A, &error);
  BOOST_TEST_MESSAGE("relative error against the dense LU " << error << ", |x| " << x.norm());
  BOOST_TEST(error <= 1e-13);
  KinsolSolver copy(solver);  // its own linear solver, in the state of the original
  BOOST_TEST((run(copy, A, &error) - x).norm() == 0.0);
  // Bordered (two extra unknowns), with A as is and with a block column of A zero: the first by
  // block LU, the second by the KLU fallback, both to the dense LU's solution.
  for (const bool singular_blocks : {false, true}) {
    Dense M = bordered(random_staircase(13, 7, 6, 12, true), 2, 13);
    if (singular_blocks) M.block(0, 20, 78, 1).setZero();
    KinsolSolver bordered_solver(bordered_pattern(M, 13, 7, 2), KluReuse::analysis,
                                 KluOrder::natural, NewtonLinearSolver::almost_block_diagonal);
    run(bordered_solver, M, &error);
    BOOST_TEST_MESSAGE((singular_blocks ? "KLU fallback" : "bordered")
                       << ": relative error " << error);
    BOOST_TEST(error <= 1e-12);
  }
  // A pattern outside the staircase: refused at construction.
  Sparse wide = pattern;
  wide.coeffRef(0, 40) = 1.0;
  BOOST_CHECK_THROW(KinsolSolver(wide, KluReuse::analysis, KluOrder::natural,
                                 NewtonLinearSolver::almost_block_diagonal),
                    std::invalid_argument);
}
