#pragma once
// DDPG's replay buffer (Lillicrap et al. 2016, section 3; thesis 4.3.1): the last `capacity`
// transitions (s, a, r, s', terminal) in a ring, minibatches drawn uniformly with replacement
// from a caller's generator. Columns are samples; storage is allocated once.
#include <cstdint>
#include <random>
#include <span>

#include <Eigen/Core>

namespace rodlab::solvers::learning {

class ReplayBuffer {
 public:
  using Matrix = Eigen::MatrixXd;
  /// Throws std::invalid_argument for sizes or a capacity < 1.
  ReplayBuffer(int observation_size, int action_size, long capacity);

  void add(std::span<const double> s, std::span<const double> a, double r,
           std::span<const double> s_next, bool terminal);
  long size() const { return size_; }
  long capacity() const { return capacity_; }

  /// A minibatch of `batch` samples into the given matrices (resized to batch columns; no
  /// allocation once they have that size): S, A, S' one column per sample, R and T (1 if
  /// terminal) rows. Throws std::invalid_argument when the buffer is empty.
  void sample(std::mt19937_64& rng, int batch, Matrix& S, Matrix& A, Eigen::RowVectorXd& R,
              Matrix& S_next, Eigen::RowVectorXd& T) const;

 private:
  Matrix s_, a_, s_next_;
  Eigen::RowVectorXd r_, terminal_;
  long capacity_ = 0, size_ = 0, next_ = 0;
};

}  // namespace rodlab::solvers::learning
