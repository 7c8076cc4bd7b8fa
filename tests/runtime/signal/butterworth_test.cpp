// The zero-phase Butterworth low-pass of the contact-force statistics against
// SciPy (tests/runtime/signal/filter_golden.csv, made by
// tests/runtime/signal/make_filter_golden.py, the command in its header), and
// the statistics against sums computed here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/signal/butterworth.h"
#include "runtime/signal/force_statistics.h"
#include "tests/support/filter_golden.h"

namespace mbfe::runtime {
namespace {

// The coefficients are printed to 17 digits and computed by the same
// formulas in another order: agreement to ~1e-14 relative.
constexpr double kCoefficientTol = 1e-12;
// The filtered signal (~100 N) goes through 2 x 2000 recursive steps of a
// filter with poles near 0.93: rounding grows to ~1e-11 N.
constexpr double kSignalTol = 1e-8;

using Golden = test::FilterGolden;

TEST(Butterworth, DesignAndZeroPhaseFilterMatchScipy) {
  const Golden g = test::read_filter_golden();
  ASSERT_EQ(g.t.size(), 2000u);
  const IirFilter f = butterworth_lowpass(4, 20.0, 1000.0);
  ASSERT_EQ(f.b.size(), g.b.size());
  ASSERT_EQ(f.a.size(), g.a.size());
  for (std::size_t i = 0; i < f.b.size(); ++i) {
    EXPECT_NEAR(f.b[i], g.b[i], kCoefficientTol * std::abs(g.b[i])) << "b" << i;
    EXPECT_NEAR(f.a[i], g.a[i], kCoefficientTol * std::max(1.0, std::abs(g.a[i]))) << "a" << i;
  }
  const std::vector<double> y = filtfilt(f, g.x);
  double worst = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i) worst = std::max(worst, std::abs(y[i] - g.y[i]));
  EXPECT_LT(worst, kSignalTol);
}

TEST(Butterworth, RefusesWhatItCannotFilter) {
  EXPECT_THROW(butterworth_lowpass(4, 600.0, 1000.0), std::invalid_argument);  // above Nyquist
  EXPECT_THROW(butterworth_lowpass(0, 20.0, 1000.0), std::invalid_argument);
  EXPECT_THROW(filtfilt(butterworth_lowpass(4, 20.0, 1000.0), std::vector<double>(10, 1.0)), std::invalid_argument);
}

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
