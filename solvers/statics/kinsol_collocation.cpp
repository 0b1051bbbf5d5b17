#include "rodlab/solvers/statics/kinsol_collocation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "rodlab/solvers/common/kinsol_solver.hpp"
#include "rodlab/solvers/statics/continuation.hpp"
#include "rodlab/solvers/statics/result_builder.hpp"

namespace rodlab::solvers::statics {
namespace {

using Eigen::VectorXd;
using Quaternion = Eigen::Quaterniond;
using State = Eigen::Matrix<double, 13, 1>;  // scaled unknowns of a node: (q_w, q_x, q_y, q_z, p/L, Lambda/scale)
using Rows = Eigen::Matrix<double, 13, 1>;   // rows of an interval: pose (6), wrench (6), |q|^2 - 1
using ConstRef = Eigen::Ref<const VectorXd>;
using Ref = Eigen::Ref<VectorXd>;
using Sparse = KinsolSolver::SparseMatrix;

constexpr int kState = 13;
constexpr int kBaseRows = 7;
constexpr int kTipRows = 6;

/// What the interval rows need of a node, computed once per node and evaluation.
struct NodeData {
  Quaternion q;       // the unknown quaternion (norm enforced by a row)
  SO3 R;              // rotation of q / |q|
  Vector3 p;
  Vector6 Lambda, xi, dLambda;  // xi = strain(Lambda), dLambda = (2.34)
};

class Collocation {
 public:
  Collocation(const StaticProblem& problem, int nodes)
      : P_(problem), N_(nodes), L_(problem.length()), h_(L_ / (nodes - 1)), node_(nodes),
        rows_(nodes - 1) {
    scale_.head<4>().setOnes();
    scale_.segment<3>(4).setConstant(L_);
    scale_.tail<6>() = P_.wrench_scale();
  }

  StaticProblem& problem() { return P_; }
  const StaticProblem& problem() const { return P_; }
  int nodes() const { return N_; }
  int size() const { return kState * N_; }

  /// Node i's data from the scaled unknowns x.
  NodeData node(const ConstRef& x, int i) const { return node_from(x.segment<kState>(kState * i)); }

  NodeData node_from(const State& xi_scaled) const {
    NodeData n;
    n.q = Quaternion(xi_scaled[0], xi_scaled[1], xi_scaled[2], xi_scaled[3]);
    n.R = SO3::from_quaternion(n.q);
    n.p = L_ * xi_scaled.segment<3>(4);
    n.Lambda = xi_scaled.tail<6>().cwiseProduct(scale_.tail<6>());
    n.xi = P_.strain(n.Lambda);
    n.dLambda = P_.wrench_derivative(n.R, n.xi, n.Lambda);  // (2.34)
    return n;
  }

  /// The 13 scaled rows of the interval from node a to node b (see the header):
  /// Hermite-Simpson (Lobatto IIIA) on the chart ODE Theta' = dexp^-1_{-Theta} xi (2.84),
  /// Lambda' = ad_xi^T Lambda - W_bar(R_a exp(Theta)), Theta(0) = 0, Theta(h) = log(g_a^-1 g_b).
  Rows interval(const NodeData& a, const NodeData& b) const {
    const SO3 R_ab = a.R.inverse() * b.R;
    const Vector3 phi = R_ab.log();
    Vector6 Theta;
    Theta << phi, lie::so3::dexp_inv_apply(phi, a.R.inverse() * Vector3(b.p - a.p));
    const Vector6 F_a = a.xi;  // dexp^-1_0 = I
    const Vector6 F_b = lie::se3::dexp_inv_apply(-Theta, b.xi);
    // Midpoint stage from the cubic Hermite interpolants (compressed form).
    const Vector6 Theta_m = 0.5 * Theta + (h_ / 8.0) * (F_a - F_b);
    const Vector6 Lambda_m = 0.5 * (a.Lambda + b.Lambda) + (h_ / 8.0) * (a.dLambda - b.dLambda);
    const Vector6 xi_m = P_.strain(Lambda_m);
    const SO3 R_m = a.R * SO3::exp(Theta_m.head<3>());
    const Vector6 F_m = lie::se3::dexp_inv_apply(-Theta_m, xi_m);
    const Vector6 dLambda_m = P_.wrench_derivative(R_m, xi_m, Lambda_m);
    const Vector6 pose = Theta - (h_ / 6.0) * (F_a + 4.0 * F_m + F_b);
    const Vector6 wrench = (b.Lambda - a.Lambda) - (h_ / 6.0) * (a.dLambda + 4.0 * dLambda_m + b.dLambda);
    Rows r;
    r.head<3>() = (L_ / h_) * pose.head<3>();     // rad per unit s/L
    r.segment<3>(3) = pose.tail<3>() / h_;         // m per m
    r.segment<6>(6) = (L_ / h_) * wrench.cwiseQuotient(scale_.tail<6>());
    r[12] = b.q.squaredNorm() - 1.0;
    return r;
  }

