// The noise of a linearisation's eigenvalues (runtime/coupled/linearization.h):
// positive real parts up to kLinearizationNoiseRel max |lambda| are not
// growth, eigenvalues up to kZeroModeRel max |lambda| are zero modes. The
// spectra are those measured on the shipped models
// (docs/damping-adjustment.md, "The stability advisor").
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <vector>

#include "runtime/coupled/linearization.h"
#include "runtime/advisor/model_spectrum.h"

namespace mbfe::runtime {
namespace {

using cplx = std::complex<double>;

bool contains(const StateSpectrum& s, cplx l) { return std::find(s.eigenvalues.begin(), s.eigenvalues.end(), l) != s.eigenvalues.end(); }

TEST(LinearizationNoise, RoundOffGrowthIsNotGrowthAndZeroModesAreZero) {
  // The adjusted moving-mass bridge at its static start: the fastest eigenvalue
  // -2740.3 (the cap), the driven carriage's zero pair (0 and +2.3e-13), an
  // undamped deck mode at 12.8 rad/s with Re = +3.1e-6 (1.1e-9 max |lambda|),
  // a damped mode.
  const StateSpectrum measured = spectrum_from_eigenvalues(
      {{-2740.3, 0.0}, {0.0, 0.0}, {2.3e-13, 0.0}, {3.1e-6, 12.8}, {3.1e-6, -12.8}, {-0.5, 70.7}, {-0.5, -70.7}});
  // split_growing (Re above 1e-9 of each |lambda|) counts three.
  EXPECT_EQ(split_growing(measured).growing, 3);
  EXPECT_EQ(growing_beyond_noise(measured), 0);
  const StateSpectrum zeroed = with_zero_modes(measured);
  EXPECT_EQ(std::count(zeroed.eigenvalues.begin(), zeroed.eigenvalues.end(), cplx(0.0, 0.0)), 2);
  EXPECT_TRUE(contains(zeroed, {3.1e-6, 12.8}));  // not a zero mode: kept as it is
  EXPECT_TRUE(contains(zeroed, {-0.5, 70.7}));
}

TEST(LinearizationNoise, GrowthAboveTheNoiseIsGrowthAndSlowModesAreNotZero) {
  // A pendulum released above its pivot inside a stiff model: +0.3 1/s growth
  // (and a pair at +2e-2 on 50 rad/s) against a fastest eigenvalue of 1e5:
  // 3e-6 and 2e-7 of it, above 1e-7.
  const StateSpectrum growing =
      spectrum_from_eigenvalues({{-1e5, 0.0}, {0.3, 0.0}, {-0.3, 0.0}, {2e-2, 50.0}, {2e-2, -50.0}});
  EXPECT_EQ(growing_beyond_noise(growing), 3);
  // The original double pendulum on the beam's first pair: -8.9e-4 +- 2.3i,
  // 2e-8 of its fastest eigenvalue 1.3e8 in modulus: not a zero mode.
  const StateSpectrum slow = with_zero_modes(spectrum_from_eigenvalues({{-1.3e8, 0.0}, {-8.9e-4, 2.3}, {-8.9e-4, -2.3}}));
  EXPECT_TRUE(contains(slow, {-8.9e-4, 2.3}));
  EXPECT_TRUE(contains(with_zero_modes(spectrum_from_eigenvalues({{-1e5, 0.0}, {-1e-4, 0.0}})), {-1e-4, 0.0}));
}

}  // namespace
}  // namespace mbfe::runtime
