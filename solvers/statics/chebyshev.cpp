#include "rodlab/solvers/statics/chebyshev.hpp"
#include "rodlab/solvers/statics/chebyshev_tracker.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/QR>

#include "rodlab/check.hpp"
#include "rodlab/solvers/common/chebyshev_operators.hpp"
#include "rodlab/solvers/common/deadline.hpp"
#include "rodlab/solvers/statics/chebyshev_newton_matrix.hpp"
#include "rodlab/solvers/statics/continuation.hpp"
#include "rodlab/solvers/statics/result_builder.hpp"
#include "rodlab/solvers/statics/shooting.hpp"

namespace rodlab::solvers::statics {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using std::numbers::pi;

/// A chart turning by more than this triggers a split into more elements.
constexpr double kSplitRotation = 2.0 * pi / 3.0;
/// Iterates whose chart turns by more than this are rejected (dexp^-1 has its pole at 2 pi).
constexpr double kChartLimit = 0.9 * 2.0 * pi;
/// Minimum nodes per element when elements are chosen automatically, and the fallback minimum
/// when a failed attempt cannot otherwise be split.
constexpr int kMinElementNodes = 5;
constexpr int kMinFallbackNodes = 3;
/// Below this ratio of the smallest to the largest pivot the Newton matrix is treated as singular.
constexpr double kSingularPivot = 1e-14;
/// Reuse the factorisation while the residual drops by at least this factor per step.
constexpr double kReuseRatio = 0.1;
/// Converged also when the residual stalls within this factor of its rounding level.
constexpr double kRoundingFactor = 10.0;
/// Newton iterations allowed per element layout, direct solve and continuation together, in
/// units of max_iterations (each may cost a dense factorisation).
constexpr int kBudgetFactor = 4;
/// A converged solution whose collocation residual between the nodes exceeds this fraction of
/// its size (scaled unknowns, at least 1) is reported as not resolved. Measured: resolved
/// solutions <= 0.05 (N = 12, heavy gravity), spurious roots >= 1.5.
constexpr double kResolvedDefect = 0.25;
/// Line-search halvings before a step is given up (alpha down to 2^-19).
constexpr int kMaxHalvings = 20;
/// Central-difference step for the node blocks of the Jacobian (scaled unknowns).
constexpr double kFdStep = 1e-5;
/// The direct solve starts from the reference guess bent by its own wrench (complete_kinematics)
/// when no chart then turns by more than this: there the undeformed rod's wrench is a good guess
/// of the deformed rod's; beyond, it over-bends the rod.
constexpr double kCompletionRotation = kSplitRotation / 2.0;
/// Fixed-point sweeps of that bending (contraction ~ rotation / 2).
constexpr int kCompletionSweeps = 2;
/// With actuator breakpoints the elements get intervals in proportion to (length / L) to this
/// power. Measured (tests/statics/test_chebyshev_actuators.cpp, five actuator cases, tip errors
/// at N = 12..40): 1 (in proportion to length) leaves short elements with 2-3 nodes and the
/// error stalls (4.4e-3 m at N = 12 with a cable entering at 0.0213 under T = 4 N, 8.4e-6 m at
/// N = 16..24 with three cables); 0 (equal shares) starves long elements; 1/2 was best or
/// close to it in every case.
constexpr double kLengthExponent = 0.5;

/// Chebyshev-Lobatto operators on [-1, 1] for one node count (chebyshev_operators.hpp).
struct Operators {
  VectorXd t;          ///< points
  MatrixXd D;          ///< differentiation
  MatrixXd absD;       ///< its entries' magnitudes
  MatrixXd integrate;  ///< chebyshev_integration_matrix
  MatrixXd midpoints;  ///< interpolation to the midpoints in angle, -cos((j + 1/2) pi / (n - 1))
  VectorXd mid;        ///< those midpoints
  VectorXd weights;    ///< Clenshaw-Curtis quadrature weights
};

/// The operators for n nodes. They depend on n only: each thread builds them once per n.
const Operators& operators(int n) {
  thread_local std::map<int, Operators> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    MatrixXd D = chebyshev_differentiation_matrix(n);
    MatrixXd absD = D.cwiseAbs();
    const int m = n - 1;
    VectorXd mid(m);
    for (int j = 0; j < m; ++j) mid[j] = -std::cos((j + 0.5) * pi / m);
    MatrixXd midpoints = chebyshev_interpolation_matrix(n, mid);
    it = cache.emplace(n, Operators{chebyshev_lobatto_points(n), std::move(D), std::move(absD),
                                    chebyshev_integration_matrix(n), std::move(midpoints), std::move(mid),
                                    clenshaw_curtis_weights(n)})
             .first;
  }
  return it->second;
}

struct Element {
  int n;                  ///< nodes
  int offset;             ///< index of its first node in the unknowns (interface nodes duplicated)
  double half;            ///< half its length: d/ds = D / half
  const Operators* op;
  std::vector<double> s;  ///< arclengths of its nodes
  StaticProblem::Mask mask = 0;  ///< actuators active on it (one set: no breakpoint inside)
  bool entry_after = false;      ///< a cable enters the rod at its end (Lambda jumps there)
};

/// Element boundaries and intervals (nodes - 1) per element of one layout (chebyshev.hpp,
/// "spectral elements" and "actuators").
struct Layout {
  std::vector<double> cuts;
  std::vector<int> intervals;
  int elements() const { return static_cast<int>(intervals.size()); }
};

/// Element boundaries of layout level E: E equal elements without breakpoints; with them, every
/// stretch between breakpoints (and the ends) split into ceil(E l / L) equal elements.
std::vector<double> element_cuts(const StaticProblem& P, int level) {
  const double L = P.length();
  const auto& breaks = P.breakpoints();
  std::vector<double> cuts{0.0};
  if (breaks.empty()) {
    for (int e = 1; e <= level; ++e) cuts.push_back(e == level ? L : L * e / level);
    return cuts;
  }
  double a = 0.0;
  for (std::size_t k = 0; k <= breaks.size(); ++k) {
    const double b = k < breaks.size() ? breaks[k] : L;
    const int parts = std::max(1, static_cast<int>(std::ceil(level * (b - a) / L - 1e-9)));
    for (int c = 1; c <= parts; ++c) cuts.push_back(c == parts ? b : a + (b - a) * c / parts);
    a = b;
  }
  return cuts;
}

int element_count(const StaticProblem& P, int level) {
  return static_cast<int>(element_cuts(P, level).size()) - 1;
}

/// The layout of level E with N nodes. Without breakpoints the first (N - 1) mod E elements have
/// one interval more than the others. With breakpoints the N - 1 intervals are shared in
/// proportion to (l_e / L)^kLengthExponent, at least 2 per element when N allows (else 1).
Layout make_layout(const StaticProblem& P, int nodes, int level) {
  const double L = P.length();
  const int intervals = nodes - 1;
  Layout out{element_cuts(P, level), {}};
  const int E = static_cast<int>(out.cuts.size()) - 1;
  if (P.breakpoints().empty()) {
    for (int e = 0; e < E; ++e) out.intervals.push_back(intervals / E + (e < intervals % E ? 1 : 0));
    return out;
  }
  const int least = intervals >= 2 * E ? 2 : 1;
  std::vector<double> ideal(E);
  double sum = 0.0;
  for (int e = 0; e < E; ++e)
    sum += ideal[e] = std::pow((out.cuts[e + 1] - out.cuts[e]) / L, kLengthExponent);
  out.intervals.resize(E);
  int total = 0;
  for (int e = 0; e < E; ++e) {
    ideal[e] *= intervals / sum;
    out.intervals[e] = std::max(least, static_cast<int>(std::floor(ideal[e])));
    total += out.intervals[e];
  }
  while (total > intervals) {  // take from the most over-served element that can spare one
    int best = -1;
    for (int e = 0; e < E; ++e)
      if (out.intervals[e] > least &&
          (best < 0 || out.intervals[e] - ideal[e] > out.intervals[best] - ideal[best]))
        best = e;
    --out.intervals[best];
    --total;
  }
  while (total < intervals) {  // give to the most under-served one
    int best = 0;
    for (int e = 1; e < E; ++e)
      if (ideal[e] - out.intervals[e] > ideal[best] - out.intervals[best]) best = e;
    ++out.intervals[best];
    ++total;
  }
  return out;
}

