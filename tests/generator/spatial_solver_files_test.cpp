// The files of spatial solvers and of planar ones with loops fill the fields
// ABI version 4 appended (runtime/abi/mbfe_model_abi.h) — dimension,
// velocities, q' = G(q) v, driven joints' indices into q and v, the loop
// table — and a driven joint behind a quaternion joint is driven at its own
// entries of q and v.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "api/solver_cache.h"
#include "frontend/parse_model.h"
#include "generator/emit/generate_solver.h"

namespace mbfe {
namespace {

constexpr const char* kDrivenBehindBall = R"yaml(model: driven_behind_ball
dimension: 3
gravity: [0, 0, -9.81]
bodies:
  - {name: ball, parent: ground, joint: {type: spherical}, mass: 1, inertia: [0.1, 0.1, 0.1, 0, 0, 0], com: [0, 0, -0.5]}
  - {name: wrist, parent: ball, joint: {type: revolute, axis: [0, 1, 0], at: [0, 0, -1], motion: "0.5*sin(2*t)"}, mass: 0.5, inertia: [0.01, 0.01, 0.01, 0, 0, 0], com: [0.1, 0, 0]}
)yaml";

TEST(SpatialSolverFiles, DrivenJointIndicesIntoQAndV) {
  const ir::Model m = frontend::parse_model_text(kDrivenBehindBall, "driven.yaml");
  const std::string source = gen::generate_solver(m).files.at(1).text;
  // The wrist is entry 4 of q (after the quaternion) and entry 3 of v.
  EXPECT_NE(source.find("const int kDrivenCoordinates[] = {3};"), std::string::npos);
  EXPECT_NE(source.find("const int kDrivenPositions[] = {4};"), std::string::npos);
  const mbfe_model_v1& k = *load_solver(m, /*quiet=*/true).model;
  ASSERT_EQ(k.num_driven, 1);
  EXPECT_EQ(k.driven_coordinates[0], 3);
  ASSERT_NE(k.driven_positions, nullptr);
  EXPECT_EQ(k.driven_positions[0], 4);
  double q = 0, qd = 0, qdd = 0;
  const double t = 0.3;
  k.motion(t, &q, &qd, &qdd);
  EXPECT_DOUBLE_EQ(q, 0.5 * std::sin(2 * t));
  EXPECT_DOUBLE_EQ(qd, std::cos(2 * t));
  EXPECT_DOUBLE_EQ(qdd, -2 * std::sin(2 * t));
  EXPECT_EQ(k.dimension, 3);
  EXPECT_EQ(k.num_coordinates, 5);
  EXPECT_EQ(k.num_velocities, 4);
  EXPECT_STREQ(k.coordinate_names[1], "ball_qx");
  EXPECT_STREQ(k.velocity_names[3], "wrist");
  EXPECT_EQ(k.point_position, nullptr);
  EXPECT_EQ(k.num_loop_rows, 0);
  EXPECT_EQ(k.loops, nullptr);
}

TEST(SpatialSolverFiles, PlanarLoopModelFillsTheLoopFieldsOnly) {
  const ir::Model m = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/four_bar.yaml");
  const mbfe_model_v1& k = *load_solver(m, /*quiet=*/true).model;
  EXPECT_EQ(k.dimension, 2);
  EXPECT_EQ(k.num_velocities, 0);  // nv = nq
  EXPECT_EQ(k.velocity_names, nullptr);
  EXPECT_EQ(k.position_derivative, nullptr);
  EXPECT_NE(k.point_position, nullptr);
  EXPECT_EQ(k.point_position3, nullptr);
  ASSERT_EQ(k.num_loops, 1);
  EXPECT_STREQ(k.loops[0].name, "coupler_rocker");
  EXPECT_EQ(k.loops[0].type, 1);  // revolute
  EXPECT_EQ(k.loops[0].first_row, 0);
  EXPECT_EQ(k.loops[0].rows, 2);
  EXPECT_EQ(k.num_loop_rows, 2);
}

TEST(SpatialSolverFiles, PlanarModelWithoutLoopsLeavesTheAppendedFieldsZero) {
  const ir::Model m = frontend::load_model_file(std::string(MBFE_SOURCE_DIR) + "/models/double_pendulum.yaml");
  const mbfe_model_v1& k = *load_solver(m, /*quiet=*/true).model;
  EXPECT_EQ(k.dimension, 0);
  EXPECT_EQ(k.num_velocities, 0);
  EXPECT_EQ(k.position_derivative, nullptr);
  EXPECT_EQ(k.num_loop_rows, 0);
  EXPECT_EQ(k.loop_constraints, nullptr);
  EXPECT_EQ(k.point_position3, nullptr);
}

}  // namespace
}  // namespace mbfe
