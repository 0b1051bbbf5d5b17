#include "rodlab/solvers/learning/replay_buffer.hpp"

#include <algorithm>

#include "rodlab/check.hpp"

namespace rodlab::solvers::learning {

ReplayBuffer::ReplayBuffer(int observation_size, int action_size, long capacity)
    : capacity_(capacity) {
  RODLAB_THROW_UNLESS(observation_size >= 1 && action_size >= 1 && capacity >= 1,
                      "replay buffer: sizes and capacity must be >= 1 (got {}, {}, {})",
                      observation_size, action_size, capacity);
  s_.resize(observation_size, capacity);
  s_next_.resize(observation_size, capacity);
  a_.resize(action_size, capacity);
  r_.resize(capacity);
  terminal_.resize(capacity);
}

void ReplayBuffer::add(std::span<const double> s, std::span<const double> a, double r,
                       std::span<const double> s_next, bool terminal) {
  RODLAB_THROW_UNLESS(static_cast<Eigen::Index>(s.size()) == s_.rows() &&
                          static_cast<Eigen::Index>(s_next.size()) == s_.rows() &&
                          static_cast<Eigen::Index>(a.size()) == a_.rows(),
                      "replay buffer: expected observations of {} and actions of {} values",
                      s_.rows(), a_.rows());
  s_.col(next_) = Eigen::Map<const Eigen::VectorXd>(s.data(), s_.rows());
  s_next_.col(next_) = Eigen::Map<const Eigen::VectorXd>(s_next.data(), s_.rows());
  a_.col(next_) = Eigen::Map<const Eigen::VectorXd>(a.data(), a_.rows());
  r_[next_] = r;
  terminal_[next_] = terminal ? 1.0 : 0.0;
  next_ = (next_ + 1) % capacity_;
  size_ = std::min(size_ + 1, capacity_);
}

void ReplayBuffer::sample(std::mt19937_64& rng, int batch, Matrix& S, Matrix& A,
                          Eigen::RowVectorXd& R, Matrix& S_next, Eigen::RowVectorXd& T) const {
  RODLAB_THROW_UNLESS(size_ > 0 && batch >= 1, "replay buffer: sampling {} from {} transitions",
                      batch, size_);
  S.resize(s_.rows(), batch);
  S_next.resize(s_.rows(), batch);
  A.resize(a_.rows(), batch);
  R.resize(batch);
  T.resize(batch);
  for (int k = 0; k < batch; ++k) {
    const auto i = static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(size_));
    S.col(k) = s_.col(i);
    S_next.col(k) = s_next_.col(i);
    A.col(k) = a_.col(i);
    R[k] = r_[i];
    T[k] = terminal_[i];
  }
}

}  // namespace rodlab::solvers::learning