/// Path lengths of the actuators by index (StaticProblem::extra_residuals).
using Lengths = std::array<double, StaticProblem::kMaxActuators>;

struct NewtonOutcome {
  bool converged = false;
  int iterations = 0;
  double residual_norm = 0.0;
  std::string reason;
  bool factorized = false;  ///< the Newton matrix holds a valid (condensed) factorisation on return
};

/// The collocation system of one element layout at the problem's current load factor.
class Collocation {
 public:
  /// The layout of level E (make_layout); with actuators, element boundaries at the breakpoints.
  Collocation(const StaticProblem& problem, int nodes, int level)
      : P_(problem), extra_(problem.extra_unknowns()) {
    const double L = P_.length();
    const Layout layout = make_layout(P_, nodes, level);
    const int elements = layout.elements();
    int offset = 0, largest = 0;
    for (int e = 0; e < elements; ++e) {
      const int n = layout.intervals[e] + 1;
      const Operators& op = operators(n);
      const double a = layout.cuts[e], b = layout.cuts[e + 1];
      std::vector<double> s(n);
      for (int i = 0; i < n; ++i)
        s[i] = i == 0 ? a : i == n - 1 ? b : 0.5 * (a + b) + 0.5 * (b - a) * op.t[i];
      Element el{n, offset, 0.5 * (b - a), &op, std::move(s)};
      if (P_.has_actuators()) {
        el.mask = P_.active_mask(0.5 * (a + b));
        el.entry_after = e + 1 < elements && P_.has_entry(b);
      }
      elements_.push_back(std::move(el));
      offset += n;
      largest = std::max(largest, n);
    }
    nodes_ = nodes;
    total_nodes_ = offset;
    theta_scale_ << 1.0, 1.0, 1.0, L, L, L;
    charts_.resize(elements);
    std::vector<ChebyshevNewtonMatrix::Element> shape;
    for (const auto& el : elements_) shape.push_back({el.n, el.offset, &el.op->D});
    newton_matrix_.emplace(std::move(shape), extra_);
    linear_scratch_.resize(largest, 12);
    for (std::size_t k = 0, j = 0; k < P_.actuators().size(); ++k)
      extra_row_[k] = P_.actuators()[k].has_unknown() ? static_cast<int>(j++) : -1;
  }

  int size() const { return 12 * total_nodes_ + extra_; }
  int node_unknowns() const { return 12 * total_nodes_; }
  int elements() const { return static_cast<int>(elements_.size()); }
  StaticProblem& problem() { return P_; }
  ChebyshevNewtonMatrix& newton_matrix() { return *newton_matrix_; }

  /// The tip pose of x (sets the charts from x).
  SE3 tip_pose(const VectorXd& x) {
    update_charts(x);
    const Element& last = elements_.back();
    return charts_.back() * SE3::exp(theta(x.data() + 12 * (last.offset + last.n - 1)));
  }

  /// Reference configuration theta = (s - s_e) xi* and the undeformed rod's equilibrium wrench at
  /// the current load factor (the actuator forces are internal: only cables entering from
  /// outside appear in it, as jumps); extra unknowns at their initial guess (zero force,
  /// Delta = Delta*), which it also sets in the problem.
  VectorXd reference_guess() {
    std::vector<double> all;
    for (const auto& el : elements_) all.insert(all.end(), el.s.begin(), el.s.end());
    const auto Lambda = rigid_wrench_profile(P_, all, nodes_ - 1);  // ascending, with duplicates
    VectorXd x(size());
    set_initial_extras(x);
    for (std::size_t e = 0; e < elements_.size(); ++e) {
      const Element& el = elements_[e];
      const Vector6& xi_star = P_.model().xi_star(0.5 * (el.s.front() + el.s.back()));
      for (int i = 0; i < el.n; ++i) {
        double* xn = x.data() + 12 * (el.offset + i);
        node_theta(xn) = ((el.s[i] - el.s[0]) * xi_star).cwiseQuotient(theta_scale_);
        // The profile holds the value left of a breakpoint at both copies of an interface node;
        // the next element's first node is right of it, after a cable's entry.
        Vector6 La = Lambda[el.offset + i];
        if (i == 0 && e > 0 && elements_[e - 1].entry_after)
          La += P_.entry_jump(el.s[0], P_.model().xi_star(el.s[0] - 1e-12 * P_.length()));
        node_lambda(xn) = La.cwiseQuotient(P_.wrench_scale());
      }
    }
    return x;
  }

  /// Makes theta of a guess consistent with its Lambda: the theta rows (2.104) solved for theta
  /// with Lambda fixed, theta = S (L_e/2) dexp^-1_{-theta} xi(Lambda) per element (S:
  /// chebyshev_integration_matrix, theta_0 = 0), by kCompletionSweeps fixed-point sweeps. From the
  /// reference guess this bends the rod by the undeformed rod's equilibrium wrench, the
  /// linear-elastic deflection, and the first Newton matrix is evaluated near the solution (5
  /// iterations instead of 8 on the gravity cantilever). False, x unchanged, when a chart would
  /// turn by more than kCompletionRotation.
  bool complete_kinematics(VectorXd& x) {
    set_extras(x);
    using Block = Eigen::Matrix<double, Eigen::Dynamic, 12, Eigen::RowMajor>;
    VectorXd bent = x;
    Eigen::Matrix<double, Eigen::Dynamic, 6> rate;
    for (const auto& el : elements_) {
      Eigen::Map<Block> X(bent.data() + 12 * el.offset, el.n, 12);
      rate.setZero(el.n, 6);  // row 0: theta_0 = 0
      for (int sweep = 0; sweep < kCompletionSweeps; ++sweep) {
        for (int i = 1; i < el.n; ++i) {
          const double* xn = bent.data() + 12 * (el.offset + i);
          rate.row(i) = theta_rate(el, theta(xn), node_strain(el, i, lambda(xn))).transpose();
        }
        X.leftCols<6>() = el.op->integrate * rate;
      }
    }
    if (!(max_chart_rotation(bent) <= kCompletionRotation)) return false;
    x.swap(bent);
    return true;
  }

  /// Clamped tip: the constant twist xi_c = log(g_0^-1 g_target) / L that joins base and target
  /// (thesis 2.5), theta = (s - s_e) xi_c, Lambda = K (xi_c - xi*) (Kirchhoff: its moment part).
  /// Exact for a target at the end of a circular arc or helix.
  VectorXd constant_twist_guess() {
    const Vector6 xi = (P_.base().inverse() * P_.tip_target()).log() / P_.length();
    Vector6 Lambda = P_.rod_wrench(xi, 0.0);  // (with rest-strain spans: the first span's)
    if (P_.model().is_kirchhoff()) Lambda.tail<3>().setZero();
    VectorXd x(size());
    set_initial_extras(x);
    for (const auto& el : elements_)
      for (int i = 0; i < el.n; ++i) {
        double* xn = x.data() + 12 * (el.offset + i);
        node_theta(xn) = ((el.s[i] - el.s[0]) * xi).cwiseQuotient(theta_scale_);
        node_lambda(xn) = Lambda.cwiseQuotient(P_.wrench_scale());
      }
    return x;
  }

