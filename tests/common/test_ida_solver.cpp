#define BOOST_TEST_MODULE ida_solver
#include <boost/test/unit_test.hpp>

// The IDA + KLU adapter on small systems with closed-form solutions: the harmonic oscillator
// written implicitly (y = [cos t, -sin t]) and an index-1 DAE (y0' = -y0, 0 = y1 - y0^2, so
// y = [e^-t, e^-2t]); plus the error paths: a callback's exception is rethrown after IDASolve
// returns, a recoverable error makes IDA retry, too much work is a status with IDA's flag name,
// and a Jacobian callback may not change the sparsity pattern.

#include <cmath>
#include <stdexcept>
#include <vector>

#include "rodlab/solvers/common/ida_solver.hpp"

using rodlab::solvers::IdaRecoverableError;
using rodlab::solvers::IdaSolver;
using rodlab::solvers::IdaSolverOptions;
using rodlab::solvers::IdaStats;
using Vector = Eigen::VectorXd;
using Sparse = IdaSolver::SparseMatrix;
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

IdaSolverOptions tight(int n) {
  IdaSolverOptions o;
  o.rtol = 1e-10;
  o.atol = Vector::Constant(n, 1e-12);
  return o;
}

// y0' - y1 = 0, y1' + y0 = 0.
void oscillator(double, const ConstRef& y, const ConstRef& yp, VecRef r) {
  r[0] = yp[0] - y[1];
  r[1] = yp[1] + y[0];
}
void oscillator_jacobian(double, double cj, const ConstRef&, const ConstRef&, const ConstRef&, Sparse& J) {
  J.coeffRef(0, 0) = cj;
  J.coeffRef(0, 1) = -1.0;
  J.coeffRef(1, 0) = 1.0;
  J.coeffRef(1, 1) = cj;
}
Sparse oscillator_pattern() { return pattern_from(2, {{0, 0}, {0, 1}, {1, 0}, {1, 1}}); }

}  // namespace

// Reference: cos t, -sin t. Tolerance 1e-8 over 10 time units (rtol 1e-10, atol 1e-12: the global
// error grows about linearly with t).
BOOST_AUTO_TEST_CASE(oscillator_matches_closed_form) {
  IdaSolver ida(oscillator_pattern(), oscillator, oscillator_jacobian, tight(2));
  ida.initialize(0.0, Vector{{1.0, 0.0}}, Vector{{0.0, -1.0}});
  long steps = 0;
  for (int k = 1; k <= 10; ++k) {
    const IdaStats s = ida.advance(k);
    BOOST_REQUIRE_MESSAGE(s.ok, s.flag_name);
    BOOST_TEST(s.t == static_cast<double>(k));  // the stop time is hit exactly
    BOOST_TEST(ida.time() == static_cast<double>(k));
    BOOST_TEST(std::abs(ida.y()[0] - std::cos(k)) <= 1e-8);
    BOOST_TEST(std::abs(ida.y()[1] + std::sin(k)) <= 1e-8);
    BOOST_TEST(std::abs(ida.yp()[0] + std::sin(k)) <= 1e-8);
    steps += s.steps;
  }
  const IdaStats total = ida.statistics();
  BOOST_TEST(total.steps == steps);
  BOOST_TEST(total.jacobian_evaluations > 0);
  BOOST_TEST(total.nonlinear_iterations >= total.steps);
  BOOST_TEST(total.last_order >= 1);
  BOOST_TEST(total.last_order <= 5);

  // A restart (IDAReInit) from the exact state at t = 10 continues to t = 12.
  ida.initialize(10.0, Vector{{std::cos(10.0), -std::sin(10.0)}}, Vector{{-std::sin(10.0), -std::cos(10.0)}});
  BOOST_TEST(ida.statistics().steps == 0);
  BOOST_REQUIRE(ida.advance(12.0).ok);
  BOOST_TEST(std::abs(ida.y()[0] - std::cos(12.0)) <= 1e-8);
}

// Reference: y0 = e^-t, y1 = e^-2t, for an index-1 DAE with an algebraic row. Tolerance 1e-8.
BOOST_AUTO_TEST_CASE(index_one_dae) {
  auto residual = [](double, const ConstRef& y, const ConstRef& yp, VecRef r) {
    r[0] = yp[0] + y[0];
    r[1] = y[1] - y[0] * y[0];
  };
  auto jacobian = [](double, double cj, const ConstRef& y, const ConstRef&, const ConstRef&, Sparse& J) {
    J.coeffRef(0, 0) = cj + 1.0;
    J.coeffRef(1, 0) = -2.0 * y[0];
    J.coeffRef(1, 1) = 1.0;
  };
  IdaSolver ida(pattern_from(2, {{0, 0}, {1, 0}, {1, 1}}), residual, jacobian, tight(2));
  ida.initialize(0.0, Vector{{1.0, 1.0}}, Vector{{-1.0, -2.0}});
  const IdaStats s = ida.advance(2.0);
  BOOST_REQUIRE_MESSAGE(s.ok, s.flag_name);
  BOOST_TEST(std::abs(ida.y()[0] - std::exp(-2.0)) <= 1e-8);
  BOOST_TEST(std::abs(ida.y()[1] - std::exp(-4.0)) <= 1e-8);
}

