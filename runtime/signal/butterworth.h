// Zero-phase low-pass filtering of a sampled signal, the way the contact-force
// statistics of EN 50318 want it (0-20 Hz, no phase shift): a digital
// Butterworth filter run forward and backward.
//
// The filter is a cascade of second-order sections (biquads), never one
// high-order polynomial: the coefficients of a polynomial of order 5 or more
// with its poles near z = 1 (a cut-off far below the sample rate) lose every
// digit, and the filter then blows up or loses its gain at 0 Hz. Both halves
// follow scipy.signal so that its results are the reference
// (tests/runtime/signal/, docs/contact-statistics.md):
// butterworth_lowpass() is scipy.signal.butter(N, Wn, output='sos') (analog
// prototype poles, cut-off pre-warped, bilinear transform, poles and zeros
// paired into sections nearest first, the gain in the first section), and
// sosfiltfilt() is scipy.signal.sosfiltfilt(sos, x) with its defaults (odd
// extension of 3 (order + 1) samples at each end,
// steady-state initial conditions of every section scaled by the first sample).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace mbfe::runtime {

/// One section: b0 b1 b2 a0 a1 a2 of (b0 + b1 z^-1 + b2 z^-2) / (a0 + a1 z^-1
/// + a2 z^-2), a0 = 1 (scipy's row of an `sos` array).
using Biquad = std::array<double, 6>;

/// A cascade of sections, applied in order.
struct SosFilter {
  std::vector<Biquad> sections;
};

/// The lowest cut-off the filter takes, as a fraction of the sample rate:
/// below it the rounding of the recursion grows as (sample rate / cut-off)^2
/// past 1e-7 of the signal (docs/contact-statistics.md).
constexpr double kMinCutoffFraction = 1e-5;

/// Order-`order` digital Butterworth low-pass with its -3 dB point at
/// `cutoff_hz`, for samples `sample_hz` apart in frequency: (order + 1) / 2
/// sections.
/// @throws std::invalid_argument unless 1 <= order <= 8 and
///         kMinCutoffFraction * sample_hz <= cutoff_hz < sample_hz / 2.
SosFilter butterworth_lowpass(int order, double cutoff_hz, double sample_hz);

/// The samples sosfiltfilt() adds at each end, as scipy.signal.sosfiltfilt:
/// 3 (2 sections + 1 - k), k the smaller of the counts of sections with b2 = 0
/// and with a2 = 0 (an odd order's first-order section): 3 (order + 1) for a
/// Butterworth filter.
std::size_t sosfiltfilt_padding(const SosFilter& f);

/// y = f applied forward, then backward (zero phase, squared magnitude).
/// @throws std::invalid_argument if x has no more samples than the padding.
std::vector<double> sosfiltfilt(const SosFilter& f, const std::vector<double>& x);

}  // namespace mbfe::runtime