  /// F(x); false if a chart leaves its domain or something is not finite. With extra unknowns
  /// (set in the problem from x) F ends with their length rows (StaticProblem::extra_residuals),
  /// the path lengths by Clenshaw-Curtis quadrature on every element's nodes: spectral, as the
  /// collocation (the path length rate |u| is smooth inside each element).
  bool residual(const VectorXd& x, VectorXd& F) {
    check_deadline();  // the run's wall-time guard (common/deadline.hpp)
    set_extras(x);
    if (!update_charts(x)) return false;
    F.resize(size());
    Lengths lengths{};
    for (int e = 0; e < elements(); ++e) {
      const Element& el = elements_[e];
      for (int i = 0; i < el.n; ++i)
        local_rows(e, i, x.data(), F.data() + 12 * (el.offset + i), extra_ ? &lengths : nullptr);
      add_linear(e, x, F);
    }
    if (extra_) P_.extra_residuals(lengths, std::span<double>(F.data() + node_unknowns(), extra_));
    return F.allFinite();
  }

  /// The parts of the Newton matrix at x (chebyshev_newton_matrix.hpp): each node's block of
  /// its rows' derivatives with respect to its own unknowns (the D part is linear and known),
  /// and the chart blocks.
  void jacobian(const VectorXd& x) {
    set_extras(x);
    update_charts(x);
    ChebyshevNewtonMatrix& M = *newton_matrix_;
    VectorXd& xp = jacobian_scratch_;  // resized once: no allocation per Newton matrix
    xp = x;
    if (extra_) border(x, xp);
    for (int e = 0; e < elements(); ++e) {
      const Element& el = elements_[e];
      for (int i = 0; i < el.n; ++i) {
        if (i + 1 == el.n && e + 1 == elements()) differenced_block(e, i, x, xp, M.node_block(el.offset + i));
        else node_block(e, i, x.data() + 12 * (el.offset + i), M.node_block(el.offset + i));
      }
    }
    // Chart chain: the last theta of element e moves the charts of all later elements.
    for (int e = 0; e + 1 < elements(); ++e) {
      const Element& el = elements_[e];
      const int col = 12 * (el.offset + el.n - 1);
      for (int c = 0; c < 6; ++c) {
        const double h = kFdStep * std::max(1.0, std::abs(x[col + c]));
        xp[col + c] = x[col + c] + h;
        const auto plus = downstream_rows(e, xp);
        xp[col + c] = x[col + c] - h;
        const auto minus = downstream_rows(e, xp);
        xp[col + c] = x[col + c];
        M.chart_block(e).col(c) = (plus - minus) / (2.0 * h);
      }
    }
    update_charts(x);
  }

  /// Newton at the current load factor; x is updated in place (the last accepted iterate). With
  /// `reuse`, the first steps are chord steps with the factorisation the Newton matrix holds
  /// already (ChebyshevTracker: the one at the previous equilibrium), refreshed as usual when
  /// they stop contracting.
  NewtonOutcome newton(VectorXd& x, double tol, int max_iterations, int& factorizations,
                       bool reuse = false) {
    NewtonOutcome out;
    out.factorized = reuse;
    // Scratch kept across calls (a followed solve, ChebyshevTracker, calls this once per update).
    VectorXd &F = newton_scratch_[0], &x_new = newton_scratch_[1], &F_new = newton_scratch_[2],
             &dx = newton_scratch_[3], &next = newton_scratch_[4];
    if (!residual(x, F)) {
      out.reason = "the residual is not finite at the initial guess";
      out.residual_norm = std::numeric_limits<double>::infinity();
      return out;
    }
    ChebyshevNewtonMatrix& M = *newton_matrix_;
    Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod;
    bool use_cod = false;  // the Newton matrix is singular: minimum-norm least-squares steps
    // out = -J^-1 rhs.
    auto newton_step = [&](const VectorXd& rhs, VectorXd& out) {
      if (use_cod) out = cod.solve(rhs);
      else M.solve(rhs, out);
      out = -out;
    };
    bool have_lu = reuse, fresh = false, have_next = false, stalled = false;
    // Converged: |F| <= tol, or |F| at its rounding level and no longer decreasing.
    auto at_rounding_level = [&] { return out.residual_norm <= kRoundingFactor * rounding_level(x); };
    for (out.iterations = 0;; ++out.iterations) {
      out.residual_norm = F.lpNorm<Eigen::Infinity>();
      if (out.residual_norm <= tol || (stalled && at_rounding_level())) {
        out.converged = true;
        return out;
      }
      if (out.iterations == max_iterations) break;
      if (!have_lu) {
        jacobian(x);
        ++factorizations;
        out.factorized = true;
        // A singular matrix (e.g. the axial mode of a straight Kirchhoff rod with both ends
        // clamped, where the axial force is undetermined to first order) gets least-squares steps
        // with the full matrix.
        use_cod = !M.factorize(kSingularPivot);
        if (!use_cod) {
          newton_step(F, next);
          use_cod = !next.allFinite();
        }
        if (use_cod) {
          M.assemble(J_);
          cod.compute(J_);
          out.factorized = false;
        }
        have_lu = fresh = true;
        have_next = !use_cod;
      }
      if (have_next) dx.swap(next);
      else newton_step(F, dx);
      if (!dx.allFinite()) {
        out.reason = "singular Newton matrix";
        return out;
      }
      // Backtracking with the natural monotonicity test (Deuflhard): the residual scaled by the
      // current Newton matrix, i.e. the next simplified Newton step -J^-1 F(x + alpha dx), must be
      // shorter than (1 - alpha/4) |dx|. That step is then the next (chord) step.
      const double step = dx.norm();
      double alpha = 1.0;
      bool accepted = false;
      for (int k = 0; k < kMaxHalvings; ++k, alpha *= 0.5) {
        x_new = x + alpha * dx;
        if (!residual(x_new, F_new)) continue;
        newton_step(F_new, next);
        if (next.norm() <= (1.0 - 0.25 * alpha) * step) {
          accepted = true;
          break;
        }
      }
      if (!accepted) {
        if (at_rounding_level()) {
          out.converged = true;
          return out;
        }
        if (fresh) {
          out.reason = "line search failed (natural monotonicity test)";
          return out;
        }
        have_lu = false;  // a stale factorisation: refresh it at the same x
        continue;
      }
      const double ratio = F_new.norm() / F.norm();
      stalled = ratio > 0.5;
      x.swap(x_new);
      F.swap(F_new);
      fresh = false;
      have_next = true;
      if (ratio > kReuseRatio) have_lu = false;  // slow: a new Newton matrix at the new x
    }
    out.reason = rodlab::format("no convergence within {} Newton iterations", max_iterations);
    return out;
  }

