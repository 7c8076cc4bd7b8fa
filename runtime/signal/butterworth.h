// Zero-phase low-pass filtering of a sampled signal, the way the contact-force
// statistics of EN 50318 want it (0-20 Hz, no phase shift): a digital
// Butterworth filter run forward and backward.
//
// Both halves follow scipy.signal so that its results are the reference
// (tests/runtime/signal/): butterworth_lowpass() is scipy.signal.butter(N, Wn)
// (analog prototype poles, cutoff pre-warped, bilinear transform, then the
// transfer function), filtfilt() is scipy.signal.filtfilt(b, a, x) with its
// defaults (odd extension of 3 max(len(a), len(b)) samples at each end,
// steady-state initial conditions scaled by the first sample).
#pragma once

#include <vector>

namespace mbfe::runtime {

/// A transfer function b(z) / a(z), a[0] = 1.
struct IirFilter {
  std::vector<double> b, a;
};

/// Order-`order` digital Butterworth low-pass with its -3 dB point at
/// `cutoff_hz`, for samples `sample_hz` apart in frequency.
/// @throws std::invalid_argument unless 1 <= order <= 8 and
///         0 < cutoff_hz < sample_hz / 2.
IirFilter butterworth_lowpass(int order, double cutoff_hz, double sample_hz);

/// y = f applied forward, then backward (zero phase, squared magnitude).
/// @throws std::invalid_argument if x has no more samples than the padding
///         (3 max(len(a), len(b))).
std::vector<double> filtfilt(const IirFilter& f, const std::vector<double>& x);

}  // namespace mbfe::runtime
