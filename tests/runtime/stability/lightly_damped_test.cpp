// A lightly damped oscillatory eigenvalue (a pendulum on a beam with no joint
// damping: -5e-7 +- 2.99i) sets forward Euler's limit at -2 Re / |lambda|^2;
// the boundary tolerance must not call larger steps stable.
#include <gtest/gtest.h>

#include <complex>

#include "runtime/integrators/integrator.h"
#include "runtime/stability/step_limits.h"

namespace mbfe::runtime {
namespace {

TEST(StepLimits, LightlyDampedEigenvalueSetsForwardEulerLimit) {
  constexpr double kRelTol = 1e-9;  // the closed form; bisection-free crossing
  const std::complex<double> lambda(-5e-7, 2.99);
  const double expected = -2.0 * lambda.real() / std::norm(lambda);
  const StepLimit lim = stable_step(parse_integrator("forward_euler"), lambda);
  ASSERT_EQ(lim.kind, StepLimit::Kind::kFinite);
  EXPECT_NEAR(lim.h, expected, kRelTol * expected);
  // And with a fast real eigenvalue beside it, the slow pair still wins.
  const StepLimit both =
      stable_step(parse_integrator("forward_euler"), std::vector<std::complex<double>>{lambda, {-1.37e5, 0.0}});
  EXPECT_NEAR(both.h, expected, kRelTol * expected);
}

}  // namespace
}  // namespace mbfe::runtime