  /// Tip rows (see the header).
  Vector6 tip_rows(const NodeData& n) const {
    if (P_.tip_clamped()) {
      const SE3 target = P_.tip_target();
      const Quaternion e = target.rotation().quaternion().conjugate() * n.R.quaternion();
      return lie::se3::join(2.0 * e.vec(), (n.p - target.translation()) / L_);
    }
    return P_.tip_residual(SE3(n.R, n.p), n.Lambda);
  }

  void residual(const ConstRef& x, Ref F) {
    for (int i = 0; i < N_; ++i) node_[i] = node(x, i);
    base_rows(x, F);
    for (int i = 0; i + 1 < N_; ++i) F.segment<kState>(kBaseRows + kState * i) = interval(node_[i], node_[i + 1]);
    F.tail<kTipRows>() = tip_rows(node_[N_ - 1]);
  }

  /// Block-bidiagonal pattern: the columns of node j have the rows [first_row(j), last_row(j)].
  Sparse pattern() const {
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(static_cast<std::size_t>(kState) * kState * 2 * N_ + kState * (kBaseRows + kTipRows));
    for (int j = 0; j < N_; ++j)
      for (int c = kState * j; c < kState * (j + 1); ++c)
        for (int r = first_row(j); r <= last_row(j); ++r) t.emplace_back(r, c, 1.0);
    Sparse J(size(), size());
    J.setFromTriplets(t.begin(), t.end());
    J.makeCompressed();
    return J;
  }

  /// Forward differences node by node: a column of node j re-evaluates node j's data and the
  /// (at most two) intervals, base or tip rows it enters; the base rows are exact.
  void jacobian(const ConstRef& x, Sparse& J) {
    for (int i = 0; i < N_; ++i) node_[i] = node(x, i);
    for (int i = 0; i + 1 < N_; ++i) rows_[i] = interval(node_[i], node_[i + 1]);
    const Vector6 tip0 = tip_rows(node_[N_ - 1]);
    double* values = J.valuePtr();
    const int* outer = J.outerIndexPtr();
    for (int j = 0; j < N_; ++j) {
      const State xj = x.segment<kState>(kState * j);
      for (int k = 0; k < kState; ++k) {
        const int column = kState * j + k;
        double* v = values + outer[column];  // this column's rows, contiguous from first_row(j)
        State xp = xj;
        xp[k] += kFdStep * std::max(1.0, std::abs(xj[k]));
        const double step = xp[k] - xj[k];  // the step actually taken
        const NodeData np = node_from(xp);
        if (j == 0)
          for (int r = 0; r < kBaseRows; ++r) *v++ = r == k ? 1.0 : 0.0;
        if (j >= 1) {  // interval j-1: node j is its right end
          const Rows d = (interval(node_[j - 1], np) - rows_[j - 1]) / step;
          for (int r = 0; r < kState; ++r) *v++ = d[r];
        }
        if (j + 1 < N_) {  // interval j: node j is its left end
          const Rows d = (interval(np, node_[j + 1]) - rows_[j]) / step;
          for (int r = 0; r < kState; ++r) *v++ = d[r];
        }
        if (j == N_ - 1) {
          const Vector6 d = (tip_rows(np) - tip0) / step;
          for (int r = 0; r < kTipRows; ++r) *v++ = d[r];
        }
      }
    }
  }