  /// dF/du at x (ChebyshevTracker): the residual's derivative with respect to each actuator's
  /// input (ActuatorTerm::input), x held fixed. An input moves the residual through the axial
  /// force F_k (tension, -P A_c, the muscle law in q) and, for length control, the target length
  /// of its length row; dF_k/du_k and d target/du_k are central differences of those scalars
  /// (step steps[k]; exact for the linear laws). F_k enters the node rows only through the tendon
  /// law's strain: at fixed Lambda, dxi/dF_k = -(d law/d xi)^-1 c_k(xi) = -strain_jacobian c_k,
  /// and (2.104) is linear in xi through dexp^-1_{-theta}, (2.103)'s ad_xi^T Lambda linear in xi,
  /// the path lengths through d|u|/dxi (as in border()). One strain solve per node for all
  /// inputs, where differencing the residual would take 2 per node and input. The continuity row
  /// of a cable's entry (Lambda + F c(xi), rare) is differenced locally.
  void input_jacobian(const VectorXd& x, std::span<const double> steps, MatrixXd& Fu) {
    const int m = static_cast<int>(P_.actuators().size());
    const auto& actuators = P_.actuators();
    set_extras(x);
    update_charts(x);
    Fu.setZero(size(), m);
    std::array<double, StaticProblem::kMaxActuators> dF{};
    for (int k = 0; k < m; ++k) {
      const double u = actuators[k].input, h = steps[k];
      P_.set_actuator_input(k, u + h);
      const double Fp = P_.axial_force(k), Tp = actuators[k].target_length.value_or(0.0);
      P_.set_actuator_input(k, u - h);
      const double Fm = P_.axial_force(k), Tm = actuators[k].target_length.value_or(0.0);
      P_.set_actuator_input(k, u);
      dF[k] = (Fp - Fm) / (2.0 * h);
      if (extra_row_[k] >= 0 && actuators[k].target_length)  // extra_residuals: (length - target) / L
        Fu(node_unknowns() + extra_row_[k], k) -= P_.load_factor() * (Tp - Tm) / (2.0 * h) / P_.length();
    }
    const Vector6& ws = P_.wrench_scale();
    Eigen::Matrix<double, 12, 1> plus, minus;
    for (int e = 0; e < elements(); ++e) {
      const Element& el = elements_[e];
      for (int i = 0; i < el.n; ++i) {
        const int row = 12 * (el.offset + i);
        const bool entry_row = i + 1 == el.n && el.entry_after;
        if (entry_row) {  // Lambda + F c(xi(Lambda)): differenced (both terms move with F)
          for (int k = 0; k < m; ++k) {
            const double u = actuators[k].input, h = steps[k];
            P_.set_actuator_input(k, u + h);
            local_rows(e, i, x.data(), plus.data());
            P_.set_actuator_input(k, u - h);
            local_rows(e, i, x.data(), minus.data());
            P_.set_actuator_input(k, u);
            Fu.block<6, 1>(row + 6, k) = (plus.tail<6>() - minus.tail<6>()) / (2.0 * h);
          }
        }
        if (!el.mask) continue;
        const double* xn = x.data() + row;
        const Vector6 th = theta(xn), La = lambda(xn);
        const double s = probe(el, i);
        const Vector6 xi = P_.strain(La, s, el.mask);
        const lie::Matrix6 S = P_.strain_jacobian(xi, s, el.mask);
        const lie::Matrix6 A = i > 0 ? lie::se3::dexp_inv(-th) : lie::Matrix6::Zero();
        const double w = el.half * el.op->weights[i] / P_.length();
        for (int k = 0; k < m; ++k) {
          if (!((el.mask >> k) & 1U) || dF[k] == 0.0) continue;
          const Vector6 dxi = -dF[k] * (S * actuators[k].path.unit_wrench(s, xi));
          if (i > 0) Fu.block<6, 1>(row, k) = (-el.half * (A * dxi)).cwiseQuotient(theta_scale_);  // (2.104)
          if (i + 1 < el.n)  // (2.103)
            Fu.block<6, 1>(row + 6, k) = (-el.half * lie::se3::coad_apply(dxi, La)).cwiseQuotient(ws);
          for (int j = 0; j < m; ++j) {  // path lengths of the length-controlled actuators here
            if (!((el.mask >> j) & 1U) || extra_row_[j] < 0) continue;
            const Vector3 t = actuators[j].path.tangent_vector(s, xi).normalized();
            Eigen::Matrix<double, 1, 6> grad;  // d|u|/dxi
            grad << -(t.transpose() * lie::so3::hat(actuators[j].path.offset(s))), t.transpose();
            Fu(node_unknowns() + extra_row_[j], k) += w * grad.dot(dxi);
          }
        }
      }
    }
  }

  /// The assembled Newton matrix at x against central differences of the residual, column by
  /// column: max_c |J_c - J_fd,c|_inf / max(1, |J_fd,c|_inf).
  double newton_matrix_error(const VectorXd& x) {
    jacobian(x);
    MatrixXd J;
    newton_matrix_->assemble(J);
    VectorXd xp = x, Fp, Fm;
    double worst = 0.0;
    for (int c = 0; c < size(); ++c) {
      const double h = kFdStep * std::max(1.0, std::abs(x[c]));
      xp[c] = x[c] + h;
      residual(xp, Fp);
      xp[c] = x[c] - h;
      residual(xp, Fm);
      xp[c] = x[c];
      const VectorXd column = (Fp - Fm) / (2.0 * h);
      worst = std::max(worst, (J.col(c) - column).lpNorm<Eigen::Infinity>() /
                                  std::max(1.0, column.lpNorm<Eigen::Infinity>()));
    }
    residual(x, Fp);  // the problem's extra unknowns and the charts back at x
    return worst;
  }

  /// Rounding level of the residual at x: eps max_j sum_k |D_jk| |x_k| (the D rows dominate; it
  /// grows like N^2, so at large N a tight tol may lie below it).
  double rounding_level(const VectorXd& x) const {
    using Block = Eigen::Matrix<double, Eigen::Dynamic, 12, Eigen::RowMajor>;
    double level = 0.0;
    for (const auto& el : elements_) {
      const Eigen::Map<const Block> X(x.data() + 12 * el.offset, el.n, 12);
      level = std::max(level, (el.op->absD * X.cwiseAbs()).maxCoeff());
    }
    return std::numeric_limits<double>::epsilon() * level;
  }

  /// The unknowns of another layout's solution x_other on this layout: g and Lambda
  /// interpolated spectrally in the other's elements (an element's first node from the other's
  /// element to its right: Lambda jumps at a cable entry), theta = log(g_e^-1 g) in this
  /// layout's charts; the extra unknowns as they are.
  VectorXd resample(Collocation& other, const VectorXd& x_other) const {
    other.update_charts(x_other);
    VectorXd x(size());
    x.tail(extra_) = x_other.tail(extra_);
    for (const auto& el : elements_) {
      SE3 chart;
      for (int i = 0; i < el.n; ++i) {
        SE3 g;
        Vector6 La;
        other.sample(x_other, el.s[i], i == 0, g, La);
        if (i == 0) chart = g;
        double* xn = x.data() + 12 * (el.offset + i);
        const Vector6 th = i == 0 ? Vector6::Zero() : Vector6((chart.inverse() * g).log());
        node_theta(xn) = th.cwiseQuotient(theta_scale_);
        node_lambda(xn) = La.cwiseQuotient(P_.wrench_scale());
      }
    }
    return x;
  }

  /// The collocation residual between the nodes: (2.103)-(2.104) for the interpolants of theta
  /// and Lambda (and of D theta, D Lambda: the interpolants' derivatives) at the midpoints in
  /// angle of consecutive nodes of every element, scaled like the rows, inf-norm. Of the size of
  /// the discretisation error for a resolved solution; comparable to the solution itself for a
  /// spurious root of an under-resolved discretisation.
  double off_grid_residual(const VectorXd& x) {
    set_extras(x);
    update_charts(x);
    double worst = 0.0;
    using Block = Eigen::Matrix<double, Eigen::Dynamic, 12, Eigen::RowMajor>;
    for (int e = 0; e < elements(); ++e) {
      const Element& el = elements_[e];
      const int m = el.n - 1;
      const MatrixXd& C = el.op->midpoints;
      const Eigen::Map<const Block> X(x.data() + 12 * el.offset, el.n, 12);
      const Block values = C * X, slopes = C * (el.op->D * X);
      for (int j = 0; j < m; ++j) {
        const Vector6 th = Vector6(values.row(j).head<6>().transpose()).cwiseProduct(theta_scale_);
        const Vector6 La = Vector6(values.row(j).tail<6>().transpose()).cwiseProduct(P_.wrench_scale());
        const double s = el.s.front() + el.half * (1.0 + el.op->mid[j]);
        const Vector6 xi = P_.strain(La, s, el.mask);
        const SO3 R = charts_[e].rotation() * SO3::exp(th.head<3>());
        const Vector6 r_theta = Vector6(slopes.row(j).head<6>().transpose()) - theta_rate(el, th, xi);
        const Vector6 r_lambda = Vector6(slopes.row(j).tail<6>().transpose()) - lambda_rate(el, R, xi, La);
        worst = std::max({worst, r_theta.lpNorm<Eigen::Infinity>(), r_lambda.lpNorm<Eigen::Infinity>()});
      }
    }
    return worst;
  }

  /// Largest |omega(theta)| over all nodes: how far each chart turns.
  double max_chart_rotation(const VectorXd& x) const {
    double m = 0.0;
    for (int k = 0; k < total_nodes_; ++k) m = std::max(m, x.segment<3>(12 * k).norm());
    return m;
  }

