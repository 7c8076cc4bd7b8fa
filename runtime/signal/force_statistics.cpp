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

/// Neumaier's compensated sum: the rounding of each addition is kept and
/// added back at the end, so the error does not grow with the count.
class CompensatedSum {
 public:
  void add(double v) {
    const double t = sum_ + v;
    compensation_ += std::abs(sum_) >= std::abs(v) ? (sum_ - t) + v : (v - t) + sum_;
    sum_ = t;
  }
  double value() const { return sum_ + compensation_; }

 private:
  double sum_ = 0.0, compensation_ = 0.0;
};

template <class It>
double largest_magnitude(It begin, It end) {
  double out = 0.0;
  for (It it = begin; it != end; ++it) out = std::max(out, std::abs(*it));
  return out;
}

}  // namespace

ForceStatistics force_statistics(const std::vector<double>& t, const std::vector<double>& force,
                                 const ForceStatisticsOptions& options) {
  if (t.size() != force.size() || t.size() < 2)
    throw std::invalid_argument("need at least two samples of time and force");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]) || !std::isfinite(force[i])) {
      std::ostringstream os;
      if (!std::isfinite(t[i]))
        os << "the time is " << t[i];
      else
        os << "the value is " << force[i];
      os << "; the statistics take finite numbers only";
      throw BadSample(i, os.str());
    }
    if (i > 0 && !(t[i] > t[i - 1])) {
      std::ostringstream os;
      os.precision(17);
      os << "t = " << t[i] << " s is not after the row before (t = " << t[i - 1]
         << " s); times must increase strictly";
      throw BadSample(i, os.str());
    }
  }
  std::vector<double> filtered = force;
  std::size_t n = t.size();
  if (options.lowpass_hz > 0.0) {
    const double dt = t[1] - t[0];
    // A run writes its last state whatever --every says: a final row closer
    // than the others is left out rather than refused.
    if (n > 2 && !(std::abs((t[n - 1] - t[n - 2]) - dt) <= kEvenSpacing * dt) && t[n - 1] - t[n - 2] < dt) --n;
    for (std::size_t i = 1; i < n; ++i) {
      if (!(std::abs((t[i] - t[i - 1]) - dt) <= kEvenSpacing * dt)) {
        std::ostringstream os;
        os << "the samples are not evenly spaced (t = " << t[i - 1] << " to " << t[i] << " s against " << dt
           << " s at the start); the filter needs rows every step or every N steps";
        throw std::invalid_argument(os.str());
      }
    }
    // The filter is linear: run it on the signal scaled to |x| <= 1, so that
    // its odd extension (2 x[0] - x[i]) cannot overflow.
    const double scale = largest_magnitude(force.begin(), force.begin() + static_cast<std::ptrdiff_t>(n));
    std::vector<double> scaled(force.begin(), force.begin() + static_cast<std::ptrdiff_t>(n));
    if (scale > 0.0)
      for (double& v : scaled) v /= scale;
    filtered = sosfiltfilt(butterworth_lowpass(options.order, options.lowpass_hz, 1.0 / dt), scaled);
    for (double& v : filtered) {
      v *= scale;
      if (!std::isfinite(v)) throw std::invalid_argument("the filtered signal exceeds the largest double");
    }
  }
  std::vector<double> window;
  ForceStatistics s;
  int lost = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (t[i] < options.from || t[i] > options.to) continue;
    window.push_back(filtered[i]);
    if (force[i] <= 0.0) ++lost;
  }
  if (window.empty()) throw std::invalid_argument("no sample lies in the window");
  s.samples = static_cast<int>(window.size());
  s.max = *std::max_element(window.begin(), window.end());
  s.min = *std::min_element(window.begin(), window.end());
  // Sums of the values divided by the largest |value| (each term in [-1, 1],
  // so no sum of up to 2^53 terms overflows), compensated.
  const double scale = largest_magnitude(window.begin(), window.end());
  const double count = static_cast<double>(window.size());
  if (scale > 0.0) {
    CompensatedSum sum;
    for (double v : window) sum.add(v / scale);
    const double mean_scaled = sum.value() / count;
    CompensatedSum squares;
    for (double v : window) {
      const double d = v / scale - mean_scaled;
      squares.add(d * d);
    }
    s.mean = scale * mean_scaled;
    s.std = scale * std::sqrt(squares.value() / count);
  }
  s.statistical_max = s.mean + 3.0 * s.std;
  s.statistical_min = s.mean - 3.0 * s.std;
  if (!std::isfinite(s.statistical_max) || !std::isfinite(s.statistical_min)) {
    std::ostringstream os;
    os << "mean +- 3 std (mean " << s.mean << ", std " << s.std << ") exceeds the largest double";
    throw std::invalid_argument(os.str());
  }
  s.loss_percent = 100.0 * lost / s.samples;
  return s;
}

}  // namespace mbfe::runtime
