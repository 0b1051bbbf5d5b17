#include "inverse_broyden.hpp"

#include <cmath>

#include <Eigen/KLUSupport>
#include <Eigen/LU>

namespace rodlab::solvers::dynamics {

struct InverseBroyden::Factors {
  Eigen::KLU<Jacobian> klu;
};

InverseBroyden::InverseBroyden() = default;
InverseBroyden::~InverseBroyden() = default;

InverseBroyden::InverseBroyden(const InverseBroyden& o)
    : J_(o.J_), H_(o.H_), s_(o.s_), u_(o.u_), at_(o.at_), H_at_(o.H_at_) {}

InverseBroyden& InverseBroyden::operator=(const InverseBroyden& o) {
  if (this == &o) return *this;
  J_ = o.J_, H_ = o.H_, s_ = o.s_, u_ = o.u_, at_ = o.at_, H_at_ = o.H_at_;
  lu_.reset();
  return *this;
}

bool InverseBroyden::refresh() {
  s_.clear();
  u_.clear();
  at_.resize(0);
  lu_.reset();
  H_.resize(0, 0);
  if (!J_.isCompressed()) J_.makeCompressed();
  for (Eigen::Index p = 0; p < J_.nonZeros(); ++p)
    if (!std::isfinite(J_.valuePtr()[p])) return false;
  if (!dense()) return factorise();
  H_ = Eigen::PartialPivLU<Eigen::MatrixXd>(Eigen::MatrixXd(J_)).inverse();
  return H_.allFinite();
}

InverseBroyden::Vector InverseBroyden::step(const Vector& r) {
  if (dense()) return -(H_ * r);
  if (!step_input_is(r)) {
    at_ = r;
    H_at_ = apply(r);
  }
  return -H_at_;
}

bool InverseBroyden::update(const Vector& s, const Vector& r, const Vector& r_new) {
  if (dense()) {
    const Vector Hy = H_ * (r_new - r);
    const double denominator = s.dot(Hy);
    if (denominator != 0.0) H_ += (s - Hy) * (s.transpose() * H_) / denominator;
    return true;
  }
  const Vector Hr = step_input_is(r) ? H_at_ : apply(r);
  at_ = r_new;
  H_at_ = apply(r_new);
  const Vector Hy = H_at_ - Hr;
  const double denominator = s.dot(Hy);
  if (denominator != 0.0) {
    s_.push_back(s);
    u_.push_back((s - Hy) / denominator);
    H_at_ += u_.back() * s.dot(H_at_);
  }
  return static_cast<int>(s_.size()) < kMaxUpdates;
}

bool InverseBroyden::factorise() {
  lu_ = std::make_unique<Factors>();
  klu_common& options = lu_->klu.kluCommon();
  options.tol = 1.0;     // partial pivoting (KLU's default 0.001 prefers the diagonal)
  options.ordering = 2;  // the caller's order (a staircase fills only inside itself)...
  options.btf = 0;       // ...kept whole (no block triangular form: the matrix is irreducible)
  lu_->klu.compute(J_);
  return lu_->klu.info() == Eigen::Success;
}

InverseBroyden::Vector InverseBroyden::apply(const Vector& v) {
  if (!lu_ && !factorise()) return Vector::Constant(v.size(), std::nan(""));
  Vector w = lu_->klu.solve(v);
  for (std::size_t j = 0; j < s_.size(); ++j) w += u_[j] * s_[j].dot(w);
  return w;
}

}  // namespace rodlab::solvers::dynamics