  /// Node values of a solution, interface duplicates removed (the value right of an interface:
  /// after a cable's entry, as the other schemes report it); sets its extra unknowns in the problem.
  void nodes(const VectorXd& x, std::vector<double>& s, std::vector<SE3>& g, std::vector<Vector6>& Lambda) {
    set_extras(x);
    update_charts(x);
    s.clear();
    g.clear();
    Lambda.clear();
    for (int e = 0; e < elements(); ++e) {
      const Element& el = elements_[e];
      const int last = e + 1 < elements() ? el.n - 1 : el.n;
      for (int i = 0; i < last; ++i) {
        const double* xn = x.data() + 12 * (el.offset + i);
        s.push_back(el.s[i]);
        g.push_back(charts_[e] * SE3::exp(theta(xn)));
        Lambda.push_back(lambda(xn));
      }
    }
  }

 private:
  /// Where node i of an element evaluates the actuator paths and xi*: at its s, except the last
  /// node, just inside the element (a routing's r' and xi* jump at a breakpoint, and both give
  /// right limits).
  double probe(const Element& el, int i) const {
    return i + 1 < el.n ? el.s[i] : el.s[i] - 1e-12 * P_.length();
  }
  /// The strain at node i of an element: the tendon law with the element's actuators, the
  /// closed form xi* + K^-1 Lambda without.
  Vector6 node_strain(const Element& el, int i, const Vector6& La) const {
    return P_.strain(La, probe(el, i), el.mask);
  }
  /// The extra unknowns (the tail of x) into the problem.
  void set_extras(const VectorXd& x) {
    if (extra_) P_.set_extra_unknowns(std::span<const double>(x.data() + node_unknowns(), extra_));
  }
  /// Their initial guess into x and the problem.
  void set_initial_extras(VectorXd& x) {
    if (!extra_) return;
    const auto z = P_.extra_initial_guess();
    for (int j = 0; j < extra_; ++j) x[node_unknowns() + j] = z[j];
    set_extras(x);
  }

  static Eigen::Map<Vector6> node_theta(double* xn) { return Eigen::Map<Vector6>(xn); }
  static Eigen::Map<Vector6> node_lambda(double* xn) { return Eigen::Map<Vector6>(xn + 6); }
  Vector6 theta(const double* xn) const { return Eigen::Map<const Vector6>(xn).cwiseProduct(theta_scale_); }
  Vector6 lambda(const double* xn) const {
    return Eigen::Map<const Vector6>(xn + 6).cwiseProduct(P_.wrench_scale());
  }

  /// g and Lambda at arclength s by barycentric interpolation of theta and Lambda in the element
  /// that contains s, at an element boundary the one to its right if `right` (the charts must be
  /// those of x).
  void sample(const VectorXd& x, double s, bool right, SE3& g, Vector6& Lambda) const {
    std::size_t e = 0;
    while (e + 1 < elements_.size() && (right ? s >= elements_[e].s.back() : s > elements_[e].s.back())) ++e;
    const Element& el = elements_[e];
    Eigen::VectorXd t(1);
    t[0] = std::clamp((s - el.s.front()) / el.half - 1.0, -1.0, 1.0);
    const Eigen::RowVectorXd C = chebyshev_interpolation_matrix(el.n, t);
    Vector6 th = Vector6::Zero();
    Lambda.setZero();
    for (int i = 0; i < el.n; ++i) {
      th += C[i] * theta(x.data() + 12 * (el.offset + i));
      Lambda += C[i] * lambda(x.data() + 12 * (el.offset + i));
    }
    g = charts_[e] * SE3::exp(th);
  }

  /// Chart bases g_e from x; false if some chart turns past kChartLimit.
  bool update_charts(const VectorXd& x) { return update_charts_from(0, x); }
  bool update_charts_from(int first, const VectorXd& x) {
    if (first == 0) charts_[0] = P_.base();
    bool ok = true;
    for (int e = 0; e < elements(); ++e) {
      const Element& el = elements_[e];
      for (int i = 0; i < el.n; ++i)
        if (!(x.segment<3>(12 * (el.offset + i)).norm() < kChartLimit)) ok = false;
      if (e + 1 < elements() && e + 1 >= first)
        charts_[e + 1] = charts_[e] * SE3::exp(theta(x.data() + 12 * (el.offset + el.n - 1)));
    }
    return ok;
  }

  /// (2.104)'s right-hand side at a node, scaled like the theta rows: (L_e/2) dexp^-1_{-theta} xi.
  Vector6 theta_rate(const Element& el, const Vector6& th, const Vector6& xi) const {
    return (el.half * lie::se3::dexp_inv_apply(-th, xi)).cwiseQuotient(theta_scale_);
  }
  /// (2.103)'s right-hand side at a node, scaled like the Lambda rows: (L_e/2) (ad_xi^T Lambda - W_bar(R)).
  Vector6 lambda_rate(const Element& el, const SO3& R, const Vector6& xi, const Vector6& La) const {
    return (el.half * P_.wrench_derivative(R, xi, La)).cwiseQuotient(P_.wrench_scale());
  }

  /// The node block of node i of element e (not the tip) at its unknowns xn. The Lambda columns
  /// are exact: (2.104) depends on Lambda through xi(Lambda), with d/dxi = dexp^-1_{-theta} and
  /// dxi/dLambda = StaticProblem::strain_jacobian (K^-1 without actuators; with them the
  /// linearised tendon law, so that Newton stays quadratic); (2.103)'s ad_xi^T Lambda is bilinear
  /// in (xi, Lambda); a continuity row with a cable entry, Lambda + F c(xi(Lambda)), has
  /// I + F dc/dxi dxi/dLambda. The theta columns (dexp^-1 in theta, the loads through R) by
  /// central differences.
  void node_block(int e, int i, const double* xn, ChebyshevNewtonMatrix::Matrix12& G) const {
    const Element& el = elements_[e];
    const Vector6 th = theta(xn), La = lambda(xn), xi = node_strain(el, i, La);
    const Vector6& ws = P_.wrench_scale();
    // d xi / d (Lambda / wrench scale)
    const lie::Matrix6 slope = P_.strain_jacobian(xi, probe(el, i), el.mask) * ws.asDiagonal();
    auto step = [&](int c) { return kFdStep * std::max(1.0, std::abs(xn[c])); };
    G.setZero();
    if (i == 0) {
      G.topLeftCorner<6, 6>().setIdentity();  // theta_0 = 0
    } else {  // (2.104)
      G.block<6, 6>(0, 6) =
          (-el.half * theta_scale_.cwiseInverse()).asDiagonal() * (lie::se3::dexp_inv(-th) * slope);
      for (int c = 0; c < 6; ++c) {
        const double h = step(c);
        Vector6 plus = th, minus = th;
        plus[c] += h * theta_scale_[c];
        minus[c] -= h * theta_scale_[c];
        G.block<6, 1>(0, c) = (theta_rate(el, minus, xi) - theta_rate(el, plus, xi)) / (2.0 * h);
      }
    }
    if (i + 1 < el.n) {  // (2.103): -(L/2) (ad_xi^T Lambda - W_bar(R))
      for (int c = 0; c < 6; ++c) {
        const Vector6 d = ws[c] * lie::se3::coad_apply(xi, Vector6::Unit(c)) +
                          lie::se3::coad_apply(Vector6(slope.col(c)), La);
        G.block<6, 1>(6, 6 + c) = (-el.half * d).cwiseQuotient(ws);
      }
      const SO3 chart = charts_[e].rotation();
      for (int c = 0; c < 3; ++c) {
        const double h = step(c);
        Vector3 plus = th.head<3>(), minus = th.head<3>();
        plus[c] += h;
        minus[c] -= h;
        const Vector6 diff =
            P_.distributed_load(chart * SO3::exp(plus)) - P_.distributed_load(chart * SO3::exp(minus));
        G.block<6, 1>(6, c) = (el.half / (2.0 * h) * diff).cwiseQuotient(ws);
      }
    } else {  // continuity, with a cable entry: Lambda + F c(xi)
      G.bottomRightCorner<6, 6>().setIdentity();
      if (el.entry_after)
        G.bottomRightCorner<6, 6>() += ws.cwiseInverse().asDiagonal() *
                                       (P_.entry_jump_jacobian(el.s.back(), xi) * slope);
    }
  }

