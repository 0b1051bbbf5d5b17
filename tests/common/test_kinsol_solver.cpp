#define BOOST_TEST_MODULE kinsol_solver
#include <boost/test/unit_test.hpp>

// The KINSOL + KLU adapter on small sparse systems with known roots: the extended Rosenbrock
// system (root: all ones) and the Broyden tridiagonal problem (More, Garbow & Hillstrom 1981,
// problem 30; checked by its residual), plus the error paths: exceptions thrown in callbacks
// are rethrown after KINSol returns, non-convergence is a status with KINSOL's flag name, and a
// Jacobian callback may not change the sparsity pattern. solve_broyden (good Broyden's steps on
// one factorised Jacobian) against KINSOL's root and KINSOL's chord method, with its kept
// factors, refreshes and failures.

#include <cmath>
#include <stdexcept>
#include <vector>

#include "rodlab/solvers/common/kinsol_solver.hpp"

using rodlab::solvers::KinsolOptions;
using rodlab::solvers::KinsolRecoverableError;
using rodlab::solvers::KinsolSolver;
using rodlab::solvers::KinsolStats;
using rodlab::solvers::KluOrder;
using rodlab::solvers::KluReuse;
using Vector = Eigen::VectorXd;
using Sparse = KinsolSolver::SparseMatrix;
using VecRef = Eigen::Ref<Vector>;
using ConstRef = Eigen::Ref<const Vector>;