  /// The reference configuration g(s) = base exp(s xi*) with, for a free tip, the undeformed
  /// rod's equilibrium wrench ((2.34) marched back from the tip with RK4 along it); zero wrench
  /// for a clamped tip (its reaction is unknown; zero keeps the pose rows exact). Scaled unknowns.
  VectorXd reference_guess() const {
    const Vector6& xi_star = P_.model().xi_star();
    const SE3& base = P_.base();
    auto rotation_at = [&](double s) { return base.rotation() * SO3::exp(s * Vector3(xi_star.head<3>())); };
    auto dLambda = [&](double s, const Vector6& Lambda) {
      return P_.wrench_derivative(rotation_at(s), xi_star, Lambda);
    };
    const bool march = !P_.tip_clamped();
    Vector6 Lambda = march ? P_.tip_load(rotation_at(L_)) : Vector6::Zero();
    VectorXd x(size());
    for (int i = N_ - 1; i >= 0; --i) {
      const double s = i * h_;
      if (march && i < N_ - 1) {  // classical RK4 from s + h back to s
        const double sb = s + h_;
        const Vector6 k1 = dLambda(sb, Lambda);
        const Vector6 k2 = dLambda(sb - 0.5 * h_, Lambda - 0.5 * h_ * k1);
        const Vector6 k3 = dLambda(sb - 0.5 * h_, Lambda - 0.5 * h_ * k2);
        const Vector6 k4 = dLambda(s, Lambda - h_ * k3);
        Lambda -= h_ * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
      }
      x.segment<kState>(kState * i) = scaled(i == 0 ? base : base * SE3::exp(s * xi_star), Lambda);
    }
    return x;
  }

  /// For a clamped tip: the rod of constant strain xi_c = log(base^-1 g_target) / L that joins
  /// base and target (the reference configuration when the target is the reference tip), with
  /// Lambda = K (xi_c - xi*). It is the exact answer for targets on a constant-strain arc, and
  /// away from the straight rod, where a Kirchhoff rod's axial force is indeterminate.
  VectorXd geodesic_guess() const {
    const SE3& base = P_.base();
    const Vector6 xi_c = (base.inverse() * P_.tip_target()).log() / L_;
    const Vector6 Lambda = P_.rod_wrench(xi_c);
    VectorXd x(size());
    for (int i = 0; i < N_; ++i)
      x.segment<kState>(kState * i) = scaled(i == 0 ? base : base * SE3::exp(i * h_ * xi_c), Lambda);
    return x;
  }

  /// The scaled unknowns of a node.
  State scaled(const SE3& g, const Vector6& Lambda) const {
    const Quaternion& q = g.rotation().quaternion();
    State y;
    y << q.w(), q.x(), q.y(), q.z(), g.translation() / L_, Lambda.cwiseQuotient(scale_.tail<6>());
    return y;
  }

  /// Below this max norm a residual is at the rounding level of the rows (differences of O(1)
  /// unknowns divided by h / L, and the unknowns' own size).
  double rounding_floor(const ConstRef& x) const {
    return 64.0 * std::numeric_limits<double>::epsilon() * (N_ - 1) *
           std::max(1.0, x.lpNorm<Eigen::Infinity>());
  }

 private:
  static constexpr double kFdStep = 1.5e-8;  // ~ sqrt(eps), relative to max(1, |x|)

  int first_row(int j) const { return j == 0 ? 0 : kBaseRows + kState * (j - 1); }
  int last_row(int j) const { return j == N_ - 1 ? size() - 1 : kBaseRows + kState * (j + 1) - 1; }

  void base_rows(const ConstRef& x, Ref F) const {
    const Quaternion& qb = P_.base().rotation().quaternion();
    F[0] = x[0] - qb.w();
    F[1] = x[1] - qb.x();
    F[2] = x[2] - qb.y();
    F[3] = x[3] - qb.z();
    F.segment<3>(4) = x.segment<3>(4) - P_.base().translation() / L_;
  }

