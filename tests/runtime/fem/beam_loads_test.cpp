// The time-dependent loads of a beam: a moving force's consistent nodal loads
// do the work F w(s) on every cubic w (rigid motions: they sum to F and to
// its moment F s, the statics of a point force), nothing is loaded while the
// force is off the beam, a windowed point load is on in [start, stop), and a
// value that is not finite is a LoadValueError at its time.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "runtime/fem/beam_loads.h"
#include "runtime/fem/beam_system.h"
#include "tests/runtime/fem/beam_fixtures.h"

namespace mbfe::runtime {
namespace {

// Sums of four nodal loads of O(1e2) N times powers of x <= 1 m: round-off.
constexpr double kWorkTol = 1e-12;

constexpr double kForce = -80.0;  // N
constexpr double kSpeed = 2.0;    // m/s
constexpr double kStart = -0.1;   // m at t = 0: off the beam until t = 0.05 s

BeamSystem beam_with_moving_force() {
  ir::Beam b = test::paper_beam(0.005, 10);  // 0.1 m elements, pinned at both ends
  ir::BeamMovingLoad load;
  load.value = ir::Expression::number(kForce);
  load.speed = kSpeed;
  load.start = kStart;
  b.moving_loads = {load};
  return assemble_beam(b, {0.0, 0.0});
}

/// The work of the nodal loads on w = x^k
/// (w_i = x_i^k on a deflection DOF, w'_i = k x_i^(k-1) on a slope DOF).
double work_on_monomial(const BeamSystem& beam, const std::vector<NodalForce>& loads, int k) {
  double work = 0.0;
  for (const NodalForce& f : loads) {
    const int full = beam.free_dof[static_cast<std::size_t>(f.index)];
    const double x = (full / 2) * beam.element_length;
    const bool slope = full % 2 == 1;
    const double w = slope ? (k == 0 ? 0.0 : k * std::pow(x, k - 1)) : std::pow(x, k);
    work += f.value * w;
  }
  return work;
}

TEST(BeamLoads, MovingForceDoesItsWorkOnEveryCubic) {
  const BeamSystem beam = beam_with_moving_force();
  std::vector<NodalForce> loads;
  // Positions inside elements away from the pinned ends (all four DOFs free).
  for (double s : {0.13, 0.37, 0.55, 0.64, 0.871}) {
    const double t = (s - kStart) / kSpeed;
    time_dependent_loads(beam, t, loads);
    ASSERT_EQ(loads.size(), 4u) << "s = " << s;
    for (int k = 0; k <= 3; ++k)
      EXPECT_NEAR(work_on_monomial(beam, loads, k), kForce * std::pow(s, k), kWorkTol * std::abs(kForce))
          << "s = " << s << ", w = x^" << k;
  }
}

TEST(BeamLoads, NothingWhileTheForceIsOffTheBeam) {
  const BeamSystem beam = beam_with_moving_force();
  std::vector<NodalForce> loads{{0, 1.0}};
  time_dependent_loads(beam, 0.0, loads);  // s = -0.1 m
  EXPECT_TRUE(loads.empty());
  time_dependent_loads(beam, (1.05 - kStart) / kSpeed, loads);  // s = 1.05 m > L
  EXPECT_TRUE(loads.empty());
  // On a node the load goes to that node's deflection alone.
  time_dependent_loads(beam, (0.3 - kStart) / kSpeed, loads);
  double on_node = 0.0, elsewhere = 0.0;
  for (const NodalForce& f : loads)
    (beam.free_dof[static_cast<std::size_t>(f.index)] == 6 ? on_node : elsewhere) += std::abs(f.value);
  EXPECT_NEAR(on_node, std::abs(kForce), kWorkTol * std::abs(kForce));
  EXPECT_LT(elsewhere, kWorkTol * std::abs(kForce));
}

TEST(BeamLoads, WindowedPointLoadIsOnFromStartUntilStop) {
  ir::Beam b = test::paper_beam(0.005, 10);
  ir::BeamPointLoad load;
  load.at = 0.4;
  load.value = ir::Expression::number(25.0);
  load.window = {0.1, 0.2};
  b.loads = {load};
  const BeamSystem beam = assemble_beam(b, {0.0, 0.0});
  EXPECT_EQ(beam.P.cwiseAbs().maxCoeff(), 0.0);  // not in the constant part
  std::vector<NodalForce> loads;
  for (const auto [t, on] : {std::pair{0.0999, false}, std::pair{0.1, true}, std::pair{0.15, true},
                             std::pair{0.2, false}}) {
    time_dependent_loads(beam, t, loads);
    ASSERT_EQ(loads.size(), on ? 1u : 0u) << "t = " << t;
    if (on) {
      EXPECT_EQ(beam.free_dof[static_cast<std::size_t>(loads[0].index)], 8);  // w of node 4
      EXPECT_EQ(loads[0].value, 25.0);
    }
  }
}

TEST(BeamLoads, NonFiniteValueIsALoadValueErrorAtItsTime) {
  ir::Beam b = test::paper_beam(0.005, 10);
  ir::BeamMovingLoad load;
  load.value = ir::Expression::number(std::numeric_limits<double>::infinity());
  load.speed = 1.0;
  load.start = 0.5;
  b.moving_loads = {load};
  const BeamSystem beam = assemble_beam(b, {0.0, 0.0});
  std::vector<NodalForce> loads;
  try {
    time_dependent_loads(beam, 0.25, loads);
    FAIL() << "an infinite load was applied";
  } catch (const LoadValueError& e) {
    EXPECT_EQ(e.t(), 0.25);
  }
}

}  // namespace
}  // namespace mbfe::runtime
