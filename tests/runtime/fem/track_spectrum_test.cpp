// The track spectra against their published formulas, and a random profile's
// estimated one-sided PSD against the spectrum it was drawn from: a
// periodogram (direct DFT, Hann window) of profiles from 16 seeds, averaged
// over the seeds and over bands of frequency.
#include "runtime/fem/track_spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

namespace mbfe::runtime {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFormulaTol = 1e-12;  // relative: the same arithmetic in another order

TEST(TrackSpectrum, FormulasGiveThePublishedValues) {
  // FRA class 6 at Omega = 1 rad/m: A_v Omega_c^2 / (Omega^2 (Omega^2 + Omega_c^2)), cm^2 -> m^2.
  const double c2 = 0.8245 * 0.8245;
  EXPECT_NEAR(track_psd(ir::TrackSpectrum::kFra, 6, 1.0), 1e-4 * 0.0339 * c2 / (1.0 + c2),
              kFormulaTol * 1e-6);
  EXPECT_NEAR(track_psd(ir::TrackSpectrum::kFra, 1, 0.5), 1e-4 * 1.2107 * c2 / (0.25 * (0.25 + c2)),
              kFormulaTol * 1e-3);
  // German low disturbance at Omega = 0.3 rad/m.
  const double g2 = 0.8246 * 0.8246, r2 = 0.0206 * 0.0206;
  EXPECT_NEAR(track_psd(ir::TrackSpectrum::kGerman, 0, 0.3), 4.032e-7 * g2 / ((0.09 + r2) * (0.09 + g2)),
              kFormulaTol * 1e-5);
  EXPECT_NEAR(track_psd(ir::TrackSpectrum::kGerman, 1, 0.3) / track_psd(ir::TrackSpectrum::kGerman, 0, 0.3),
              1.080e-6 / 4.032e-7, kFormulaTol);
  EXPECT_THROW(track_psd(ir::TrackSpectrum::kFra, 7, 1.0), std::invalid_argument);
  EXPECT_THROW(track_psd(ir::TrackSpectrum::kGerman, 2, 1.0), std::invalid_argument);
}

TEST(TrackSpectrum, ASeedGivesOneProfileAndAnotherSeedAnother) {
  const HarmonicProfile a = spectrum_profile(ir::TrackSpectrum::kFra, 5, 1.0, 80.0, 30.0, 7);
  const HarmonicProfile b = spectrum_profile(ir::TrackSpectrum::kFra, 5, 1.0, 80.0, 30.0, 7);
  const HarmonicProfile c = spectrum_profile(ir::TrackSpectrum::kFra, 5, 1.0, 80.0, 30.0, 8);
  EXPECT_EQ(a.phase, b.phase);
  EXPECT_EQ(a.omega, b.omega);
  EXPECT_NE(a.phase, c.phase);
  // Harmonics inside the band.
  for (double o : a.omega) {
    EXPECT_GE(o, 2 * kPi / 80.0);
    EXPECT_LE(o, 2 * kPi / 1.0);
  }
}

TEST(TrackSpectrum, DerivativesOfTheSumAreThoseOfItsTerms) {
  const HarmonicProfile p = spectrum_profile(ir::TrackSpectrum::kGerman, 1, 2.0, 50.0, 40.0, 3);
  constexpr double h = 1e-3;              // m: central differences
  constexpr double kDifferenceTol = 1e-4;  // relative to the derivative's scale (h^2 omega^2 / 6 ~ 2e-6)
  constexpr double kDifferenceFloor = 1e-12;  // absolute, where the derivative itself is near 0: round-off / h
  for (double s : {0.0, 7.3, 25.0}) {
    double r, dr, ddr, rp, drp, ddrp, rm, drm, ddrm;
    p.evaluate(s, r, dr, ddr);
    p.evaluate(s + h, rp, drp, ddrp);
    p.evaluate(s - h, rm, drm, ddrm);
    EXPECT_NEAR(dr, (rp - rm) / (2 * h), kDifferenceTol * std::abs(dr) + kDifferenceFloor);
    EXPECT_NEAR(ddr, (drp - drm) / (2 * h), kDifferenceTol * std::abs(ddr) + kDifferenceFloor);
  }
}

// The estimate: profiles of kLength m sampled every kDx m, a Hann-windowed
// periodogram P(Omega_m) = 2 dx |sum w_n r_n e^{-i Omega_m x_n}|^2 / (2 pi sum w_n^2)
// (one-sided, per rad/m) at Omega_m = 2 pi m / kLength, averaged over kSeeds
// seeds and over the bins of each band. Each band holds about 20 bins, so the
// average is over ~320 (correlated pairs of) periodogram values, each a
// chi-squared variable with 2 degrees of freedom: a relative standard error
// of about 1/sqrt(160) = 8 %, and the spectrum's slope across a band and the
// window's leakage add a few percent. 25 % is three standard errors.
constexpr double kLength = 400.0;
constexpr double kDx = 0.25;
constexpr int kSeeds = 16;
constexpr double kPsdTol = 0.25;

TEST(TrackSpectrum, EstimatedPsdOfRandomProfilesFollowsTheFormula) {
  for (const auto& [spectrum, track_class] :
       {std::pair{ir::TrackSpectrum::kFra, 4}, std::pair{ir::TrackSpectrum::kGerman, 0}}) {
    const double lambda_min = 2.0, lambda_max = 50.0;
    const int n = static_cast<int>(kLength / kDx);
    std::vector<double> window(n);
    double w2 = 0.0;
    for (int k = 0; k < n; ++k) {
      window[k] = 0.5 - 0.5 * std::cos(2 * kPi * k / n);
      w2 += window[k] * window[k];
    }
    // Bins strictly inside the band (the window smears one bin each side).
    const int m_lo = static_cast<int>(std::ceil(kLength / lambda_max)) + 2;
    const int m_hi = static_cast<int>(std::floor(kLength / lambda_min)) - 2;
    std::vector<double> estimate(m_hi + 1, 0.0);
    for (int seed = 0; seed < kSeeds; ++seed) {
      const HarmonicProfile p = spectrum_profile(spectrum, track_class, lambda_min, lambda_max, kLength, 100 + seed);
      std::vector<double> r(n);
      for (int k = 0; k < n; ++k) {
        double dr, ddr;
        p.evaluate(k * kDx, r[k], dr, ddr);
      }
      for (int m = m_lo; m <= m_hi; ++m) {
        const double omega = 2 * kPi * m / kLength;
        std::complex<double> x = 0.0;
        for (int k = 0; k < n; ++k) x += window[k] * r[k] * std::polar(1.0, -omega * k * kDx);
        estimate[m] += 2 * kDx * std::norm(x) / (2 * kPi * w2) / kSeeds;
      }
    }
    constexpr int kBand = 20;
    int bands = 0;
    for (int m0 = m_lo; m0 + kBand - 1 <= m_hi; m0 += kBand) {
      double est = 0.0, formula = 0.0;
      for (int m = m0; m < m0 + kBand; ++m) {
        est += estimate[m];
        formula += track_psd(spectrum, track_class, 2 * kPi * m / kLength);
      }
      EXPECT_NEAR(est / formula, 1.0, kPsdTol) << "spectrum " << static_cast<int>(spectrum) << ", bins " << m0
                                               << ".." << m0 + kBand - 1;
      ++bands;
    }
    EXPECT_GE(bands, 8);
  }
}

TEST(TrackSpectrum, VarianceIsTheIntegralOfTheSpectrumOverTheBand) {
  // Over a long stretch the mean square of the sum is sum a_k^2 / 2 = sum S(Omega_k) dOmega,
  // the midpoint-like rule for the integral; Simpson's rule on a fine grid is the oracle.
  const double lo = 2 * kPi / 50.0, hi = 2 * kPi / 2.0;
  const int n = 20000;
  double integral = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double o = lo + (hi - lo) * k / n;
    integral += (k == 0 || k == n ? 1 : (k % 2 ? 4 : 2)) * track_psd(ir::TrackSpectrum::kFra, 6, o);
  }
  integral *= (hi - lo) / n / 3;
  double mean_square = 0.0;
  constexpr int kSeedCount = 20;
  for (int seed = 0; seed < kSeedCount; ++seed) {
    const HarmonicProfile p = spectrum_profile(ir::TrackSpectrum::kFra, 6, 2.0, 50.0, 400.0, seed);
    for (double a : p.amplitude) mean_square += a * a / 2 / kSeedCount;
  }
  // Random harmonic positions within their cells: the sum scatters about the
  // integral by a few 1e-3 relative where S falls as Omega^-4.
  constexpr double kVarianceTol = 0.01;
  EXPECT_NEAR(mean_square / integral, 1.0, kVarianceTol);
}

}  // namespace
}  // namespace mbfe::runtime
