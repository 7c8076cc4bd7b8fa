// The linearisation of models whose positions are not a vector space of their
// own (closed loops, quaternions), in their minimal tangent coordinates, as
// mbfe stability takes it (Model::spectrum): the four-bar hanging at rest
// against its one-degree-of-freedom equation m_eff(theta) theta'' =
// -dV/dtheta written here from the geometry (and the shipped four-bar,
// released away from rest, where it settles), a spherical pendulum against
// its closed-form frequency, and a free body without gravity (only zero
// modes).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <sstream>
#include <string>
#include <vector>

#include "api/mbfe.h"
#include "runtime/coupled/linearization.h"
#include "tests/support/four_bar_oracle.h"

namespace mbfe {
namespace {

using test::FourBar;
constexpr double kGravity = test::FourBar::kGravity;

// The hand-written oracle differentiates its closed forms by central
// differences (steps 1e-5 and 1e-4 rad: truncation and round-off ~1e-9
// relative), the model by the same with rel_step 1e-6 along the loop closed
// to 1e-13 m: their frequencies agree to this.
constexpr double kFrequencyRel = 1e-6;

std::string four_bar_at(double theta, double phi, double psi) {
  std::ostringstream os;
  os.precision(17);
  os << "model: four_bar_hanging\ngravity: [0, -9.81]\n" << test::kFourBarBodies
     << "initial: {q: {crank: " << theta << ", coupler: " << phi - theta << ", rocker: " << psi << "}}\n";
  return os.str();
}

double largest_imaginary(const runtime::StateSpectrum& s) {
  double w = 0.0;
  for (const auto& l : s.eigenvalues) w = std::max(w, std::abs(l.imag()));
  return w;
}

TEST(TangentLinearization, FourBarHangingSwingsAtItsReducedEquationsFrequency) {
  const FourBar bar;
  const double theta = bar.hanging_angle();
  ASSERT_GT(bar.curvature(theta), 0.0);  // a minimum: it hangs there
  double phi, psi;
  bar.angles(theta, phi, psi);
  const double omega = std::sqrt(bar.curvature(theta) / bar.effective_mass(theta));
  const Model model = Model::parse(four_bar_at(theta, phi, psi), "four_bar_hanging.yaml");
  const runtime::ModelSpectrum s = model.spectrum(false);
  EXPECT_EQ(s.coordinates, 1);  // the independent coordinate
  ASSERT_EQ(s.full.eigenvalues.size(), 2u);
  EXPECT_EQ(s.growing, 0);
  // Undamped: real parts at the QR iteration's rounding.
  for (const auto& l : s.full.eigenvalues) EXPECT_LE(std::abs(l.real()), runtime::kRoundingRe * std::abs(l)) << l;
  EXPECT_NEAR(largest_imaginary(s.full), omega, kFrequencyRel * omega);
}

TEST(TangentLinearization, SphericalPendulumSwingsInTwoEqualPairs) {
  // A body hanging from a ball joint, centre of mass l below it, turned about
  // the vertical by 0.7 rad (a quaternion off the identity): it swings about
  // x and y with omega^2 = m g l / (A + m l^2) and spins freely about z.
  const double m = 2.0, l = 0.8, A = 0.01;
  const Model model = Model::parse(
      "model: ball_pendulum\ndimension: 3\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - {name: bob, parent: ground, joint: {type: spherical}, mass: 2.0, inertia: [0.01, 0.01, 0.004, 0, 0, 0],"
      " com: [0, 0, -0.8]}\n"
      "initial: {q: {bob: [0.9393727128473789, 0, 0, 0.34289780745545134]}}\n",
      "ball_pendulum.yaml");
  const runtime::ModelSpectrum s = model.spectrum(false);
  EXPECT_EQ(s.coordinates, 3);  // three rotation increments, not four components
  ASSERT_EQ(s.full.eigenvalues.size(), 6u);
  EXPECT_EQ(s.growing, 0);
  const double omega = std::sqrt(m * kGravity * l / (A + m * l * l));
  int swinging = 0, zero = 0;
  for (const auto& lambda : s.full.eigenvalues) {
    if (lambda == 0.0) {
      ++zero;
      continue;
    }
    EXPECT_LE(std::abs(lambda.real()), runtime::kRoundingRe * std::abs(lambda)) << lambda;
    EXPECT_NEAR(std::abs(lambda.imag()), omega, kFrequencyRel * omega) << lambda;
    ++swinging;
  }
  EXPECT_EQ(swinging, 4);
  EXPECT_EQ(zero, 2);
}

TEST(TangentLinearization, AFourBarReleasedAwayFromRestIsLinearisedWhereItSettles) {
  // models/four_bar.yaml starts at crank 1 rad turning at 2 rad/s: there the
  // linearisation grows (the motion leaves the state). The advisor relaxes
  // it to the hanging equilibrium and reads the modes there: the reduced
  // equation's frequency at the oracle's hanging angle.
  const FourBar bar;
  const double theta = bar.hanging_angle();
  const double omega = std::sqrt(bar.curvature(theta) / bar.effective_mass(theta));
  const runtime::ModelSpectrum s = Model::load(std::string(MBFE_SOURCE_DIR) + "/models/four_bar.yaml").spectrum(false);
  EXPECT_TRUE(s.at_equilibrium);
  EXPECT_GT(s.growing_at_start, 0);
  EXPECT_EQ(s.growing, 0);
  ASSERT_EQ(s.full.eigenvalues.size(), 2u);
  EXPECT_NEAR(largest_imaginary(s.full), omega, kFrequencyRel * omega);
}

TEST(TangentLinearization, ABallPendulumReleasedTiltedIsLinearisedWhereItHangs) {
  // The ball pendulum above tilted 2 rad about x (above the horizontal,
  // where the linearisation grows) and let go: the advisor relaxes it to
  // hanging straight down and finds the two equal pairs there.
  const double m = 2.0, l = 0.8, A = 0.01;
  const Model model = Model::parse(
      "model: ball_pendulum_tilted\ndimension: 3\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - {name: bob, parent: ground, joint: {type: spherical}, mass: 2.0, inertia: [0.01, 0.01, 0.004, 0, 0, 0],"
      " com: [0, 0, -0.8]}\n"
      "initial: {q: {bob: [0.5403023058681398, 0.8414709848078965, 0, 0]}}\n",
      "ball_pendulum_tilted.yaml");
  const runtime::ModelSpectrum s = model.spectrum(false);
  EXPECT_TRUE(s.at_equilibrium);
  EXPECT_GT(s.growing_at_start, 0);
  ASSERT_EQ(s.full.eigenvalues.size(), 6u);
  const double omega = std::sqrt(m * kGravity * l / (A + m * l * l));
  int swinging = 0;
  for (const auto& lambda : s.full.eigenvalues) {
    if (lambda == 0.0) continue;
    EXPECT_NEAR(std::abs(lambda.imag()), omega, kFrequencyRel * omega) << lambda;
    ++swinging;
  }
  EXPECT_EQ(swinging, 4);
}

TEST(TangentLinearization, FreeBodyWithoutGravityHasOnlyZeroModes) {
  const Model model = Model::parse(
      "model: drifting_box\ndimension: 3\ngravity: [0, 0, 0]\nbodies:\n"
      "  - {name: box, parent: ground, joint: {type: free}, mass: 2, inertia: [0.1, 0.2, 0.3, 0, 0, 0]}\n"
      "initial: {q: {box: [1, -2, 0.5, 0.5, 0.5, 0.5, 0.5]}}\n",
      "drifting_box.yaml");
  const runtime::ModelSpectrum s = model.spectrum(false);
  EXPECT_EQ(s.coordinates, 6);
  ASSERT_EQ(s.full.eigenvalues.size(), 12u);
  EXPECT_EQ(s.growing, 0);
  for (const auto& lambda : s.full.eigenvalues) EXPECT_EQ(lambda, 0.0);
}

}  // namespace
}  // namespace mbfe