  StaticProblem P_;
  int N_;
  double L_, h_;
  State scale_;
  std::vector<NodeData> node_;  // workspace: node data at the current x
  std::vector<Rows> rows_;      // workspace: interval rows at the current x
};

class Driver {
 public:
  Driver(const StaticProblem& problem, const KinsolCollocationOptions& options)
      : C_(problem, options.nodes), options_(options), solver_(C_.pattern()) {
    kinsol_.fnormtol = options.tol;
    kinsol_.scsteptol = options.step_tol;
    kinsol_.max_iterations = options.max_iterations;
    kinsol_.line_search = true;
    kinsol_.max_setup_calls = 1;
  }

  /// One KINSOL run (line search) at a load factor, with at most max_iterations if > 0.
  /// KIN_STEP_LT_STPTOL (no further progress) at a residual on the rounding floor of the rows
  /// counts as converged: a tolerance below that floor cannot be met by any iterate.
  KinsolStats solve_at(double load_factor, VectorXd& x, int max_iterations = 0) {
    C_.problem().set_load_factor(load_factor);
    KinsolOptions options = kinsol_;
    if (max_iterations > 0) options.max_iterations = std::min(max_iterations, options.max_iterations);
    KinsolStats stats = solver_.solve(
        x, [this](const ConstRef& u, Ref F) { C_.residual(u, F); },
        [this](const ConstRef& u, const ConstRef&, Sparse& J) { C_.jacobian(u, J); }, options);
    ++report_.kinsol_solves;
    report_.nonlinear_iterations += stats.nonlinear_iterations;
    report_.function_evaluations += stats.function_evaluations;
    report_.jacobian_evaluations += stats.jacobian_evaluations;
    report_.backtracks += stats.backtracks;
    report_.flag = stats.flag_name;
    if (!stats.converged && stats.flag_name == "KIN_STEP_LT_STPTOL" &&
        residual_norm(x) <= std::max(options.fnormtol, C_.rounding_floor(x)))
      stats.converged = true;
    return stats;
  }

  double residual_norm(const VectorXd& x) {
    VectorXd F(C_.size());
    C_.residual(x, F);
    return F.lpNorm<Eigen::Infinity>();
  }

  /// The initial guess at a load factor: the reference configuration, or for a clamped tip the
  /// constant-strain rod to the target.
  VectorXd guess_at(double load_factor) {
    C_.problem().set_load_factor(load_factor);
    return C_.problem().tip_clamped() ? C_.geodesic_guess() : C_.reference_guess();
  }

  /// 1. Direct: Newton with KINSOL's line search at load factor 1 from the initial guess(es)
  ///    (a clamped tip has two: the constant-strain rod to the target and the reference
  ///    configuration with zero wrench, tried in the order of their residual norms), at most
  ///    15 iterations. Accepted only when the line search never had to cut a step, i.e. the
  ///    guess was inside Newton's basin: from further away Newton can land on another
  ///    equilibrium (a coiled rod under a large dead load, say) than the load path reaches.
  /// 2. Otherwise load continuation, which follows the load path from the unloaded rod.
  /// 3. If that fails too, the direct solves again with the full iteration budget, accepting
  ///    backtracking.
  KinsolCollocationReport run() {
    const auto start = std::chrono::steady_clock::now();
    std::vector<VectorXd> guesses{guess_at(1.0)};
    if (C_.problem().tip_clamped()) {
      guesses.push_back(C_.reference_guess());
      if (residual_norm(guesses[1]) < residual_norm(guesses[0])) std::swap(guesses[0], guesses[1]);
    }
    std::string reason;
    VectorXd best;  // the first direct iterate, reported if nothing converges
    auto note = [&](const KinsolStats& stats, const char* what) {
      reason += (reason.empty() ? "" : "; ") + describe(stats) + " (" + what +
                (stats.converged ? ", with backtracking)" : ")");
    };
    if (options_.direct) {
      for (const VectorXd& guess : guesses) {
        VectorXd x = guess;
        const KinsolStats stats = solve_at(1.0, x, kDirectIterations);
        if (stats.converged && stats.backtracks == 0) return finish(x, true, "", "direct", start);
        if (best.size() == 0) best = x;
        note(stats, "direct");
      }
    }
    if (options_.continuation) {
      report_.used_continuation = true;
      VectorXd xc;
      std::string why;
      if (continuation(xc, why)) return finish(xc, true, "", "continuation", start);
      reason += "; continuation: " + why;
    }
    if (options_.direct && options_.max_iterations > kDirectIterations) {
      for (const VectorXd& guess : guesses) {
        VectorXd x = guess;
        const KinsolStats stats = solve_at(1.0, x);
        if (stats.converged) return finish(x, true, "", "direct, with backtracking", start);
        note(stats, "direct, full budget");
      }
    }
    if (best.size() == 0) best = guesses.front();
    return finish(best, false, reason, "none", start);
  }