namespace {

Sparse pattern_from(int n, const std::vector<std::pair<int, int>>& entries) {
  std::vector<Eigen::Triplet<double>> t;
  for (auto [i, j] : entries) t.emplace_back(i, j, 1.0);
  Sparse P(n, n);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

// Extended Rosenbrock (n even): F_{2k} = 10 (x_{2k+1} - x_{2k}^2), F_{2k+1} = 1 - x_{2k}.
// The unique root is x = 1; J is block diagonal with 2x2 blocks.
struct Rosenbrock {
  int n;
  Sparse pattern() const {
    std::vector<std::pair<int, int>> e;
    for (int k = 0; k < n; k += 2) e.insert(e.end(), {{k, k}, {k, k + 1}, {k + 1, k}});
    return pattern_from(n, e);
  }
  void residual(const ConstRef& x, VecRef F) const {
    for (int k = 0; k < n; k += 2) {
      F[k] = 10.0 * (x[k + 1] - x[k] * x[k]);
      F[k + 1] = 1.0 - x[k];
    }
  }
  void jacobian(const ConstRef& x, const ConstRef&, Sparse& J) const {
    for (int k = 0; k < n; k += 2) {
      J.coeffRef(k, k) = -20.0 * x[k];
      J.coeffRef(k, k + 1) = 10.0;
      J.coeffRef(k + 1, k) = -1.0;
    }
  }
  Vector start() const {
    Vector x(n);
    for (int k = 0; k < n; k += 2) x[k] = -1.2, x[k + 1] = 1.0;
    return x;
  }
};

// Broyden tridiagonal: F_i = (3 - 2 x_i) x_i - x_{i-1} - 2 x_{i+1} + 1, x_0 = x_{n+1} = 0.
struct BroydenTridiagonal {
  int n;
  Sparse pattern() const {
    std::vector<std::pair<int, int>> e;
    for (int i = 0; i < n; ++i)
      for (int j = std::max(0, i - 1); j <= std::min(n - 1, i + 1); ++j) e.emplace_back(i, j);
    return pattern_from(n, e);
  }
  void residual(const ConstRef& x, VecRef F) const {
    for (int i = 0; i < n; ++i) {
      const double left = i > 0 ? x[i - 1] : 0.0, right = i + 1 < n ? x[i + 1] : 0.0;
      F[i] = (3.0 - 2.0 * x[i]) * x[i] - left - 2.0 * right + 1.0;
    }
  }
  /// Writes the values column by column through the pattern (no search per entry).
  void jacobian(const ConstRef& x, const ConstRef&, Sparse& J) const {
    for (int j = 0; j < n; ++j)
      for (Sparse::InnerIterator it(J, j); it; ++it) {
        const int i = static_cast<int>(it.row());
        it.valueRef() = i == j ? 3.0 - 4.0 * x[i] : (j == i - 1 ? -1.0 : -2.0);
      }
  }
};

template <class Problem>
KinsolSolver::Residual residual_of(const Problem& p) {
  return [&p](const ConstRef& x, VecRef F) { p.residual(x, F); };
}
template <class Problem>
KinsolSolver::Jacobian jacobian_of(const Problem& p) {
  return [&p](const ConstRef& x, const ConstRef& F, Sparse& J) { p.jacobian(x, F, J); };
}

}  // namespace

BOOST_AUTO_TEST_CASE(rosenbrock_converges_to_the_known_root) {
  const Rosenbrock p{20};
  KinsolSolver solver(p.pattern());
  BOOST_TEST(solver.size() == 20);
  Vector x = p.start();
  KinsolOptions options;
  options.fnormtol = 1e-12;
  const KinsolStats stats = solver.solve(x, residual_of(p), jacobian_of(p), options);
  BOOST_TEST_MESSAGE("Rosenbrock: " << stats.flag_name << ", " << stats.nonlinear_iterations
                                    << " iterations, " << stats.jacobian_evaluations << " Jacobians");
  BOOST_TEST(stats.converged);
  BOOST_TEST(stats.flag_name == "KIN_SUCCESS");
  BOOST_TEST((x.array() - 1.0).abs().maxCoeff() <= 1e-12);
  BOOST_TEST(stats.nonlinear_iterations >= 1);
  BOOST_TEST(stats.nonlinear_iterations <= 20);
  // Exact Newton (max_setup_calls = 1): one Jacobian per iteration.
  BOOST_TEST(stats.jacobian_evaluations == stats.nonlinear_iterations);
  BOOST_TEST(stats.function_evaluations >= stats.nonlinear_iterations + 1);
  BOOST_TEST(stats.fnorm <= 1e-11);

  // A second solve on the same solver object starts fresh (statistics of that call only).
  x = p.start();
  const KinsolStats again = solver.solve(x, residual_of(p), jacobian_of(p), options);
  BOOST_TEST(again.converged);
  BOOST_TEST(again.nonlinear_iterations == stats.nonlinear_iterations);
  BOOST_TEST(again.function_evaluations == stats.function_evaluations);

  // From the root itself: KIN_INITIAL_GUESS_OK, no iteration.
  const KinsolStats at_root = solver.solve(x, residual_of(p), jacobian_of(p), options);
  BOOST_TEST(at_root.converged);
  BOOST_TEST(at_root.flag_name == "KIN_INITIAL_GUESS_OK");
  BOOST_TEST(at_root.nonlinear_iterations == 0);
}

BOOST_AUTO_TEST_CASE(broyden_tridiagonal_with_and_without_line_search_and_scaling) {
  const BroydenTridiagonal p{200};
  KinsolSolver solver(p.pattern());
  for (bool line_search : {true, false}) {
    Vector x = Vector::Constant(p.n, -1.0);  // the standard starting point
    KinsolOptions options;
    options.line_search = line_search;
    options.fnormtol = 1e-12;
    const KinsolStats stats = solver.solve(x, residual_of(p), jacobian_of(p), options);
    BOOST_TEST(stats.converged);
    Vector F(p.n);
    p.residual(x, F);
    BOOST_TEST(F.lpNorm<Eigen::Infinity>() <= 1e-12);
    BOOST_TEST(stats.nonlinear_iterations <= 10);
  }
  // Scaling vectors: the scaled residual is what is tested against fnormtol.
  Vector x = Vector::Constant(p.n, -1.0);
  KinsolOptions options;
  options.fnormtol = 1e-10;
  options.u_scale = Vector::Constant(p.n, 2.0);
  options.f_scale = Vector::Constant(p.n, 1e-3);
  const KinsolStats stats = solver.solve(x, residual_of(p), jacobian_of(p), options);
  BOOST_TEST(stats.converged);
  Vector F(p.n);
  p.residual(x, F);
  BOOST_TEST(1e-3 * F.lpNorm<Eigen::Infinity>() <= 1e-10);
}

// KLU in the pattern's own column order (KluOrder::natural, what kinsol statics uses for its
// block-banded Jacobian), with and without kept factors: the same root as the default
// fill-reducing order, to the tolerance (reference: the default-order solve of the same system).
BOOST_AUTO_TEST_CASE(natural_column_order_finds_the_same_root) {
  const BroydenTridiagonal p{200};
  KinsolOptions options;
  options.fnormtol = 1e-12;
  Vector reference = Vector::Constant(p.n, -1.0);
  KinsolSolver fill_reducing(p.pattern());
  BOOST_TEST(fill_reducing.solve(reference, residual_of(p), jacobian_of(p), options).converged);
  for (KluReuse reuse : {KluReuse::none, KluReuse::analysis, KluReuse::factors}) {
    KinsolSolver natural(p.pattern(), reuse, KluOrder::natural);
    Vector x = Vector::Constant(p.n, -1.0);
    const KinsolStats stats = natural.solve(x, residual_of(p), jacobian_of(p), options);
    BOOST_TEST(stats.converged);
    BOOST_TEST(stats.nonlinear_iterations <= 10);
    BOOST_TEST((x - reference).lpNorm<Eigen::Infinity>() <= 1e-11);
    KinsolSolver copy(natural);  // the order travels with a copy
    Vector y = Vector::Constant(p.n, -1.0);
    BOOST_TEST(copy.solve(y, residual_of(p), jacobian_of(p), options).converged);
    BOOST_TEST((y - reference).lpNorm<Eigen::Infinity>() <= 1e-11);
  }
}

BOOST_AUTO_TEST_CASE(modified_newton_reuses_the_jacobian) {
  const BroydenTridiagonal p{50};
  KinsolSolver solver(p.pattern());
  Vector x = Vector::Constant(p.n, -1.0);
  KinsolOptions options;
  options.max_setup_calls = 10;
  options.fnormtol = 1e-11;
  const KinsolStats stats = solver.solve(x, residual_of(p), jacobian_of(p), options);
  BOOST_TEST(stats.converged);
  BOOST_TEST(stats.jacobian_evaluations < stats.nonlinear_iterations);
}

// A copy and an assigned solver (control snapshots of a time stepper, stepper.hpp) hold the
// kept KLU factors of the original: a solve that starts from them (reuse_factorisation) repeats
// the original's bit for bit, where a solver with other kept factors ends elsewhere in the last
// bits. Assigning from another size is refused.
BOOST_AUTO_TEST_CASE(copy_and_assign_repeat_the_kept_factors) {
  const BroydenTridiagonal p{50};
  KinsolOptions options;
  options.max_setup_calls = 10;  // modified Newton: the kept factors serve several iterations
  options.fnormtol = 1e-11;
  auto solve_from = [&](KinsolSolver& solver, double start, bool reuse) {
    Vector x = Vector::Constant(p.n, start);
    KinsolOptions o = options;
    o.reuse_factorisation = reuse;
    const KinsolStats stats = solver.solve(x, residual_of(p), jacobian_of(p), o);
    BOOST_TEST_REQUIRE(stats.converged);
    return x;
  };
  KinsolSolver original(p.pattern(), KluReuse::factors);
  solve_from(original, -1.0, false);
  KinsolSolver copy(original);
  KinsolSolver assigned(p.pattern(), KluReuse::factors), other(p.pattern(), KluReuse::factors);
  solve_from(assigned, -0.5, false);  // other factors, then replaced by the original's
  assigned.assign(original);
  solve_from(other, -0.5, false);
  const Vector reference = solve_from(original, -0.9, true);
  BOOST_TEST((solve_from(copy, -0.9, true) - reference).norm() == 0.0);
  BOOST_TEST((solve_from(assigned, -0.9, true) - reference).norm() == 0.0);
  BOOST_TEST((solve_from(other, -0.9, true) - reference).norm() > 0.0);  // the factors matter
  KinsolSolver smaller(BroydenTridiagonal{10}.pattern(), KluReuse::factors);
  BOOST_CHECK_THROW(smaller.assign(original), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(exception_in_the_residual_is_rethrown_after_kinsol_returns) {
  const Rosenbrock p{4};
  KinsolSolver solver(p.pattern());
  int calls = 0;
  const KinsolSolver::Residual throwing = [&](const ConstRef& x, VecRef F) {
    if (++calls == 3) throw std::domain_error("residual failed on purpose");
    p.residual(x, F);
  };
  Vector x = p.start();
  BOOST_CHECK_THROW(solver.solve(x, throwing, jacobian_of(p)), std::domain_error);
  BOOST_TEST(calls == 3);  // KINSOL stopped at the unrecoverable flag
  // The solver object is still usable afterwards.
  x = p.start();
  BOOST_TEST(solver.solve(x, residual_of(p), jacobian_of(p)).converged);
}

BOOST_AUTO_TEST_CASE(exception_in_the_jacobian_is_rethrown) {
  const Rosenbrock p{4};
  KinsolSolver solver(p.pattern());
  const KinsolSolver::Jacobian throwing = [](const ConstRef&, const ConstRef&, Sparse&) {
    throw std::out_of_range("jacobian failed on purpose");
  };
  Vector x = p.start();
  BOOST_CHECK_THROW(solver.solve(x, residual_of(p), throwing), std::out_of_range);
}

BOOST_AUTO_TEST_CASE(changing_the_pattern_is_an_error) {
  const Rosenbrock p{4};
  KinsolSolver solver(p.pattern());
  const KinsolSolver::Jacobian inserting = [&p](const ConstRef& x, const ConstRef& F, Sparse& J) {
    p.jacobian(x, F, J);
    J.coeffRef(1, 1) = 1.0;  // not in the pattern: inserts an entry
  };
  Vector x = p.start();
  BOOST_CHECK_THROW(solver.solve(x, residual_of(p), inserting), std::logic_error);
}

BOOST_AUTO_TEST_CASE(non_convergence_is_a_status_with_the_flag_name) {
  const Rosenbrock p{4};
  KinsolSolver solver(p.pattern());
  Vector x = p.start();
  KinsolOptions options;
  options.max_iterations = 1;
  const KinsolStats stats = solver.solve(x, residual_of(p), jacobian_of(p), options);
  BOOST_TEST(!stats.converged);
  BOOST_TEST(stats.flag_name == "KIN_MAXITER_REACHED");
  BOOST_TEST(stats.nonlinear_iterations == 1);
  BOOST_TEST(!stats.message.empty());

  // x^2 + 1 = 0 has no real root: the line search fails (or the iteration stalls).
  KinsolSolver scalar(pattern_from(1, {{0, 0}}));
  Vector y = Vector::Constant(1, 0.5);
  const KinsolStats none = scalar.solve(
      y, [](const ConstRef& v, VecRef F) { F[0] = v[0] * v[0] + 1.0; },
      [](const ConstRef& v, const ConstRef&, Sparse& J) { J.coeffRef(0, 0) = 2.0 * v[0]; });
  BOOST_TEST_MESSAGE("x^2 + 1: " << none.flag_name << " after " << none.nonlinear_iterations << " iterations");
  BOOST_TEST(!none.converged);
  BOOST_TEST(none.flag < 0);
  BOOST_TEST(none.flag_name.rfind("KIN_", 0) == 0);
}

BOOST_AUTO_TEST_CASE(non_finite_residual_is_recoverable_not_thrown) {
  const Rosenbrock p{4};
  KinsolSolver solver(p.pattern());
  Vector x = p.start();
  const KinsolStats stats = solver.solve(
      x, [](const ConstRef&, VecRef F) { F.setConstant(std::nan("")); }, jacobian_of(p));
  BOOST_TEST(!stats.converged);
  BOOST_TEST(stats.flag_name == "KIN_FIRST_SYSFUNC_ERR");

  x = p.start();
  const KinsolStats thrown = solver.solve(
      x, [](const ConstRef&, VecRef) { throw KinsolRecoverableError("cannot evaluate here"); },
      jacobian_of(p));
  BOOST_TEST(!thrown.converged);
  BOOST_TEST(thrown.flag_name == "KIN_FIRST_SYSFUNC_ERR");
}

BOOST_AUTO_TEST_CASE(bad_inputs_throw_invalid_argument) {
  BOOST_CHECK_THROW(KinsolSolver(Sparse(3, 4)), std::invalid_argument);
  BOOST_CHECK_THROW(KinsolSolver(Sparse(3, 3)), std::invalid_argument);  // no entries
  const Rosenbrock p{4};
  KinsolSolver solver(p.pattern());
  Vector wrong(3);
  wrong.setZero();
  BOOST_CHECK_THROW(solver.solve(wrong, residual_of(p), jacobian_of(p)), std::invalid_argument);
  Vector x = p.start();
  KinsolOptions bad;
  bad.fnormtol = -1.0;
  BOOST_CHECK_THROW(solver.solve(x, residual_of(p), jacobian_of(p), bad), std::invalid_argument);
  bad = {};
  bad.u_scale = Vector::Constant(4, -1.0);
  BOOST_CHECK_THROW(solver.solve(x, residual_of(p), jacobian_of(p), bad), std::invalid_argument);
  bad = {};
  bad.f_scale = Vector::Ones(5);
  BOOST_CHECK_THROW(solver.solve(x, residual_of(p), jacobian_of(p), bad), std::invalid_argument);
}

// solve_broyden: full steps of good Broyden's method on one factorised Jacobian (QNERR,
// broyden_steps.hpp). References: KINSOL's exact Newton root of the same system (to the
// tolerance), and KINSOL's chord method on the same Jacobian (full steps, no line search,
// max_setup_calls 1000), which converges linearly where Broyden's secant updates converge
// superlinearly: fewer iterations from the same start.
BOOST_AUTO_TEST_CASE(broyden_steps_find_the_root_in_fewer_iterations_than_the_chord) {
  const BroydenTridiagonal p{200};
  KinsolOptions options;
  options.fnormtol = 1e-12;
  options.u_scale = Vector::LinSpaced(p.n, 0.5, 2.0);
  Vector reference = Vector::Constant(p.n, -1.0);
  KinsolSolver solver(p.pattern(), KluReuse::factors);
  BOOST_TEST_REQUIRE(solver.solve(reference, residual_of(p), jacobian_of(p), options).converged);

  const double start = -0.8;
  Vector x = Vector::Constant(p.n, start);
  KinsolOptions one = options;
  one.broyden_jacobians = 1;
  const KinsolStats broyden = solver.solve_broyden(x, residual_of(p), jacobian_of(p), one);
  Vector chord = Vector::Constant(p.n, start);
  KinsolOptions chord_options = options;
  chord_options.line_search = false;
  chord_options.max_setup_calls = 1000;
  const KinsolStats kinsol = solver.solve(chord, residual_of(p), jacobian_of(p), chord_options);
  BOOST_TEST_MESSAGE("from " << start << ": Broyden " << broyden.nonlinear_iterations
                             << " iterations, chord " << kinsol.nonlinear_iterations << " ("
                             << kinsol.flag_name << ", " << kinsol.jacobian_evaluations
                             << " Jacobians)");
  BOOST_TEST(broyden.converged);
  BOOST_TEST(broyden.flag_name == "KIN_SUCCESS");
  BOOST_TEST(broyden.jacobian_evaluations == 1);
  BOOST_TEST(broyden.function_evaluations == broyden.nonlinear_iterations + 1);
  Vector F(p.n);
  p.residual(x, F);
  BOOST_TEST(F.lpNorm<Eigen::Infinity>() <= 1e-12);
  BOOST_TEST((x - reference).lpNorm<Eigen::Infinity>() <= 1e-11);
  BOOST_TEST(kinsol.converged);
  BOOST_TEST(kinsol.jacobian_evaluations >= broyden.jacobian_evaluations);
  BOOST_TEST(broyden.nonlinear_iterations < kinsol.nonlinear_iterations);
}

// Kept factors: a nearby system starts from them with no Jacobian; factors formed far away
// stop the steps contracting, and a Jacobian is set up where they stand; an initial guess
// within fnormtol / 100 takes no step.
BOOST_AUTO_TEST_CASE(broyden_steps_start_from_kept_factors_and_refresh_them) {
  const BroydenTridiagonal p{50};
  KinsolOptions options;
  options.fnormtol = 1e-11;
  KinsolSolver solver(p.pattern(), KluReuse::factors);
  Vector root = Vector::Constant(p.n, -1.0);
  BOOST_TEST_REQUIRE(solver.solve_broyden(root, residual_of(p), jacobian_of(p), options).converged);
  KinsolOptions kept = options;
  kept.reuse_factorisation = true;
  Vector x = root + Vector::Constant(p.n, 1e-3);
  const KinsolStats near = solver.solve_broyden(x, residual_of(p), jacobian_of(p), kept);
  BOOST_TEST(near.converged);
  BOOST_TEST(near.jacobian_evaluations == 0);
  BOOST_TEST((x - root).lpNorm<Eigen::Infinity>() <= 1e-10);

  // Factors formed at x = 3 (one step from there), where dF_i/dx_i = 3 - 4 x_i is -9 against
  // about +5 at the root: the kept model points the wrong way near the root.
  Vector elsewhere = Vector::Constant(p.n, 3.0);
  KinsolOptions one_step = options;
  one_step.max_iterations = 1;
  solver.solve_broyden(elsewhere, residual_of(p), jacobian_of(p), one_step);
  x = root + Vector::Constant(p.n, 1e-2);
  const KinsolStats refreshed = solver.solve_broyden(x, residual_of(p), jacobian_of(p), kept);
  BOOST_TEST_MESSAGE("near the root with factors from x = 3: " << refreshed.nonlinear_iterations
                                                               << " iterations, "
                                                               << refreshed.jacobian_evaluations
                                                               << " Jacobians");
  BOOST_TEST(refreshed.converged);
  BOOST_TEST(refreshed.jacobian_evaluations >= 1);
  BOOST_TEST((x - root).lpNorm<Eigen::Infinity>() <= 1e-10);

  KinsolOptions loose = kept;
  loose.fnormtol = 1e-7;  // the root to 1e-11 is within fnormtol / 100
  const KinsolStats at_root = solver.solve_broyden(x, residual_of(p), jacobian_of(p), loose);
  BOOST_TEST(at_root.converged);
  BOOST_TEST(at_root.flag_name == "KIN_INITIAL_GUESS_OK");
  BOOST_TEST(at_root.nonlinear_iterations == 0);
}

BOOST_AUTO_TEST_CASE(broyden_failures_are_statuses_and_errors_are_thrown) {
  const Rosenbrock p{4};
  KinsolSolver solver(p.pattern());
  KinsolOptions options;
  options.max_iterations = 1;  // Newton needs 2 on the extended Rosenbrock system
  Vector x = p.start();
  const KinsolStats few = solver.solve_broyden(x, residual_of(p), jacobian_of(p), options);
  BOOST_TEST(!few.converged);
  BOOST_TEST(few.flag_name == "KIN_MAXITER_REACHED");
  BOOST_TEST(few.nonlinear_iterations == 1);

  // x^2 + 1 = 0: no real root; the steps stop contracting and the Jacobians run out.
  KinsolSolver scalar(pattern_from(1, {{0, 0}}));
  Vector y = Vector::Constant(1, 0.5);
  const KinsolStats none = scalar.solve_broyden(
      y, [](const ConstRef& v, VecRef F) { F[0] = v[0] * v[0] + 1.0; },
      [](const ConstRef& v, const ConstRef&, Sparse& J) { J.coeffRef(0, 0) = 2.0 * v[0]; },
      KinsolOptions{});
  BOOST_TEST_MESSAGE("x^2 + 1: " << none.flag_name << " after " << none.nonlinear_iterations
                                 << " iterations, " << none.jacobian_evaluations << " Jacobians");
  BOOST_TEST(!none.converged);
  BOOST_TEST(none.jacobian_evaluations == KinsolOptions{}.broyden_jacobians);

  x = p.start();
  const KinsolStats nan = solver.solve_broyden(
      x, [](const ConstRef&, VecRef F) { F.setConstant(std::nan("")); }, jacobian_of(p), {});
  BOOST_TEST(!nan.converged);
  x = p.start();
  const KinsolStats recoverable = solver.solve_broyden(
      x, [](const ConstRef&, VecRef) { throw KinsolRecoverableError("cannot evaluate here"); },
      jacobian_of(p), {});
  BOOST_TEST(!recoverable.converged);
  BOOST_TEST(recoverable.message == "cannot evaluate here");
  x = p.start();
  const KinsolSolver::Jacobian throwing = [](const ConstRef&, const ConstRef&, Sparse&) {
    throw std::out_of_range("jacobian failed on purpose");
  };
  BOOST_CHECK_THROW(solver.solve_broyden(x, residual_of(p), throwing, {}), std::out_of_range);

  KinsolOptions bad;
  bad.broyden_jacobians = 0;
  BOOST_CHECK_THROW(solver.solve_broyden(x, residual_of(p), jacobian_of(p), bad),
                    std::invalid_argument);
  bad = {};
  bad.reuse_factorisation = true;  // a solver without KluReuse::factors keeps none
  BOOST_CHECK_THROW(solver.solve_broyden(x, residual_of(p), jacobian_of(p), bad),
                    std::invalid_argument);
}

// Near the tolerance the residual of a real system is rounding (collocation's at N = 20, 1 ms
// stalls at 1-2 fnormtol): steps of that size do not contract, and a new Jacobian would not
// make them. solve_broyden keeps its J0 there (within 4 fnormtol). Reference: a linear system
// F = 2 (x - 1) + e with e a deterministic "rounding" of +-1.2 fnormtol that stops after the
// 8th evaluation: the steps keep the first Jacobian and converge (7 iterations); without the
// rule every noisy step sets a Jacobian up and they run out (3, not converged).
BOOST_AUTO_TEST_CASE(broyden_keeps_its_jacobian_at_the_rounding_level) {
  const int n = 3;
  KinsolSolver solver(pattern_from(n, {{0, 0}, {1, 1}, {2, 2}}));
  KinsolOptions options;  // fnormtol 1e-10
  int calls = 0;
  const KinsolSolver::Residual noisy = [&](const ConstRef& x, VecRef F) {
    ++calls;
    const double e = calls <= 8 ? (calls % 2 ? 1.2e-10 : -1.2e-10) : 0.0;
    for (int i = 0; i < n; ++i) F[i] = 2.0 * (x[i] - 1.0) + e * (i + 1) / n;
  };
  const KinsolSolver::Jacobian exact = [](const ConstRef&, const ConstRef&, Sparse& J) {
    for (int i = 0; i < 3; ++i) J.coeffRef(i, i) = 2.0;
  };
  Vector x = Vector::Zero(n);
  const KinsolStats stats = solver.solve_broyden(x, noisy, exact, options);
  BOOST_TEST_MESSAGE("rounding-level residual: " << stats.flag_name << " after "
                                                 << stats.nonlinear_iterations << " iterations, "
                                                 << stats.jacobian_evaluations << " Jacobians");
  BOOST_TEST(stats.converged);
  BOOST_TEST(stats.jacobian_evaluations == 1);
  BOOST_TEST((x.array() - 1.0).abs().maxCoeff() <= 1e-10);
}
