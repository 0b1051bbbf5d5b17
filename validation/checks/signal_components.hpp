#pragma once
// The sinusoids in a uniformly sampled signal, by the matrix pencil method (Y. Hua, T. K. Sarkar,
// Matrix pencil method for estimating parameters of exponentially damped/undamped sinusoids in
// noise, IEEE Trans. ASSP 38 (1990) 814-824): the signal's Hankel matrix, its `order` leading
// right singular vectors, and the eigenvalues z_i of the pencil between their shifted halves,
// z_i = exp((-d_i + i 2 pi f_i) dt); amplitudes by least squares on the z_i^k. It resolves
// frequencies far more finely than 1 / (record length), which a free vibration of a few periods
// of its lowest mode needs (the "literature" family's frequencies, docs/validation.md).
#include <vector>

namespace rodlab::validation {

struct SignalComponent {
  double frequency_hz = 0.0;
  double amplitude = 0.0;  ///< of the real sinusoid (twice the complex amplitude)
  double decay = 0.0;      ///< 1/s; 0 for an undamped one
};

/// The components of positive frequency of y (samples dt apart), ascending in frequency, those
/// smaller than `relative_floor` times the largest left out. `order`: the model order (two per
/// sinusoid, one for an offset), at most a third of the samples.
std::vector<SignalComponent> signal_components(const std::vector<double>& y, double dt, int order,
                                               double relative_floor = 1e-4);

}  // namespace rodlab::validation