BOOST_AUTO_TEST_CASE(callback_exception_is_rethrown) {
  auto residual = [](double t, const ConstRef& y, const ConstRef& yp, VecRef r) {
    if (t > 0.5) throw std::domain_error("residual refuses t > 0.5");
    oscillator(t, y, yp, r);
  };
  IdaSolver ida(oscillator_pattern(), residual, oscillator_jacobian, tight(2));
  ida.initialize(0.0, Vector{{1.0, 0.0}}, Vector{{0.0, -1.0}});
  BOOST_CHECK_THROW(ida.advance(1.0), std::domain_error);
  BOOST_TEST(ida.time() <= 0.5);
  // The solver stays usable: a restart integrates to 0.4.
  ida.initialize(0.0, Vector{{1.0, 0.0}}, Vector{{0.0, -1.0}});
  BOOST_TEST(ida.advance(0.4).ok);
}

BOOST_AUTO_TEST_CASE(recoverable_error_makes_ida_retry) {
  int refusals = 0;
  auto residual = [&](double t, const ConstRef& y, const ConstRef& yp, VecRef r) {
    if (t > 0.3 && refusals < 3) {
      ++refusals;
      throw IdaRecoverableError("not yet");
    }
    oscillator(t, y, yp, r);
  };
  IdaSolver ida(oscillator_pattern(), residual, oscillator_jacobian, tight(2));
  ida.initialize(0.0, Vector{{1.0, 0.0}}, Vector{{0.0, -1.0}});
  const IdaStats s = ida.advance(1.0);
  BOOST_TEST(s.ok, s.flag_name << ": " << s.message);
  BOOST_TEST(refusals == 3);
  BOOST_TEST(std::abs(ida.y()[0] - std::cos(1.0)) <= 1e-8);
}

BOOST_AUTO_TEST_CASE(too_much_work_is_a_status) {
  IdaSolverOptions o = tight(2);
  o.max_steps = 3;
  IdaSolver ida(oscillator_pattern(), oscillator, oscillator_jacobian, o);
  ida.initialize(0.0, Vector{{1.0, 0.0}}, Vector{{0.0, -1.0}});
  const IdaStats s = ida.advance(10.0);
  BOOST_TEST(!s.ok);
  BOOST_TEST(s.flag_name == "IDA_TOO_MUCH_WORK");
  BOOST_TEST(!s.message.empty());
  BOOST_TEST(s.steps == 3);
  BOOST_TEST(s.t > 0.0);
  BOOST_TEST(s.t < 10.0);
  BOOST_TEST(ida.time() == s.t);
}

BOOST_AUTO_TEST_CASE(pattern_change_and_bad_input_throw) {
  auto bad_jacobian = [](double, double cj, const ConstRef&, const ConstRef&, const ConstRef&, Sparse& J) {
    J.insert(1, 1) = cj;  // not in the pattern
  };
  IdaSolver ida(pattern_from(2, {{0, 0}, {0, 1}, {1, 0}}), oscillator, bad_jacobian, tight(2));
  BOOST_CHECK_THROW(ida.advance(1.0), std::logic_error);  // before initialize()
  ida.initialize(0.0, Vector{{1.0, 0.0}}, Vector{{0.0, -1.0}});
  BOOST_CHECK_THROW(ida.advance(1.0), std::logic_error);
  BOOST_CHECK_THROW(ida.advance(-1.0), std::invalid_argument);
  BOOST_CHECK_THROW(ida.initialize(0.0, Vector{{1.0}}, Vector{{0.0}}), std::invalid_argument);

  IdaSolverOptions wrong = tight(3);
  BOOST_CHECK_THROW(IdaSolver(oscillator_pattern(), oscillator, oscillator_jacobian, wrong),
                    std::invalid_argument);
  wrong = tight(2);
  wrong.atol[1] = 0.0;
  BOOST_CHECK_THROW(IdaSolver(oscillator_pattern(), oscillator, oscillator_jacobian, wrong),
                    std::invalid_argument);
  BOOST_CHECK_THROW(IdaSolver(Sparse(2, 3), oscillator, oscillator_jacobian, tight(2)),
                    std::invalid_argument);
}