  /// The node block by central differences of local_rows (xp: a copy of x, restored on return).
  void differenced_block(int e, int i, const VectorXd& x, VectorXd& xp,
                         ChebyshevNewtonMatrix::Matrix12& G) const {
    const int base = 12 * (elements_[e].offset + i);
    Eigen::Matrix<double, 12, 1> Fp, Fm;
    for (int c = 0; c < 12; ++c) {
      const double h = kFdStep * std::max(1.0, std::abs(x[base + c]));
      xp[base + c] = x[base + c] + h;
      local_rows(e, i, xp.data(), Fp.data());
      xp[base + c] = x[base + c] - h;
      local_rows(e, i, xp.data(), Fm.data());
      xp[base + c] = x[base + c];
      G.col(c) = (Fp - Fm) / (2.0 * h);
    }
  }

  /// The rows of node i of element e that depend on the node's own unknowns (and the chart);
  /// with `lengths`, adds the node's Clenshaw-Curtis share of each active path's length
  /// (weight (L_e/2) w_i times |u|; (2.47), (2.53), (2.66)).
  void local_rows(int e, int i, const double* x, double* out, Lengths* lengths = nullptr) const {
    const Element& el = elements_[e];
    const double* xn = x + 12 * (el.offset + i);
    const Vector6 th = theta(xn), La = lambda(xn);
    const Vector6 xi = node_strain(el, i, La);
    Eigen::Map<Vector6> theta_row(out), lambda_row(out + 6);
    if (i == 0) {
      theta_row = Eigen::Map<const Vector6>(xn);  // theta_0 = 0
    } else {  // (2.104)
      theta_row = -theta_rate(el, th, xi);
    }
    if (i < el.n - 1) {  // (2.103)
      const SO3 R = charts_[e].rotation() * SO3::exp(th.head<3>());
      lambda_row = -lambda_rate(el, R, xi, La);
    } else if (e + 1 < elements()) {  // continuity; the next element's part is linear
      lambda_row = Eigen::Map<const Vector6>(xn + 6);
      // A cable entering at the element's end adds its pull: Lambda(b+) = Lambda(b-) + F c(xi(b-)).
      if (el.entry_after) lambda_row += P_.entry_jump(el.s.back(), xi).cwiseQuotient(P_.wrench_scale());
    } else {
      lambda_row = P_.tip_residual(charts_[e] * SE3::exp(th), La);
    }
    if (lengths && el.mask) {
      const double w = el.half * el.op->weights[i], s = probe(el, i);
      for (std::size_t k = 0; k < P_.actuators().size(); ++k)
        if ((el.mask >> k) & 1U) (*lengths)[k] += w * P_.actuators()[k].path.length_rate(s, xi);
    }
  }

  /// The border of the Newton matrix (extra unknowns z): the columns dF/dz (node rows and
  /// length rows) by central differences of the residual, and the length rows' derivatives with
  /// respect to each node's Lambda in closed form, d|u|/dxi = t^T [-hat(r), I] (u = nu + omega x
  /// r + r', (2.39)) times dxi/dLambda; the lengths do not depend on theta. xp: a copy of x,
  /// restored on return, as are the problem's extra unknowns and the charts.
  void border(const VectorXd& x, VectorXd& xp) {
    ChebyshevNewtonMatrix& M = *newton_matrix_;
    const int n = node_unknowns();
    VectorXd Fp(size()), Fm(size());
    for (int j = 0; j < extra_; ++j) {
      const int col = n + j;
      const double h = kFdStep * std::max(1.0, std::abs(x[col]));
      xp[col] = x[col] + h;
      residual(xp, Fp);
      xp[col] = x[col] - h;
      residual(xp, Fm);
      xp[col] = x[col];
      M.border_columns().col(j) = (Fp.head(n) - Fm.head(n)) / (2.0 * h);
      M.border_corner().col(j) = (Fp.tail(extra_) - Fm.tail(extra_)) / (2.0 * h);
    }
    set_extras(x);
    update_charts(x);
    auto& C = M.border_rows();
    C.setZero();
    const Vector6& ws = P_.wrench_scale();
    const auto& actuators = P_.actuators();
    for (const Element& el : elements_) {
      if (!el.mask) continue;
      for (int i = 0; i < el.n; ++i) {
        const double* xn = x.data() + 12 * (el.offset + i);
        const double s = probe(el, i), w = el.half * el.op->weights[i] / P_.length();
        const Vector6 xi = node_strain(el, i, lambda(xn));
        const lie::Matrix6 slope = P_.strain_jacobian(xi, s, el.mask) * ws.asDiagonal();
        for (std::size_t k = 0; k < actuators.size(); ++k) {
          if (!((el.mask >> k) & 1U) || extra_row_[k] < 0) continue;
          const Vector3 t = actuators[k].path.tangent_vector(s, xi).normalized();
          Eigen::Matrix<double, 1, 6> grad;  // d|u|/dxi
          grad << -(t.transpose() * lie::so3::hat(actuators[k].path.offset(s))), t.transpose();
          C.row(extra_row_[k]).segment<6>(12 * (el.offset + i) + 6) += w * grad * slope;
        }
      }
    }
  }

  /// D theta, D Lambda and the continuity coupling of element e, added to F.
  void add_linear(int e, const VectorXd& x, VectorXd& F) {
    const Element& el = elements_[e];
    using Block = Eigen::Matrix<double, Eigen::Dynamic, 12, Eigen::RowMajor>;
    const Eigen::Map<const Block> X(x.data() + 12 * el.offset, el.n, 12);
    Eigen::Map<Block> Y(F.data() + 12 * el.offset, el.n, 12);
    auto DX = linear_scratch_.topRows(el.n);
    DX.noalias() = el.op->D * X;
    Y.bottomLeftCorner(el.n - 1, 6) += DX.bottomLeftCorner(el.n - 1, 6);
    Y.topRightCorner(el.n - 1, 6) += DX.topRightCorner(el.n - 1, 6);
    if (e + 1 < elements())
      F.segment<6>(12 * (el.offset + el.n - 1) + 6) -= x.segment<6>(12 * elements_[e + 1].offset + 6);
  }

  /// Local rows of every node after element e, with the charts recomputed from x.
  VectorXd downstream_rows(int e, const VectorXd& x) {
    update_charts_from(e + 1, x);
    const int first = elements_[e + 1].offset;
    VectorXd out(12 * (total_nodes_ - first));
    for (int f = e + 1; f < elements(); ++f) {
      const Element& el = elements_[f];
      for (int i = 0; i < el.n; ++i) local_rows(f, i, x.data(), out.data() + 12 * (el.offset + i - first));
    }
    return out;
  }

  StaticProblem P_;
  int extra_ = 0;                                        ///< extra unknowns (after the nodes' in x)
  std::array<int, StaticProblem::kMaxActuators> extra_row_{};  ///< per actuator: its extra row, or -1
  std::optional<ChebyshevNewtonMatrix> newton_matrix_;
  MatrixXd J_;  ///< the full Newton matrix, only when it is singular (least-squares steps)
  Eigen::Matrix<double, Eigen::Dynamic, 12, Eigen::RowMajor> linear_scratch_;  ///< D X of one element
  std::vector<Element> elements_;
  std::vector<SE3> charts_;
  int total_nodes_ = 0, nodes_ = 0;
  Vector6 theta_scale_;
  std::array<VectorXd, 5> newton_scratch_;  ///< newton(): F, x_new, F_new, dx, next
  VectorXd jacobian_scratch_;               ///< jacobian(): the perturbed copy of x
};

struct Attempt {
  bool converged = false;
  VectorXd x;
  double residual_norm = 0.0;
  double rotation = 0.0;
  std::string reason;
};

