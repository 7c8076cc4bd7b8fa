// middle_of_spectrum: what fills a partial spectrum between its two ends. The
// oracle is the definition, on hand-made lists: the source's eigenvalues
// strictly between the slow end's largest modulus and the fast end's smallest,
// with Re <= 0.
#include "runtime/coupled/tangent_spectrum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <vector>

namespace mbfe::runtime {
namespace {

using C = std::complex<double>;

StateSpectrum partial_of(std::vector<C> eigenvalues) {
  StateSpectrum s = spectrum_from_eigenvalues(std::move(eigenvalues));
  s.complete = false;
  return s;
}

TEST(MiddleOfSpectrum, TakesTheSourceBetweenTheEndsOnly) {
  // Slow end up to |lambda| = 10, fast end (the last 2) from 1000.
  const StateSpectrum partial = partial_of({0.0, C(-1, 5), C(-1, -5), C(-2, 9.8), C(-50, 1000), C(-50, -1000)});
  const StateSpectrum source = spectrum_from_eigenvalues(
      {C(-0.5, 9), C(-0.5, -9), C(-3, 100), C(-3, -100), C(-0.1, 999), C(-0.1, -999), C(-5, 2000), C(1e-3, 50), -500.0});
  std::vector<C> middle = middle_of_spectrum(partial, source, 2);
  // |9 +- 0.5i| < 10 (slow end), 2000 above 1000 (fast end), Re > 0 growth: left out.
  const std::vector<C> expected = {C(-3, 100), C(-3, -100), -500.0, C(-0.1, 999), C(-0.1, -999)};
  ASSERT_EQ(middle.size(), expected.size());
  for (const C& e : expected) EXPECT_NE(std::find(middle.begin(), middle.end(), e), middle.end()) << e;
}

TEST(MiddleOfSpectrum, NothingForACompleteSpectrumOrOneWithoutAMiddle) {
  StateSpectrum complete = spectrum_from_eigenvalues({C(-1, 5), C(-1, -5), C(-50, 1000), C(-50, -1000)});
  const StateSpectrum source = spectrum_from_eigenvalues({C(-3, 100), C(-3, -100)});
  EXPECT_TRUE(middle_of_spectrum(complete, source, 2).empty());
  const StateSpectrum only_fast = partial_of({C(-50, 1000), C(-50, -1000)});
  EXPECT_TRUE(middle_of_spectrum(only_fast, source, 2).empty());
}

}  // namespace
}  // namespace mbfe::runtime
