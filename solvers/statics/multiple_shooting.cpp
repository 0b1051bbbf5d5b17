#include "rodlab/solvers/statics/multiple_shooting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "rodlab/solvers/statics/shooting.hpp"

namespace rodlab::solvers::statics {
namespace {

using Eigen::VectorXd;

/// An interior interval start's unknowns: rotation vector (3), position / L (3), Lambda (6).
constexpr int kStart = 12;

class MultipleShooting {
 public:
  MultipleShooting(StaticProblem& problem, RkmkMethod method, int nodes)
      : P_(problem), method_(method), nodes_(nodes), extra_(problem.extra_unknowns()),
        h_(problem.length() / (nodes - 1)) {
    const int M = std::min(nodes - 1, kMaxShootingIntervals);
    for (int k = 0; k <= M; ++k)
      bounds_.push_back(static_cast<int>(std::lround(static_cast<double>(k) * (nodes - 1) / M)));
  }

  int intervals() const { return static_cast<int>(bounds_.size()) - 1; }
  int size() const { return 6 + kStart * (intervals() - 1) + extra_; }

  /// The reference configuration g(s) = base rest_pose(s) at the interval starts, with the
  /// undeformed rod's equilibrium wrench (zero for a clamped tip), the extra unknowns at their
  /// initial guess; it fixes the rotations the unknowns are measured against.
  VectorXd reference_guess() {
    const int M = intervals();
    std::vector<double> s(M);
    for (int k = 0; k < M; ++k) s[k] = bounds_[k] * h_;
    const std::vector<Vector6> Lambda = rigid_wrench_profile(P_, s, nodes_ - 1);
    VectorXd x(size());
    x.head<6>() = Lambda[0].cwiseQuotient(P_.wrench_scale());
    reference_.assign(M, SO3());
    for (int k = 1; k < M; ++k) {
      const SE3 g = P_.base() * P_.model().rest_pose(s[k]);
      reference_[k] = g.rotation();
      x.segment<kStart>(offset(k)) << Vector3::Zero(), g.translation() / P_.length(),
          Lambda[k].cwiseQuotient(P_.wrench_scale());
    }
    const auto z = P_.extra_initial_guess();
    for (int e = 0; e < extra_; ++e) x[size() - extra_ + e] = z[e];
    return x;
  }

  /// [joins of the intervals k = 0..M-2 (rotation, position / L, Lambda / scale); the tip
  /// conditions; the actuator conditions]. False where a march fails.
  bool residual(const VectorXd& x, VectorXd& r) { return march(x, &r, {}); }

  /// The grid's nodes at x (each interval's start, then its march).
  bool path(const VectorXd& x, std::vector<Node>& nodes) {
    nodes.resize(nodes_);
    return march(x, nullptr, nodes);
  }

 private:
  int offset(int k) const { return 6 + kStart * (k - 1); }

  Node start(const VectorXd& x, int k) const {
    if (k == 0) return {P_.base(), x.head<6>().cwiseProduct(P_.wrench_scale())};
    const auto u = x.segment<kStart>(offset(k));
    return {SE3(reference_[k] * SO3::exp(u.head<3>()), P_.length() * u.segment<3>(3)),
            u.tail<6>().cwiseProduct(P_.wrench_scale())};
  }

  bool march(const VectorXd& x, VectorXd* r, std::span<Node> path) {
    if (extra_) P_.set_extra_unknowns(std::span<const double>(x.data() + size() - extra_, extra_));
    const int M = intervals();
    if (r) r->resize(size());
    std::array<double, StaticProblem::kMaxActuators> lengths{};
    Node from = start(x, 0);
    for (int k = 0; k < M; ++k) {
      const int first = bounds_[k], last = bounds_[k + 1];
      const auto span = path.empty() ? path : path.subspan(first, last - first + 1);
      const ShootResult end = shoot_span(P_, method_, nodes_, first, last, from, span);
      if (!end.ok) return false;
      for (std::size_t a = 0; a < lengths.size(); ++a) lengths[a] += end.lengths[a];
      if (k + 1 == M) {
        if (r) r->segment<6>(size() - extra_ - 6) = P_.tip_residual(end.tip.g, end.tip.Lambda);
        break;
      }
      const Node next = start(x, k + 1);
      if (r)
        r->segment<kStart>(kStart * k)
            << (next.g.rotation().inverse() * end.tip.g.rotation()).log(),
            (end.tip.g.translation() - next.g.translation()) / P_.length(),
            (end.tip.Lambda - next.Lambda).cwiseQuotient(P_.wrench_scale());
      from = next;
    }
    if (r && extra_)
      P_.extra_residuals(lengths, std::span<double>(r->data() + size() - extra_, extra_));
    return true;
  }

  StaticProblem& P_;
  RkmkMethod method_;
  int nodes_, extra_;
  double h_;
  std::vector<int> bounds_;    // the intervals' first and last nodes
  std::vector<SO3> reference_; // the rotations the start unknowns are measured against
};

}  // namespace

MultipleShootingResult solve_multiple_shooting(StaticProblem& problem, RkmkMethod method,
                                               int nodes, const NewtonOptions& options) {
  MultipleShooting ms(problem, method, nodes);
  MultipleShootingResult out;
  const Residual F = [&ms](const VectorXd& x, VectorXd& r) { return ms.residual(x, r); };
  out.newton = solve_newton(F, ms.reference_guess(), options);
  if (out.newton.converged && !ms.path(out.newton.x, out.path)) {
    out.newton.converged = false;  // cannot happen: the residual was evaluated at x
    out.newton.reason = "the march failed at the solution";
  }
  return out;
}

}  // namespace rodlab::solvers::statics