/// The collocation and the unknowns of a finished solve, for ChebyshevTracker.
struct KeptSolution {
  std::optional<Collocation> collocation;
  VectorXd x;
};

class ChebyshevSolver {
 public:
  ChebyshevSolver(const StaticProblem& problem, const ChebyshevOptions& options)
      : P_(problem), options_(options) {}

  /// With `kept`, the returned solution's collocation and unknowns are moved there.
  result::StaticResult run(ChebyshevReport* report, KeptSolution* kept = nullptr) {
    const int N = options_.nodes;
    int E = options_.elements > 0 ? options_.elements : 1;
    const bool automatic = options_.elements <= 0;
    // Splits keep elements of at least kMinElementNodes nodes on average; when that allows no
    // split and the attempt failed, down to kMinFallbackNodes (small N, e.g. a full circle with
    // N = 5). (With actuators the breakpoints' elements are there at every level.)
    auto can_split = [&](int min_nodes) { return element_count(P_, 2 * E) * (min_nodes - 1) <= N - 1; };
    std::optional<Collocation> best;
    Attempt best_attempt;
    std::string reasons;
    for (;;) {
      Collocation C(P_, N, E);
      const bool refining = best && best_attempt.converged;
      Attempt a = refining ? refine(C, *best, best_attempt.x)
                           : attempt(C, automatic && can_split(kMinElementNodes));
      if (refining && !a.converged) break;  // keep the converged coarser solution
      const bool split = automatic && a.rotation > kSplitRotation &&
                         can_split(a.converged ? kMinElementNodes : kMinFallbackNodes);
      if (a.converged) {
        best.emplace(std::move(C));
        best_attempt = std::move(a);
        if (!split) break;
      } else {
        if (!reasons.empty()) reasons += "; ";
        reasons +=
            rodlab::format("{} {}: ", C.elements(), C.elements() == 1 ? "element" : "elements");
        reasons += a.reason;
        if (!best) {
          best.emplace(std::move(C));
          best_attempt = std::move(a);
        }
        if (!split) break;
      }
      E *= 2;
    }
    Collocation& C = *best;
    C.problem().set_load_factor(1.0);
    if (best_attempt.converged) {
      // A root of the discrete equations whose polynomials violate the rod equations between the
      // nodes by as much as the solution's own size is a spurious root of an under-resolved
      // discretisation (e.g. a Kirchhoff rod "reaching" a target beyond its length), not a
      // solution.
      const double defect = C.off_grid_residual(best_attempt.x);
      const double size = std::max(1.0, best_attempt.x.lpNorm<Eigen::Infinity>());
      if (!(defect <= kResolvedDefect * size)) {
        best_attempt.converged = false;
        reasons = rodlab::format(
            "not resolved: the collocation residual between the nodes is {:g} times the "
            "solution's size (a spurious root of the discrete equations); increase nodes",
            defect / size);
      }
    }
    std::vector<double> s;
    std::vector<SE3> g;
    std::vector<Vector6> Lambda;
    C.nodes(best_attempt.x, s, g, Lambda);
    result::StaticResult out;
    fill_static_result(C.problem(), s, g, Lambda, out);
    out.scene = P_.name();
    out.converged = best_attempt.converged;
    out.reason = best_attempt.converged ? "" : reasons;
    out.iterations = iterations_;
    out.residual_norm = best_attempt.residual_norm;
    check_cables_taut(C.problem(), out);
    if (report) {
      report->elements = C.elements();
      report->factorizations = factorizations_;
      report->max_chart_rotation = C.max_chart_rotation(best_attempt.x);
    }
    if (kept) {
      kept->collocation.emplace(std::move(C));
      kept->x = std::move(best_attempt.x);
    }
    return out;
  }

 private:
  /// Newton at load factor 1 from a converged solution on fewer elements, resampled.
  Attempt refine(Collocation& C, Collocation& coarse, const VectorXd& x_coarse) {
    Attempt a;
    C.problem().set_load_factor(1.0);
    a.x = C.resample(coarse, x_coarse);
    const auto r = C.newton(a.x, options_.tol, options_.max_iterations, factorizations_);
    iterations_ += r.iterations;
    a.converged = r.converged;
    a.residual_norm = r.residual_norm;
    a.rotation = C.max_chart_rotation(a.x);
    a.reason = r.reason;
    return a;
  }

  /// Direct Newton at load factor 1 from the reference guess, then continuation. With
  /// `may_split`, a failed direct solve whose iterate turns a chart by more than kSplitRotation
  /// returns at once (more elements will be tried), and so does continuation on reaching such a
  /// rotation.
  Attempt attempt(Collocation& C, bool may_split) {
    int budget = kBudgetFactor * options_.max_iterations;
    auto solve_at = [&](double lf, VectorXd& x) {
      C.problem().set_load_factor(lf);
      const auto r = C.newton(x, options_.tol, std::min(options_.max_iterations, budget), factorizations_);
      iterations_ += r.iterations;
      budget -= r.iterations;
      return r;
    };
    Attempt a;
    C.problem().set_load_factor(1.0);
    a.x = C.reference_guess();
    C.complete_kinematics(a.x);
    auto direct = solve_at(1.0, a.x);
    a.rotation = C.max_chart_rotation(a.x);
    if (!direct.converged && !(may_split && a.rotation > kSplitRotation) && P_.tip_clamped()) {
      VectorXd x = C.constant_twist_guess();  // a second guess for a clamped tip
      const auto second = solve_at(1.0, x);
      if (second.converged || second.residual_norm < direct.residual_norm) {
        direct = second;
        a.x = std::move(x);
        a.rotation = C.max_chart_rotation(a.x);
      }
    }
    a.converged = direct.converged;
    a.residual_norm = direct.residual_norm;
    if (direct.converged || (may_split && a.rotation > kSplitRotation)) {
      a.reason = direct.reason;
      return a;
    }
    Continuation walk;
    walk.correct = [&](double lf, const VectorXd& guess) {
      CorrectorResult r;
      if (budget <= 0) {
        r.reason = rodlab::format("the budget of {} Newton iterations is spent",
                                  kBudgetFactor * options_.max_iterations);
        return r;
      }
      r.state = guess;
      const auto n = solve_at(lf, r.state);
      r.converged = n.converged;
      r.residual_norm = n.residual_norm;
      r.reason = n.reason;
      return r;
    };
    walk.first_predictor = [&](double from, double to, const VectorXd& state) {
      C.problem().set_load_factor(to);
      VectorXd predicted = state + C.reference_guess();
      C.problem().set_load_factor(from);
      return VectorXd(predicted - C.reference_guess());
    };
    if (may_split)
      walk.stop = [&](double lf, const VectorXd& state, std::string& why) {
        if (C.max_chart_rotation(state) <= kSplitRotation) return false;
        why = rodlab::format("a chart turns by more than 2 pi / 3 at load factor {:g}", lf);
        return true;
      };
    C.problem().set_load_factor(0.0);
    const auto cont = continue_load(walk, C.reference_guess());
    if (cont.converged) {
      a.x = cont.state;
      a.converged = true;
      a.residual_norm = cont.residual_norm;
      a.rotation = C.max_chart_rotation(a.x);
      a.reason.clear();
    } else {
      a.reason = "direct Newton: " + direct.reason + "; continuation: " + cont.reason;
      a.rotation = std::max(a.rotation, C.max_chart_rotation(cont.state));
    }
    C.problem().set_load_factor(1.0);
    return a;
  }

  StaticProblem P_;
  ChebyshevOptions options_;
  int iterations_ = 0;
  int factorizations_ = 0;
};

}  // namespace

namespace {

/// Bad options: std::invalid_argument.
void check_options(const StaticProblem& problem, const ChebyshevOptions& options) {
  if (options.nodes < 2) throw std::invalid_argument("chebyshev needs nodes >= 2");
  const int elements = element_count(problem, std::max(1, options.elements));
  if (elements > std::max(1, options.nodes - 1)) {
    const auto breakpoints = problem.breakpoints().size();
    throw std::invalid_argument(rodlab::format(
        "chebyshev: {} elements{} need at least {} nodes, got {}", elements,
        breakpoints > 0
            ? rodlab::format(" (one or more per stretch between the {} actuator breakpoints)",
                             breakpoints)
            : std::string(),
        elements + 1, options.nodes));
  }
}

}  // namespace

