// The stability advisor against known limits and against actual stepping of
// y' = lambda y just inside and just outside each predicted limit.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>

#include "runtime/integrators/integrator.h"
#include "tests/runtime/integrators/test_systems.h"
#include "runtime/coupled/linearization.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::runtime {
namespace {

using cplx = std::complex<double>;

// Companion-matrix roots and 60 bisections: limits good to ~1e-10 relative.
constexpr double kLimitTol = 1e-8;

// RK4: roots of |R|^2 - 1 from a companion matrix, ~1e-12 relative.
constexpr double kRootLimitTol = 1e-9;
// Multistep methods: the boundary-locus crossing is bisected to ~1e-9.
constexpr double kLocusLimitTol = 1e-7;
// 0.1577 is the leading-order estimate s^3 = 4e-3, good to its last digit.
constexpr double kLeadingOrderTol = 1e-3;

TEST(StepLimits, KnownValues) {
  const auto fe = parse_integrator("forward_euler");
  const auto rk4 = parse_integrator("rk4");
  const auto mid = parse_integrator("explicit_midpoint");
  const auto ab2 = parse_integrator("ab2");
  EXPECT_NEAR(stable_step(fe, cplx(-1, 0)).h, 2.0, kLimitTol);
  EXPECT_NEAR(stable_step(fe, cplx(-3, 4)).h, 6.0 / 25.0, kLimitTol);
  EXPECT_EQ(stable_step(fe, cplx(0, 4)).kind, StepLimit::Kind::kNone);  // undamped mode
  EXPECT_NEAR(stable_step(rk4, cplx(-1, 0)).h, 2.785293563405282, kRootLimitTol);
  EXPECT_NEAR(stable_step(rk4, cplx(0, 1)).h, 2.0 * std::sqrt(2.0), kRootLimitTol);
  EXPECT_EQ(stable_step(mid, cplx(-1, 0)).kind, StepLimit::Kind::kNone);  // Fig. 3
  EXPECT_NEAR(stable_step(mid, cplx(0, 2)).h, 0.5, kLocusLimitTol);
  EXPECT_NEAR(stable_step(ab2, cplx(-1, 0)).h, 1.0, kLocusLimitTol);
  // AB2's principal root on the imaginary axis is 1 + (h omega)^4 / 4 + ...:
  // an undamped mode grows at every step size, as under forward Euler. (The
  // advisor used to call it "unconditional": rounding near the origin of the
  // boundary locus looked like a crossing.)
  EXPECT_EQ(stable_step(ab2, cplx(0, 1)).kind, StepLimit::Kind::kNone);
  EXPECT_EQ(stable_step(ab2, cplx(0, 4.338)).kind, StepLimit::Kind::kNone);
  // Slightly damped: the boundary Re z ~ -|z|^4 / 4 crosses the ray where
  // s^3 ~ 4 * 1e-3, s ~ 0.159.
  EXPECT_NEAR(stable_step(ab2, cplx(-1e-3, 1)).h, 0.1577, kLeadingOrderTol);
  for (const char* a : {"backward_euler", "trapezoid", "bdf2", "generalized_alpha"}) {
    EXPECT_EQ(stable_step(parse_integrator(a), cplx(-1e8, 0)).kind, StepLimit::Kind::kUnconditional) << a;
    EXPECT_EQ(stable_step(parse_integrator(a), cplx(-1, 1e3)).kind, StepLimit::Kind::kUnconditional) << a;
  }
  EXPECT_EQ(stable_step(fe, cplx(1, 0)).kind, StepLimit::Kind::kNone);
  // A spectrum: the most restrictive eigenvalue wins.
  const std::vector<cplx> spec{{-1, 0}, {-10, 0}, {-0.5, 3}, {0, 0}};
  const StepLimit s = stable_step(fe, spec);
  EXPECT_NEAR(s.h, std::min(0.2, 1.0 / 9.25), kLimitTol);
  EXPECT_EQ(s.critical, cplx(-0.5, 3));
}

TEST(StepLimits, GrowingModesAreSplitOffAndRoundingIsZeroed) {
  // A linearisation away from equilibrium: one real growth (0.3), one
  // undamped pair whose real part is rounding (+1e-12 of |lambda|), one damped pair.
  const StateSpectrum spectrum =
      spectrum_from_eigenvalues({{0.3, 0.0}, {5e-12, 5.0}, {5e-12, -5.0}, {-1.0, 2.0}, {-1.0, -2.0}});
  const SplitSpectrum split = split_growing(spectrum);
  EXPECT_EQ(split.growing, 1);
  ASSERT_EQ(split.limiting.eigenvalues.size(), 4u);
  for (const cplx& l : split.limiting.eigenvalues) EXPECT_LE(l.real(), 0.0);
  // Without the rounding fix the +5e-12 pair would make every method "none";
  // with it, RK4 is limited by the undamped pair (2 sqrt 2 / 5) and the
  // A-stable methods are unconditional again.
  const auto rk4 = parse_integrator("rk4");
  EXPECT_NEAR(stable_step(rk4, split.limiting.eigenvalues).h, 2.0 * std::sqrt(2.0) / 5.0, kRootLimitTol);
  EXPECT_EQ(stable_step(parse_integrator("backward_euler"), split.limiting.eigenvalues).kind,
            StepLimit::Kind::kUnconditional);
  EXPECT_EQ(stable_step(parse_integrator("forward_euler"), split.limiting.eigenvalues).kind,
            StepLimit::Kind::kNone);
}

/// max |y| over the last 200 of n steps of y' = lambda y from y0 = 1.
double tail_amplitude(const IntegratorSpec& m, cplx lambda, double h, int n) {
  testing::Scalar sys(lambda);
  auto st = make_stepper(m, sys);
  Eigen::VectorXd y = Eigen::Vector2d(1.0, 0.0);
  st->reset(0.0, y);
  double amp = 0.0;
  for (int k = 0; k < n; ++k) {
    st->step(k * h, h, y);
    if (k >= n - 200) amp = std::max(amp, y.norm());
    if (!std::isfinite(y.norm())) return INFINITY;
  }
  return amp;
}

// 2 % inside and 5 % outside the limit. Outside, the amplification per step
// exceeds 1 by at least ~3e-4 (the slowest case: forward Euler on the nearly
// undamped -0.2 + 5i), so 2e5 steps grow by e^30 or more; inside, the tail
// stays below the start (multistep transients included).
constexpr double kInside = 0.98, kOutside = 1.05;
constexpr int kSteps = 20000, kOutsideSteps = 200000;
constexpr double kGrown = 1e3, kBounded = 10.0;

TEST(StepLimits, SteppingConfirmsEveryFiniteLimit) {
  std::mt19937 rng(20240611);  // seeded: the same eigenvalues every run
  std::uniform_real_distribution<double> angle(100.0, 260.0), mag(0.1, 1e4);
  std::vector<cplx> lambdas{{-1, 0}, {-1e5, 0}, {-1, 1e-3}, {-0.2, 5}};
  for (int i = 0; i < 12; ++i) lambdas.push_back(std::polar(mag(rng), angle(rng) * M_PI / 180.0));
  int checked = 0;
  for (const auto& m : advisor_integrators()) {
    if (m.kind == IntegratorKind::kGeneralizedAlpha) continue;  // second-order form only
    for (const cplx l : lambdas) {
      const StepLimit lim = stable_step(m, l);
      if (lim.kind != StepLimit::Kind::kFinite) continue;
      ++checked;
      EXPECT_LT(tail_amplitude(m, l, kInside * lim.h, kSteps), kBounded) << m.name << " lambda " << l;
      EXPECT_GT(tail_amplitude(m, l, kOutside * lim.h, kOutsideSteps), kGrown) << m.name << " lambda " << l;
    }
  }
  EXPECT_GT(checked, 40);
}

TEST(StepLimits, NoneAndUnconditionalConfirmedByStepping) {
  // explicit midpoint, lambda = -1: unstable even at a tiny step.
  EXPECT_GT(tail_amplitude(parse_integrator("explicit_midpoint"), {-1, 0}, 0.01, 5000), kGrown);
  // A-stable methods at a huge step on a stiff eigenvalue.
  for (const char* a : {"backward_euler", "trapezoid", "bdf2"})
    EXPECT_LT(tail_amplitude(parse_integrator(a), {-1e6, 3e5}, 10.0, 2000), kBounded) << a;
}

TEST(StepLimits, UserLmmBoundaryLocus) {
  // Adams-Bashforth 3: real-axis limit 6/11.
  const auto ab3 = parse_integrator(
      "lmm:alpha=0,0,-1,1:beta=0.4166666666666667,-1.3333333333333333,1.9166666666666667,0");
  EXPECT_NEAR(stable_step(ab3, cplx(-1, 0)).h, 6.0 / 11.0, kLocusLimitTol);
  // Not zero-stable (rho = (z - 1)(z - 2)... here z^2 - 3z + 2): no step.
  const auto bad = parse_integrator("lmm:alpha=2,-3,1:beta=0,1,0");
  EXPECT_EQ(stable_step(bad, cplx(-1, 0)).kind, StepLimit::Kind::kNone);
}

}  // namespace
}  // namespace mbfe::runtime
