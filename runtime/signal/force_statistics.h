// The contact-force statistics of EN 50318 over a window of a sampled force:
// mean, standard deviation, statistical maximum and minimum (mean +- 3 std),
// actual maximum and minimum, all of the low-pass filtered force, and the
// share of the window in which the unfiltered force is zero (contact loss).
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace mbfe::runtime {

struct ForceStatistics {
  double mean = 0.0;
  double std = 0.0;              // population standard deviation (divided by n)
  double statistical_max = 0.0;  // mean + 3 std
  double statistical_min = 0.0;  // mean - 3 std
  double max = 0.0;
  double min = 0.0;
  double loss_percent = 0.0;     // % of the window's samples with the unfiltered force <= 0
  int samples = 0;               // in the window
};

struct ForceStatisticsOptions {
  double lowpass_hz = 0.0;  // 0: no filter
  int order = 4;            // Butterworth order (applied forward and backward)
  double from = -1e300;     // s: the window, t in [from, to]
  double to = 1e300;
};

/// A sample the statistics refuse; `sample` is its index in t and force, so
/// that the caller can name the row of its file.
class BadSample : public std::invalid_argument {
 public:
  BadSample(std::size_t sample, const std::string& what) : std::invalid_argument(what), sample(sample) {}
  std::size_t sample;
};

/// Statistics of `force` sampled at times `t` (evenly spaced when filtering).
/// The filter runs over the whole signal, then the window is cut, so that its
/// edges see no start-up transient. A last sample closer to the one before
/// than the others (a run's final state) is left out when filtering. Sums are
/// scaled by the largest |value| and compensated (Neumaier), so values up to
/// the largest double neither overflow nor lose the mean.
/// @throws BadSample for a time or force that is NaN or infinite, or a time
///         not after the one before (times must increase strictly).
/// @throws std::invalid_argument for uneven samples (when filtering), an
///         empty window, a statistic beyond the largest double, or what the
///         filter refuses.
ForceStatistics force_statistics(const std::vector<double>& t, const std::vector<double>& force,
                                 const ForceStatisticsOptions& options);

}  // namespace mbfe::runtime
