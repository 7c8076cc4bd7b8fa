// The zero-phase Butterworth low-pass of the contact-force statistics against
// SciPy: its second-order sections and sosfiltfilt at orders 1..8 and cut-offs
// 0.4 to 1e-4 of the sample rate (tests/runtime/signal/sos_golden.csv, made by
// tests/runtime/signal/make_sos_golden.py), a force-like signal against
// scipy.signal.filtfilt (tests/runtime/signal/filter_golden.csv, made by
// tests/runtime/signal/make_filter_golden.py; the commands are in the files'
// headers), and closed forms: a constant passes unchanged (gain 1 at 0 Hz,
// steady-state start), a slow sine passes with gain |H|^2 = 1 / (1 + (f /
// fc)^(2 order)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "runtime/signal/butterworth.h"
#include "tests/support/filter_golden.h"

namespace mbfe::runtime {
namespace {

// Coefficients: the same formulas in another order of rounding (numpy's prod
// and tan against ours); seen to agree to 1 ulp of each section's largest
// coefficient.
constexpr double kCoefficientTol = 1e-14;
// sosfiltfilt of the 400-sample golden signal (|x| ~ 150) against SciPy's,
// relative to max |x|. Both recursions round at ~1e-16 and the rounding of a
// section with poles at distance d from z = 1 grows as 1 / d^2, d ~ 2 pi
// cut-off: seen up to 4e-12 down to cut-offs of 1e-3 of the sample rate,
// 3e-10 at 1e-4.
constexpr double kSignalTol = 1e-11;
constexpr double kSignalTolLowestCutoff = 2e-9;
// The force-like signal (~100 N) through SciPy's transfer-function filtfilt,
// well conditioned at order 4 and 20 Hz of 1 kHz: ~1e-11 N of rounding.
constexpr double kForceTol = 1e-8;

SosFilter sections_of(const test::SosGoldenCase& c) {
  SosFilter f;
  for (std::size_t i = 0; i + 6 <= c.sections.size(); i += 6) {
    Biquad s;
    std::copy(c.sections.begin() + static_cast<std::ptrdiff_t>(i),
              c.sections.begin() + static_cast<std::ptrdiff_t>(i + 6), s.begin());
    f.sections.push_back(s);
  }
  return f;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

TEST(Butterworth, SectionsMatchScipyAtEveryOrderAndCutoff) {
  const test::SosGolden g = test::read_sos_golden();
  ASSERT_EQ(g.cases.size(), 40u);
  for (const test::SosGoldenCase& c : g.cases) {
    const SosFilter f = butterworth_lowpass(c.order, c.cutoff, 1.0);
    const SosFilter ref = sections_of(c);
    ASSERT_EQ(f.sections.size(), ref.sections.size()) << "order " << c.order;
    ASSERT_EQ(f.sections.size(), static_cast<std::size_t>((c.order + 1) / 2));
    for (std::size_t s = 0; s < f.sections.size(); ++s) {
      const Biquad& got = f.sections[s];
      const Biquad& want = ref.sections[s];
      const double b_scale = std::max({std::abs(want[0]), std::abs(want[1]), std::abs(want[2])});
      for (int k = 0; k < 6; ++k) {
        const double scale = k < 3 ? b_scale : 1.0;
        EXPECT_NEAR(got[static_cast<std::size_t>(k)], want[static_cast<std::size_t>(k)], kCoefficientTol * scale)
            << "order " << c.order << ", cut-off " << c.cutoff << ", section " << s << ", coefficient " << k;
      }
    }
  }
}

TEST(Butterworth, ZeroPhaseFilterMatchesScipysSosfiltfiltAtEveryOrderAndCutoff) {
  const test::SosGolden g = test::read_sos_golden();
  const double scale = max_abs(g.x);
  for (const test::SosGoldenCase& c : g.cases) {
    const double tol = (c.cutoff < 1e-3 ? kSignalTolLowestCutoff : kSignalTol) * scale;
    // Our design and our filter; SciPy's sections through our filter (the
    // filter alone).
    const std::vector<double> y = sosfiltfilt(butterworth_lowpass(c.order, c.cutoff, 1.0), g.x);
    const std::vector<double> y_ref_sections = sosfiltfilt(sections_of(c), g.x);
    ASSERT_EQ(y.size(), c.y.size());
    EXPECT_LT(max_difference(y, c.y), tol) << "order " << c.order << ", cut-off " << c.cutoff;
    EXPECT_LT(max_difference(y_ref_sections, c.y), tol) << "order " << c.order << ", cut-off " << c.cutoff;
  }
}

TEST(Butterworth, PaddingIsScipysThreeTimesOrderPlusOne) {
  for (int order = 1; order <= 8; ++order)
    EXPECT_EQ(sosfiltfilt_padding(butterworth_lowpass(order, 0.1, 1.0)), static_cast<std::size_t>(3 * (order + 1)));
  // A signal of exactly the padding's length is refused, one more is taken.
  const SosFilter f = butterworth_lowpass(4, 0.1, 1.0);
  EXPECT_THROW(sosfiltfilt(f, std::vector<double>(15, 1.0)), std::invalid_argument);
  EXPECT_NO_THROW(sosfiltfilt(f, std::vector<double>(16, 1.0)));
}

TEST(Butterworth, ForceLikeSignalMatchesScipysFiltfilt) {
  const test::FilterGolden g = test::read_filter_golden();
  ASSERT_EQ(g.t.size(), 2000u);
  const std::vector<double> y = sosfiltfilt(butterworth_lowpass(4, 20.0, 1000.0), g.x);
  EXPECT_LT(max_difference(y, g.y), kForceTol);
}

// A constant is a constant after the filter: gain 1 at 0 Hz and initial
// states at the steady state. The one polynomial of order 2 N this filter was
// built as before lost that: 5 at 0.01 Hz of 1 kHz came out as 0.0039.
TEST(Butterworth, AConstantPassesUnchangedDownToTheLowestCutoff) {
  // The rounding of the recursion grows as (sample rate / cut-off)^2 ~ 1e10
  // times 1e-16 at the lowest cut-off taken: seen up to 9e-8.
  constexpr double kConstantTol = 1e-6;
  for (int order = 1; order <= 8; ++order) {
    for (const double fraction : {0.4, 1e-2, 1e-4, kMinCutoffFraction}) {
      const std::vector<double> y = sosfiltfilt(butterworth_lowpass(order, fraction * 1000.0, 1000.0),
                                                std::vector<double>(3000, 5.0));
      for (double v : y) ASSERT_NEAR(v, 5.0, kConstantTol * 5.0) << "order " << order << ", cut-off " << fraction;
    }
  }
}

// A sine far below the cut-off, sampled fast: the cases that blew up as one
// polynomial (order 8 at 20 Hz of 10 kHz: a maximum of 9.3e211; order 6 at
// 5 Hz: 1.9e28; order 5 at 20 Hz of 40 kHz: 0.17 % off). Oracle: zero phase
// and gain |H(f)|^2 = 1 / (1 + (f / fc)^(2 order)) (the bilinear transform's
// warping is ~1e-6 at these frequencies), once the ends' start-up has passed.
TEST(Butterworth, ASlowSineSampledFastPassesWithItsGain) {
  struct Case {
    int order;
    double cutoff_hz, sample_hz, sine_hz;
  };
  constexpr double kSineTol = 1e-7;  // of the amplitude: start-up left 2 s in (seen 5e-9), warping, rounding
  for (const Case& c : {Case{8, 20.0, 10000.0, 2.0}, Case{6, 5.0, 10000.0, 0.5}, Case{5, 20.0, 40000.0, 2.0}}) {
    // 8 s: the slowest pole pair of order 6 at 5 Hz decays at 2 pi 5 sin(pi / 12)
    // = 8 per s, so that 2 s from the ends the start-up is gone to ~1e-7.
    const std::size_t n = static_cast<std::size_t>(8.0 * c.sample_hz);
    std::vector<double> x(n);
    for (std::size_t i = 0; i < n; ++i) x[i] = 100.0 + 10.0 * std::sin(2.0 * M_PI * c.sine_hz * i / c.sample_hz);
    const std::vector<double> y = sosfiltfilt(butterworth_lowpass(c.order, c.cutoff_hz, c.sample_hz), x);
    const double gain = 1.0 / (1.0 + std::pow(c.sine_hz / c.cutoff_hz, 2.0 * c.order));
    for (std::size_t i = n / 4; i < 3 * n / 4; ++i) {
      const double expected = 100.0 + gain * 10.0 * std::sin(2.0 * M_PI * c.sine_hz * i / c.sample_hz);
      ASSERT_NEAR(y[i], expected, kSineTol * 10.0) << "order " << c.order << " at " << c.cutoff_hz << " Hz of "
                                                   << c.sample_hz << " Hz, sample " << i;
    }
  }
}

TEST(Butterworth, RefusesWhatItCannotFilter) {
  EXPECT_THROW(butterworth_lowpass(4, 600.0, 1000.0), std::invalid_argument);  // above Nyquist
  EXPECT_THROW(butterworth_lowpass(4, 500.0, 1000.0), std::invalid_argument);  // at Nyquist
  EXPECT_THROW(butterworth_lowpass(0, 20.0, 1000.0), std::invalid_argument);
  EXPECT_THROW(butterworth_lowpass(9, 20.0, 1000.0), std::invalid_argument);
  // Below kMinCutoffFraction of the sample rate the rounding would show.
  EXPECT_THROW(butterworth_lowpass(4, 0.5 * kMinCutoffFraction * 1000.0, 1000.0), std::invalid_argument);
  EXPECT_NO_THROW(butterworth_lowpass(4, kMinCutoffFraction * 1000.0, 1000.0));
}

}  // namespace
}  // namespace mbfe::runtime
