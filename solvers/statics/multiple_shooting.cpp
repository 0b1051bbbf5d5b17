#include "rodlab/solvers/statics/multiple_shooting.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>

#include "rodlab/solvers/statics/shooting.hpp"

namespace rodlab::solvers::statics {

using Eigen::MatrixXd;
using Eigen::VectorXd;
using Lengths = std::array<double, StaticProblem::kMaxActuators>;

struct MultipleShooting::Marched {
  Node end;
  Lengths lengths{};
};

MultipleShooting::MultipleShooting(StaticProblem& problem, RkmkMethod method, int nodes)
    : P_(problem), method_(method), nodes_(nodes), extra_(problem.extra_unknowns()) {
  const int M = std::min(nodes - 1, kMaxShootingIntervals);
  for (int k = 0; k <= M; ++k)
    bounds_.push_back(static_cast<int>(std::lround(static_cast<double>(k) * (nodes - 1) / M)));
  const double h = P_.length() / (nodes - 1);
  for (int k = 0; k < M; ++k)
    reference_.push_back((P_.base() * P_.model().rest_pose(bounds_[k] * h)).rotation());
}

int MultipleShooting::size() const { return 6 + 12 * (intervals() - 1) + extra_; }

VectorXd MultipleShooting::reference_guess() const {
  const int M = intervals();
  const double h = P_.length() / (nodes_ - 1);
  std::vector<double> s(M);
  for (int k = 0; k < M; ++k) s[k] = bounds_[k] * h;
  const std::vector<Vector6> Lambda = rigid_wrench_profile(P_, s, nodes_ - 1);
  VectorXd x(size());
  x.head<6>() = Lambda[0].cwiseQuotient(P_.wrench_scale());
  for (int k = 1; k < M; ++k)
    x.segment<12>(offset(k)) << Vector3::Zero(),
        (P_.base() * P_.model().rest_pose(s[k])).translation() / P_.length(),
        Lambda[k].cwiseQuotient(P_.wrench_scale());
  const auto z = P_.extra_initial_guess();
  for (int e = 0; e < extra_; ++e) x[size() - extra_ + e] = z[e];
  return x;
}

Node MultipleShooting::start(const VectorXd& x, int k) const {
  if (k == 0) return {P_.base(), x.head<6>().cwiseProduct(P_.wrench_scale())};
  const auto u = x.segment<12>(offset(k));
  return {SE3(reference_[k] * SO3::exp(u.head<3>()), P_.length() * u.segment<3>(3)),
          u.tail<6>().cwiseProduct(P_.wrench_scale())};
}

bool MultipleShooting::march(int k, const Node& from, Marched& out, std::span<Node> path) const {
  const int first = bounds_[k], last = bounds_[k + 1];
  const ShootResult r = shoot_span(P_, method_, nodes_, first, last, from,
                                   path.empty() ? path : path.subspan(first, last - first + 1));
  out.end = r.tip;
  out.lengths = r.lengths;
  return r.ok;
}

void MultipleShooting::interval_rows(int k, const Node& end, const VectorXd& x,
                                     Eigen::Ref<VectorXd> rows) const {
  if (k + 1 == intervals()) {
    rows = P_.tip_residual(end.g, end.Lambda);
    return;
  }
  const Node next = start(x, k + 1);
  rows << (next.g.rotation().inverse() * end.g.rotation()).log(),
      (end.g.translation() - next.g.translation()) / P_.length(),
      (end.Lambda - next.Lambda).cwiseQuotient(P_.wrench_scale());
}

void MultipleShooting::set_extras(const VectorXd& x) const {
  if (extra_) P_.set_extra_unknowns(std::span<const double>(x.data() + size() - extra_, extra_));
}

bool MultipleShooting::residual(const VectorXd& x, VectorXd& r) const {
  set_extras(x);
  r.resize(size());
  Lengths total{};
  for (int k = 0; k < intervals(); ++k) {
    Marched m;
    if (!march(k, start(x, k), m)) return false;
    interval_rows(k, m.end, x, r.segment(12 * k, k + 1 == intervals() ? 6 : 12));
    for (std::size_t a = 0; a < total.size(); ++a) total[a] += m.lengths[a];
  }
  if (extra_) P_.extra_residuals(total, std::span<double>(r.data() + tip_row() + 6, extra_));
  return r.allFinite();
}

bool MultipleShooting::jacobian(const VectorXd& x, const VectorXd& r, MatrixXd& J,
                                double fd_step) const {
  const int M = intervals(), n = size();
  set_extras(x);
  std::vector<Marched> base(M);
  for (int k = 0; k < M; ++k)
    if (!march(k, start(x, k), base[k])) return false;
  J.setZero(n, n);
  VectorXd xp = x, rows(12), extras(extra_);
  for (int k = 0; k < M; ++k) {
    const int len = k + 1 == M ? 6 : 12;
    for (int j = column(k); j < column(k) + columns(k); ++j) {
      double h = fd_step * std::max(1.0, std::abs(x[j]));
      Marched m;
      xp[j] = x[j] + h;
      if (!march(k, start(xp, k), m)) {  // the other side before giving up
        h = -h;
        xp[j] = x[j] + h;
        if (!march(k, start(xp, k), m)) return false;
      }
      // The start of interval k moves its own march, the join before it and the lengths.
      interval_rows(k, m.end, xp, rows.head(len));
      J.col(j).segment(12 * k, len) = (rows.head(len) - r.segment(12 * k, len)) / h;
      if (k > 0) {
        interval_rows(k - 1, base[k - 1].end, xp, rows);
        J.col(j).segment<12>(12 * (k - 1)) = (rows - r.segment<12>(12 * (k - 1))) / h;
      }
      if (extra_) {
        Lengths total{};
        for (int i = 0; i < M; ++i)
          for (std::size_t a = 0; a < total.size(); ++a)
            total[a] += (i == k ? m.lengths : base[i].lengths)[a];
        P_.extra_residuals(total, std::span<double>(extras.data(), extra_));
        J.col(j).tail(extra_) = (extras - r.tail(extra_)) / h;
      }
      xp[j] = x[j];
    }
  }
  // An actuator unknown changes the strain law everywhere: a whole residual per column.
  VectorXd rp(n);
  for (int j = n - extra_; j < n; ++j) {
    double h = fd_step * std::max(1.0, std::abs(x[j]));
    xp[j] = x[j] + h;
    if (!residual(xp, rp)) {
      h = -h;
      xp[j] = x[j] + h;
      if (!residual(xp, rp)) return false;
    }
    J.col(j) = (rp - r) / h;
    xp[j] = x[j];
  }
  set_extras(x);
  return J.allFinite();
}

NewtonResult MultipleShooting::solve(const VectorXd& guess, NewtonOptions options) const {
  options.jacobian = [this, step = options.fd_step](const VectorXd& x, const VectorXd& F,
                                                    MatrixXd& J) {
    return jacobian(x, F, J, step);
  };
  // The rounding level of the rows, differences of unknowns of size |x| (as kinsol's rule; a
  // soft cantilever, E = 1000 Pa under gravity, N = 100, stops at 1.6e-12 against a tolerance of
  // 1e-12 with |x| ~ 1.6e3).
  options.rounding_floor = [](const VectorXd& x) {
    return 64.0 * std::numeric_limits<double>::epsilon() *
           std::max(1.0, x.lpNorm<Eigen::Infinity>());
  };
  const Residual F = [this](const VectorXd& x, VectorXd& r) { return residual(x, r); };
  NewtonResult out = solve_newton(F, guess, options);
  set_extras(out.x);
  return out;
}

bool MultipleShooting::path(const VectorXd& x, std::vector<Node>& nodes) const {
  set_extras(x);
  nodes.resize(nodes_);
  Marched m;
  for (int k = 0; k < intervals(); ++k)
    if (!march(k, start(x, k), m, nodes)) return false;
  return true;
}

}  // namespace rodlab::solvers::statics
