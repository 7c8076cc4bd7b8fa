// The static start of a model with a spherical joint (quaternions): Newton on
// three rotation increments. A ball-jointed pendulum started tilted comes to
// hang with its centre of mass straight below the joint, the equilibrium
// whatever its spin about the vertical (which nothing holds).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "api/mbfe.h"
#include "tests/support/recorded_rows.h"

namespace mbfe {
namespace {

// Newton converges to round-off of the accelerations: the body's axis is
// vertical to this (rad).
constexpr double kAxisTol = 1e-9;

TEST(QuaternionStaticStart, TiltedBallPendulumHangsStraightDown) {
  const Model model = Model::parse(
      "model: ball\ndimension: 3\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - {name: bob, parent: ground, joint: {type: spherical}, mass: 2.0, inertia: [0.012, 0.015, 0.006, 0, 0, 0],"
      " com: [0, 0, -0.8]}\n"
      "initial: {q: {bob: [0.9, 0.3, -0.2, 0.25]}, qd: {bob: [1, 0, 0]}, static: true}\n",
      "ball.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = 1e-3;
  request.t_end = 0.01;
  test::RecordedRows rows;
  const runtime::SimulationReport report = model.simulate(request, rows);
  EXPECT_EQ(report.message, "");
  ASSERT_FALSE(rows.values.empty());
  const auto& first = rows.values.front();
  const Eigen::Quaterniond q(first[rows.column("bob_qw")], first[rows.column("bob_qx")], first[rows.column("bob_qy")],
                             first[rows.column("bob_qz")]);
  EXPECT_NEAR(q.norm(), 1.0, 1e-15);
  // The body's z axis (from the joint to the centre of mass, reversed) in the ground frame.
  const Eigen::Vector3d axis = q.toRotationMatrix() * Eigen::Vector3d::UnitZ();
  EXPECT_LT((axis - Eigen::Vector3d::UnitZ()).norm(), kAxisTol) << axis.transpose();
  for (const char* rate : {"bob_wx", "bob_wy", "bob_wz"}) EXPECT_EQ(rows.series(rate).front(), 0.0) << rate;
}

TEST(QuaternionStaticStart, AFreeBodyHasNoEquilibriumAndIsCalledAMechanism) {
  // A free body (turned joint frame, centre of mass off its origin) carrying
  // a ball-jointed body under gravity: it falls, whatever its position, so
  // nothing holds its translations. Newton must say so at the start, not
  // step by the inverse of round-off to where M means nothing.
  const Model model = Model::parse(
      "model: falling\ndimension: 3\ngravity: [0, 0, -9.81]\nbodies:\n"
      "  - {name: b1, parent: ground, joint: {type: free, rotation: [0.3, 0.2, 0.1]}, mass: 3.0,"
      " inertia: [0.1, 0.12, 0.08, 0, 0, 0], com: [0.1, 0.05, -0.2]}\n"
      "  - {name: b2, parent: b1, joint: {type: spherical, at: [0, 0, -0.5]}, mass: 1.0,"
      " inertia: [0.02, 0.02, 0.01, 0, 0, 0], com: [0, 0, -0.3]}\n"
      "initial: {static: true}\n",
      "falling.yaml");
  runtime::SimulationRequest request;
  request.integrator = runtime::parse_integrator("rk4");
  request.step = 1e-3;
  request.t_end = 0.01;
  test::RecordedRows rows;
  try {
    model.simulate(request, rows);
    FAIL() << "a falling body was found at rest";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("mechanism: nothing holds 'b1_"), std::string::npos) << what;
    EXPECT_EQ(what.find("singular"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace mbfe
