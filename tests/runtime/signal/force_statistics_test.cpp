// The contact-force statistics: windowed statistics of the filtered force
// against the same sums over SciPy's filtered signal
// (tests/runtime/signal/filter_golden.csv, made by
// tests/runtime/signal/make_filter_golden.py, the command in its header).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "runtime/signal/force_statistics.h"
#include "tests/support/filter_golden.h"

namespace mbfe::runtime {
namespace {

// The filtered signal (~100 N) against SciPy's: ~1e-11 N of rounding
// (butterworth_test.cpp).
constexpr double kSignalTol = 1e-8;

using Golden = test::FilterGolden;

TEST(ForceStatistics, WindowedStatisticsOfTheFilteredForceAndTheLossOfTheRawOne) {
  const Golden g = test::read_filter_golden();
  ForceStatisticsOptions o;
  o.lowpass_hz = 20.0;
  o.from = 0.5;
  o.to = 1.5;
  const ForceStatistics s = force_statistics(g.t, g.x, o);
  // Oracle: the same sums over SciPy's filtered signal, here.
  double sum = 0, sum2 = 0, mx = -1e300, mn = 1e300;
  int n = 0, lost = 0;
  for (std::size_t i = 0; i < g.t.size(); ++i) {
    if (g.t[i] < 0.5 || g.t[i] > 1.5) continue;
    ++n;
    sum += g.y[i];
    mx = std::max(mx, g.y[i]);
    mn = std::min(mn, g.y[i]);
    if (g.x[i] <= 0.0) ++lost;
  }
  const double mean = sum / n;
  for (std::size_t i = 0; i < g.t.size(); ++i)
    if (g.t[i] >= 0.5 && g.t[i] <= 1.5) sum2 += (g.y[i] - mean) * (g.y[i] - mean);
  const double sd = std::sqrt(sum2 / n);
  EXPECT_EQ(s.samples, 1001);
  EXPECT_EQ(n, 1001);
  EXPECT_NEAR(s.mean, mean, kSignalTol);
  EXPECT_NEAR(s.std, sd, kSignalTol);
  EXPECT_NEAR(s.statistical_max, mean + 3 * sd, 4 * kSignalTol);
  EXPECT_NEAR(s.statistical_min, mean - 3 * sd, 4 * kSignalTol);
  EXPECT_NEAR(s.max, mx, kSignalTol);
  EXPECT_NEAR(s.min, mn, kSignalTol);
  // 20 zero samples of 1001 (t = 0.700 .. 0.719 s).
  EXPECT_EQ(lost, 20);
  EXPECT_NEAR(s.loss_percent, 100.0 * 20 / 1001, 1e-12);
  // The 60 Hz component is gone: the filtered mean equals the raw mean to the
  // few N the zero dip moves it, and the peak drops.
  ForceStatisticsOptions raw = o;
  raw.lowpass_hz = 0.0;
  const ForceStatistics r = force_statistics(g.t, g.x, raw);
  EXPECT_GT(r.max, s.max + 5.0);
}

TEST(ForceStatistics, AShortLastIntervalIsLeftOutAndAnUnevenOneInsideRefused) {
  // A run's last row comes at t_end whatever --every: left out when filtering.
  std::vector<double> t, f;
  for (int i = 0; i < 100; ++i) {
    t.push_back(i * 1e-3);
    f.push_back(100.0);
  }
  t.push_back(0.0994);
  f.push_back(-1000.0);  // would show in min and loss if it counted
  ForceStatisticsOptions o;
  o.lowpass_hz = 20.0;
  const ForceStatistics s = force_statistics(t, f, o);
  EXPECT_EQ(s.samples, 100);
  EXPECT_NEAR(s.min, 100.0, 1e-9);
  EXPECT_EQ(s.loss_percent, 0.0);
}

TEST(ForceStatistics, UnevenSamplesAreRefusedWhenFiltering) {
  std::vector<double> t{0.0, 0.001, 0.002, 0.0035}, f{1, 2, 3, 4};
  ForceStatisticsOptions o;
  o.lowpass_hz = 20.0;
  EXPECT_THROW(force_statistics(t, f, o), std::invalid_argument);
  o.lowpass_hz = 0.0;
  EXPECT_NO_THROW(force_statistics(t, f, o));
}

}  // namespace
}  // namespace mbfe::runtime
