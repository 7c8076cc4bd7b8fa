// The static start of a model with closed loops (`initial: {static: true}`):
// the equilibrium on the constraint manifold, against the four-bar's
// equilibrium under gravity and a torsional spring on its crank from the
// virtual work written here by hand, dV/dtheta + k (theta - rest) = 0.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "api/mbfe.h"
#include "tests/support/four_bar_oracle.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

// The oracle's dV/dtheta is a central difference (step 1e-5 rad, truncation
// ~1e-11 N m) and Newton's own residual falls to round-off of the
// accelerations: the angles agree to this (rad).
constexpr double kAngleTol = 1e-8;

TEST(LoopStaticStart, FourBarWithACrankSpringRestsWhereItsVirtualWorkVanishes) {
  const test::FourBar bar;
  const double k = 5.0, rest = 1.0;  // N m / rad, rad
  double theta = rest;
  for (int it = 0; it < 30; ++it) theta -= (bar.slope(theta) + k * (theta - rest)) / (bar.curvature(theta) + k);
  ASSERT_LT(std::abs(bar.slope(theta) + k * (theta - rest)), 1e-9);
  double phi, psi;
  bar.angles(theta, phi, psi);
  const std::string yaml =
      std::string("model: four_bar_sprung\ngravity: [0, -9.81]\n") + test::kFourBarBodies +
      "loads:\n  - {type: spring_damper, joint: crank, stiffness: 5.0, damping: 0, rest: 1.0}\n"
      "initial: {q: {crank: 1.0, coupler: -0.5357560074605321, rocker: 1.2995365385792519}, qd: {crank: 2.0},"
      " static: true}\n";
  const Model model = Model::parse(yaml, "four_bar_sprung.yaml");
  for (const auto formulation : {runtime::CoupledFormulation::kPartitioned, runtime::CoupledFormulation::kAugmented}) {
    SCOPED_TRACE(formulation == runtime::CoupledFormulation::kAugmented ? "augmented" : "partitioned");
    runtime::SimulationRequest request;
    request.integrator = runtime::parse_integrator("rk4");
    request.step = 1e-3;
    request.t_end = 0.01;
    request.formulation = formulation;
    test::RecordedRows rows;
    const runtime::SimulationReport report = model.simulate(request, rows);
    EXPECT_EQ(report.message, "");
    ASSERT_FALSE(rows.values.empty());
    EXPECT_NEAR(rows.series("crank").front(), theta, kAngleTol);
    EXPECT_NEAR(rows.series("coupler").front(), phi - theta, kAngleTol);
    EXPECT_NEAR(rows.series("rocker").front(), psi, kAngleTol);
    EXPECT_EQ(rows.series("crank_dot").front(), 0.0);  // at rest, the given 2 rad/s dropped
    // At rest in equilibrium it stays there.
    EXPECT_NEAR(rows.series("crank").back(), theta, kAngleTol);
  }
}

}  // namespace
}  // namespace mbfe
