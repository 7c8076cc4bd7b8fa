#include "runtime/signal/force_statistics.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "runtime/signal/butterworth.h"

namespace mbfe::runtime {

namespace {

// Samples count as evenly spaced when every interval is within this fraction
// of the first (the times are printed to 17 digits; a run's shortened last
// step is not even, and is reported).
constexpr double kEvenSpacing = 1e-6;

}  // namespace

ForceStatistics force_statistics(const std::vector<double>& t, const std::vector<double>& force,
                                 const ForceStatisticsOptions& options) {
  if (t.size() != force.size() || t.size() < 2)
    throw std::invalid_argument("need at least two samples of time and force");
  std::vector<double> filtered = force;
  std::size_t n = t.size();
  if (options.lowpass_hz > 0.0) {
    const double dt = t[1] - t[0];
    // A run writes its last state whatever --every says: a final row closer
    // than the others is left out rather than refused.
    if (n > 2 && !(std::abs((t[n - 1] - t[n - 2]) - dt) <= kEvenSpacing * dt) && t[n - 1] - t[n - 2] < dt) --n;
    filtered.resize(n);
    for (std::size_t i = 1; i < n; ++i) {
      if (!(std::abs((t[i] - t[i - 1]) - dt) <= kEvenSpacing * dt)) {
        std::ostringstream os;
        os << "the samples are not evenly spaced (t = " << t[i - 1] << " to " << t[i] << " s against " << dt
           << " s at the start); the filter needs rows every step or every N steps (mbfe simulate --every N)";
        throw std::invalid_argument(os.str());
      }
    }
    filtered = sosfiltfilt(butterworth_lowpass(options.order, options.lowpass_hz, 1.0 / dt),
                        std::vector<double>(force.begin(), force.begin() + static_cast<std::ptrdiff_t>(n)));
  }
  ForceStatistics s;
  double sum = 0.0, sum2 = 0.0;
  int lost = 0;
  s.max = -INFINITY;
  s.min = INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    if (t[i] < options.from || t[i] > options.to) continue;
    ++s.samples;
    sum += filtered[i];
    s.max = std::max(s.max, filtered[i]);
    s.min = std::min(s.min, filtered[i]);
    if (force[i] <= 0.0) ++lost;
  }
  if (s.samples == 0) throw std::invalid_argument("no sample lies in the window");
  s.mean = sum / s.samples;
  for (std::size_t i = 0; i < n; ++i) {
    if (t[i] < options.from || t[i] > options.to) continue;
    sum2 += (filtered[i] - s.mean) * (filtered[i] - s.mean);
  }
  s.std = std::sqrt(sum2 / s.samples);
  s.statistical_max = s.mean + 3.0 * s.std;
  s.statistical_min = s.mean - 3.0 * s.std;
  s.loss_percent = 100.0 * lost / s.samples;
  return s;
}

}  // namespace mbfe::runtime