double chebyshev_newton_matrix_error(const StaticProblem& problem, const ChebyshevOptions& options) {
  check_options(problem, options);
  Collocation C(problem, options.nodes, std::max(1, options.elements));
  VectorXd x = C.reference_guess();
  C.complete_kinematics(x);
  int factorizations = 0;
  C.newton(x, options.tol, options.max_iterations, factorizations);
  return C.newton_matrix_error(x);
}

result::StaticResult solve_chebyshev(const StaticProblem& problem, const ChebyshevOptions& options,
                                     ChebyshevReport* report) {
  check_options(problem, options);
  return ChebyshevSolver(problem, options).run(report);
}

// --- ChebyshevTracker (chebyshev_tracker.hpp) ------------------------------------------------

struct ChebyshevTracker::Impl {
  Impl(const StaticProblem& p, const ChebyshevOptions& o) : problem(p), options(o) {}

  StaticProblem problem;  ///< the inputs of the last solve (for full solves)
  ChebyshevOptions options;
  KeptSolution kept;      ///< the collocation and the last converged x (if any)
  bool have_solution = false;
  Eigen::VectorXd u_solved;   ///< the inputs of kept.x
  Eigen::MatrixXd dxdu;       ///< dx/du at an earlier solution, for the predictor (or empty)
  bool factorized = false;    ///< the kept Newton matrix holds a valid factorisation
  std::string reason;
  int iterations = 0;
  bool warm = false;
  Vector3 tip = Vector3::Zero();
  Eigen::VectorXd x_trial, F_plus, column, dx;  ///< scratch
  Eigen::MatrixXd Fu;                           ///< dF/du
  TipJacobian J_scratch;

  void set_inputs(StaticProblem& P, std::span<const double> u) {
    for (std::size_t k = 0; k < u.size(); ++k) P.set_actuator_input(static_cast<int>(k), u[k]);
  }

  /// Newton from the kept equilibrium (with the predictor); false if it fails.
  bool warm_solve(const Eigen::Map<const Eigen::VectorXd>& u) {
    Collocation& C = *kept.collocation;
    set_inputs(C.problem(), std::span<const double>(u.data(), u.size()));
    C.problem().set_load_factor(1.0);
    x_trial = kept.x;
    if (dxdu.cols() == u.size() && dxdu.rows() == x_trial.size()) x_trial.noalias() += dxdu * (u - u_solved);
    int factorizations = 0;
    const auto r = C.newton(x_trial, options.tol, options.max_iterations, factorizations, factorized);
    iterations = r.iterations;
    factorized = r.factorized;
    if (!r.converged || !(C.max_chart_rotation(x_trial) <= kSplitRotation)) return false;
    kept.x.swap(x_trial);
    return true;
  }

  bool solve(std::span<const double> inputs) {
    RODLAB_THROW_UNLESS(inputs.size() == problem.actuators().size(),
                        "chebyshev tracker: expected {} inputs, got {}", problem.actuators().size(),
                        inputs.size());
    const Eigen::Map<const Eigen::VectorXd> u(inputs.data(), static_cast<Eigen::Index>(inputs.size()));
    reason.clear();
    warm = have_solution && warm_solve(u);
    if (!warm) {
      set_inputs(problem, inputs);
      KeptSolution fresh;
      auto r = ChebyshevSolver(problem, options).run(nullptr, &fresh);
      iterations += r.iterations;
      if (!r.converged) {
        reason = r.reason;
        factorized = false;  // the kept collocation's matrix was used by the failed warm attempt
        return false;
      }
      kept = std::move(fresh);
      dxdu.resize(0, 0);
      factorized = false;
    }
    have_solution = true;
    u_solved = u;
    tip = kept.collocation->tip_pose(kept.x).translation();
    return true;
  }

  bool tip_jacobian(std::span<const double> steps, TipJacobian& J) {
    RODLAB_THROW_UNLESS(have_solution, "chebyshev tracker: no converged solution yet");
    RODLAB_THROW_UNLESS(steps.size() == static_cast<std::size_t>(u_solved.size()),
                        "chebyshev tracker: expected {} steps, got {}", u_solved.size(), steps.size());
    Collocation& C = *kept.collocation;
    StaticProblem& P = C.problem();
    const Eigen::VectorXd& x = kept.x;
    const int m = static_cast<int>(u_solved.size());
    set_inputs(P, std::span<const double>(u_solved.data(), m));
    C.jacobian(x);  // F_x at the solution
    ChebyshevNewtonMatrix& M = C.newton_matrix();
    factorized = M.factorize(kSingularPivot);
    if (!factorized) return false;
    dxdu.resize(x.size(), m);
    TipJacobian& out = J_scratch;
    out.resize(3, m);
    C.input_jacobian(x, steps, Fu);
    for (int k = 0; k < m; ++k) {
      column = Fu.col(k);
      M.solve(column, dx);  // dx/du_k = -F_x^-1 F_u,k
      dxdu.col(k) = -dx;
      // d p_tip / d x along dx/du_k, central: t |dx/du_k| ~ 1e-6 of the unknowns' O(1) scale.
      const double t = 1e-6 / std::max(1e-300, dx.lpNorm<Eigen::Infinity>());
      x_trial = x - t * dx;
      const Vector3 plus = C.tip_pose(x_trial).translation();
      x_trial = x + t * dx;
      const Vector3 minus = C.tip_pose(x_trial).translation();
      out.col(k) = (plus - minus) / (2.0 * t);
    }
    C.residual(x, F_plus);  // the charts and extra unknowns back at x
    J = out;
    return J.allFinite();
  }
};

ChebyshevTracker::ChebyshevTracker(const StaticProblem& problem, const ChebyshevOptions& options)
    : impl_(std::make_unique<Impl>(problem, options)) {
  check_options(problem, options);
}
ChebyshevTracker::~ChebyshevTracker() = default;
ChebyshevTracker::ChebyshevTracker(ChebyshevTracker&&) noexcept = default;
ChebyshevTracker& ChebyshevTracker::operator=(ChebyshevTracker&&) noexcept = default;

int ChebyshevTracker::inputs() const { return static_cast<int>(impl_->problem.actuators().size()); }
bool ChebyshevTracker::solve(std::span<const double> inputs) {
  impl_->iterations = 0;
  return impl_->solve(inputs);
}
const std::string& ChebyshevTracker::reason() const { return impl_->reason; }
int ChebyshevTracker::iterations() const { return impl_->iterations; }
bool ChebyshevTracker::warm() const { return impl_->warm; }
const Vector3& ChebyshevTracker::tip_position() const { return impl_->tip; }
bool ChebyshevTracker::tip_jacobian(std::span<const double> steps, TipJacobian& J) {
  return impl_->tip_jacobian(steps, J);
}

result::StaticResult ChebyshevTracker::result() const {
  RODLAB_THROW_UNLESS(impl_->have_solution, "chebyshev tracker: no converged solution yet");
  Collocation& C = *impl_->kept.collocation;
  impl_->set_inputs(C.problem(), std::span<const double>(impl_->u_solved.data(), impl_->u_solved.size()));
  std::vector<double> s;
  std::vector<SE3> g;
  std::vector<Vector6> Lambda;
  C.nodes(impl_->kept.x, s, g, Lambda);
  result::StaticResult out;
  fill_static_result(C.problem(), s, g, Lambda, out);
  out.scene = impl_->problem.name();
  out.scheme = "chebyshev";
  out.nodes = impl_->options.nodes;
  out.converged = true;
  out.iterations = impl_->iterations;
  check_cables_taut(C.problem(), out);
  return out;
}

}  // namespace rodlab::solvers::statics