 private:
  static std::string describe(const KinsolStats& s) { return s.flag_name; }

  /// Load continuation through the shared driver (continuation.hpp): from load factor 0, where
  /// the initial guess is exact, to 1; each corrector is a KINSOL solve with the line search.
  bool continuation(VectorXd& x, std::string& why) {
    Continuation walk;
    walk.correct = [this](double lf, const VectorXd& guess) {
      CorrectorResult r;
      r.state = guess;
      const KinsolStats stats = solve_at(lf, r.state, kCorrectorIterations);
      // A corrector that needs many iterations or cuts a step has left the branch's basin: the
      // step is halved instead (so the walk cannot jump to another branch).
      r.converged = stats.converged && stats.backtracks == 0;
      r.reason = describe(stats);
      r.residual_norm = residual_norm(r.state);
      return r;
    };
    walk.first_predictor = [this](double from, double to, const VectorXd& state) {
      return VectorXd(state + guess_at(to) - guess_at(from));
    };
    const ContinuationResult result = continue_load(walk, guess_at(0.0));
    x = result.state;
    why = result.reason;
    return result.converged;
  }

  KinsolCollocationReport finish(const VectorXd& x, bool converged, const std::string& reason,
                                 const char* strategy, std::chrono::steady_clock::time_point start) {
    C_.problem().set_load_factor(1.0);
    const StaticProblem& P = C_.problem();
    VectorXd F(C_.size());
    C_.residual(x, F);
    const int N = C_.nodes();
    std::vector<double> s(N);
    std::vector<SE3> g(N);
    std::vector<Vector6> Lambda(N);
    double q_error = 0.0;
    for (int i = 0; i < N; ++i) {
      const NodeData n = C_.node(x, i);
      q_error = std::max(q_error, std::abs(n.q.norm() - 1.0));
      s[i] = P.length() * i / (N - 1);
      g[i] = SE3(n.R, n.p);
      Lambda[i] = n.Lambda;
    }
    auto& out = report_.result;
    fill_static_result(P, s, g, Lambda, out);
    out.scene = P.name();
    out.scheme = "kinsol";
    out.converged = converged;
    out.reason = reason;
    out.iterations = static_cast<int>(report_.nonlinear_iterations);
    out.residual_norm = F.lpNorm<Eigen::Infinity>();
    out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_.max_quaternion_norm_error = q_error;
    report_.strategy = strategy;
    return report_;
  }

  static constexpr int kDirectIterations = 15;    // Newton inside its basin needs fewer
  static constexpr int kCorrectorIterations = 8;  // per continuation step

  Collocation C_;
  KinsolCollocationOptions options_;
  KinsolSolver solver_;
  KinsolOptions kinsol_;
  KinsolCollocationReport report_;
};

}  // namespace

KinsolCollocationReport solve_kinsol_collocation_report(const StaticProblem& problem,
                                                        const KinsolCollocationOptions& options) {
  if (options.nodes < 2)
    throw std::invalid_argument("kinsol: nodes must be >= 2, got " + std::to_string(options.nodes));
  if (!(options.tol > 0.0) || !(options.step_tol > 0.0) || options.max_iterations < 1)
    throw std::invalid_argument("kinsol: tol and step_tol must be > 0 and max_iterations >= 1");
  if (!options.direct && !options.continuation)
    throw std::invalid_argument("kinsol: direct and continuation cannot both be off");
  if (problem.has_actuators())
    throw std::invalid_argument("kinsol: actuators are not supported by the collocation yet");
  return Driver(problem, options).run();
}

result::StaticResult solve_kinsol_collocation(const StaticProblem& problem,
                                              const KinsolCollocationOptions& options) {
  return solve_kinsol_collocation_report(problem, options).result;
}

}  // namespace rodlab::solvers::statics
