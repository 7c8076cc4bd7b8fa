// The front end on spatial models (dimension: 3): joints about any axis, joint
// frames, inertia tensors, quaternion joints, 3-vector loads, the initial
// state per coordinate, and the refusals with their file:line:col.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "frontend/parse_model.h"
#include "ir/coordinate_layout.h"
#include "tests/support/model_error.h"

namespace mbfe::frontend {
using namespace mbfe::ir;
namespace {

// Normalising an axis divides by a square root: a few ulps.
constexpr double kUlpTol = 1e-15;

std::string error_of(const std::string& text) { return test::model_error_of(text); }

constexpr const char* kArm = R"yaml(model: arm
dimension: 3
gravity: [0, 0, -9.81]
bodies:
  - name: base
    parent: ground
    joint: {type: revolute, axis: [0, 0, 2], at: [0, 0, 0.3], rotation: [0.1, 0.2, 0.3]}
    mass: 4.0
    inertia: [0.05, 0.06, 0.02, 0.001, -0.002, 0.003]
    com: [0, 0, 0.1]
    points: {tip: [0, 0.1, 0.4]}
  - name: slide
    parent: base
    joint: {type: prismatic, axis: [1, 1, 0], at: [0.1, 0, 0]}
    mass: 1.0
    inertia: [0.01, 0.01, 0.01, 0, 0, 0]
  - name: ball
    parent: slide
    joint: {type: spherical, at: [0, 0, 0.2]}
    mass: 0.5
    inertia: [0.002, 0.002, 0.001, 0, 0, 0]
  - {name: drone, parent: ground, joint: {type: free}, mass: 1.5, inertia: [0.02, 0.02, 0.04, 0, 0, 0]}
loads:
  - {type: force, body: base, point: tip, value: [1, "2*t", 3]}
  - {type: torque, body: ball, value: [0, 0, "sin(t)"]}
  - {type: spring_damper, joint: slide, stiffness: 10, damping: 0.5, rest: 0.1}
initial:
  q: {base: 0.3, ball: [2, 0, 0, 0], drone: [1, 2, 3, 0, 0, 0, 3]}
  qd: {slide: -0.5, ball: [1, 2, 3], drone: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6]}
)yaml";

TEST(ParseSpatialModel, JointsFramesInertiasAndLoads) {
  const Model m = parse_model_text(kArm, "arm.yaml");
  EXPECT_EQ(m.dimension, 3);
  EXPECT_EQ(m.gravity3, (Vec3{0.0, 0.0, -9.81}));
  EXPECT_EQ(m.gravity, (Vec2{0.0, 0.0}));  // the planar members stay zero
  ASSERT_EQ(m.bodies.size(), 4u);
  const Body& base = m.bodies[0];
  EXPECT_EQ(base.joint.type, JointType::kRevolute);
  EXPECT_EQ(base.joint.axis3, (Vec3{0.0, 0.0, 1.0}));  // normalised
  EXPECT_EQ(base.joint.at3, (Vec3{0.0, 0.0, 0.3}));
  EXPECT_EQ(base.joint.rotation, (Vec3{0.1, 0.2, 0.3}));
  EXPECT_EQ(base.inertia3, (InertiaTensor{0.05, 0.06, 0.02, 0.001, -0.002, 0.003}));
  EXPECT_EQ(base.com3, (Vec3{0.0, 0.0, 0.1}));
  EXPECT_EQ(base.points.at(0).position3, (Vec3{0.0, 0.1, 0.4}));
  const Body& slide = m.bodies[1];
  EXPECT_EQ(slide.joint.type, JointType::kPrismatic);
  EXPECT_NEAR(slide.joint.axis3[0], std::sqrt(0.5), kUlpTol);
  EXPECT_NEAR(slide.joint.axis3[1], std::sqrt(0.5), kUlpTol);
  EXPECT_EQ(slide.joint.axis3[2], 0.0);
  EXPECT_EQ(m.bodies[2].joint.type, JointType::kSpherical);
  EXPECT_EQ(m.bodies[3].joint.type, JointType::kFree);

  ASSERT_EQ(m.loads.size(), 3u);
  EXPECT_EQ(m.loads[0].force3[1].evaluate(0.5), 1.0);
  EXPECT_EQ(m.loads[0].force3[2].evaluate(0.0), 3.0);
  EXPECT_NEAR(m.loads[1].torque3[2].evaluate(0.5), std::sin(0.5), kUlpTol);
  EXPECT_EQ(m.loads[2].stiffness, 10.0);

  // q: base 1, slide 1, ball 4, drone 7; v: 1, 1, 3, 6.
  const CoordinateLayout layout = coordinate_layout(m);
  EXPECT_EQ(layout.num_positions, 13);
  EXPECT_EQ(layout.num_velocities, 11);
  EXPECT_EQ(layout.first_position, (std::vector<int>{0, 1, 2, 6}));
  EXPECT_EQ(layout.first_velocity, (std::vector<int>{0, 1, 2, 5}));
  EXPECT_EQ(layout.position_names[2], "ball_qw");
  EXPECT_EQ(layout.position_names[6], "drone_x");
  EXPECT_EQ(layout.position_names[12], "drone_qz");
  EXPECT_EQ(layout.velocity_names[4], "ball_wz");
  EXPECT_EQ(layout.velocity_names[5], "drone_vx");
  EXPECT_EQ(layout.velocity_names[10], "drone_wz");
  // Quaternions are stored unit; a missing coordinate is 0.
  EXPECT_EQ(m.initial.q, (std::vector<double>{0.3, 0.0, 1, 0, 0, 0, 1, 2, 3, 0, 0, 0, 1}));
  EXPECT_EQ(m.initial.qd, (std::vector<double>{0.0, -0.5, 1, 2, 3, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6}));
}

TEST(ParseSpatialModel, MissingQuaternionIsTheIdentity) {
  const Model m = parse_model_text(R"(model: m
dimension: 3
bodies:
  - {name: a, parent: ground, joint: {type: spherical}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}
  - {name: b, parent: a, joint: {type: free}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}
)",
                                   "m.yaml");
  EXPECT_EQ(m.initial.q, (std::vector<double>{1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}));
  EXPECT_EQ(m.initial.qd, std::vector<double>(9, 0.0));
}

TEST(ParseSpatialModel, PlanarModelsKeepTheirMeaning) {
  // dimension: 2 is the default, written out.
  const Model m = parse_model_text(R"(model: m
dimension: 2
gravity: [0, -9.81]
bodies:
  - {name: a, parent: ground, joint: {type: revolute}, mass: 1, inertia: 0.1, com: [0.5, 0]}
)",
                                   "m.yaml");
  EXPECT_EQ(m.dimension, 2);
  EXPECT_EQ(m.gravity, (Vec2{0.0, -9.81}));
  EXPECT_EQ(m.bodies[0].com, (Vec2{0.5, 0.0}));
}

// Each refusal at its file:line:col, with the expected and the given.
std::string spatial(const std::string& bodies) {
  return "model: m\ndimension: 3\nbodies:\n" + bodies;
}

TEST(ParseSpatialModel, RefusesZeroAxis) {
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: revolute, axis: [0, 0, 0]}, mass: 1, "
                             "inertia: [1, 1, 1, 0, 0, 0]}\n")),
            "models/x.yaml:4:61: body 'a': joint.axis must be a non-zero, finite direction");
}

TEST(ParseSpatialModel, RefusesMissingAxisAndAxisOfSphericalJoint) {
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: prismatic}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n")),
            "models/x.yaml:4:38: body 'a': missing required key 'joint.axis'");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: spherical, axis: [0, 0, 1]}, mass: 1, "
                             "inertia: [1, 1, 1, 0, 0, 0]}\n")),
            "models/x.yaml:4:56: body 'a': joint.axis applies to revolute and prismatic joints; a spherical joint "
            "turns about every axis");
}

TEST(ParseSpatialModel, RefusesImpossibleInertiaTensors) {
  // Not positive semidefinite: eigenvalues of [[1, 2, 0], [2, 1, 0], [0, 0, 1]] are -1, 1, 3.
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: free}, mass: 1, inertia: [1, 1, 1, 2, 0, 0]}\n")),
            "models/x.yaml:4:70: body 'a': inertia is not an inertia tensor: its principal moments -1, 1, 3 include "
            "a negative one (expected a positive semidefinite matrix [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, "
            "Izz]])");
  // Positive definite but no body has it: 1 + 1 < 3.
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: free}, mass: 1, inertia: [1, 1, 3, 0, 0, 0]}\n")),
            "models/x.yaml:4:70: body 'a': inertia is not the inertia of a rigid body: its principal moments 1, 1, 3 "
            "violate the triangle inequality (1 + 1 < 3; any body's principal moments satisfy A + B >= C, a flat one "
            "with equality)");
  // A flat disc (A + B = C) and a rod (0, A, A) are bodies.
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: free}, mass: 1, inertia: [0.25, 0.25, 0.5, 0, 0, 0]}\n")),
            "(accepted)");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: free}, mass: 1, inertia: [0, 0.1, 0.1, 0, 0, 0]}\n")),
            "(accepted)");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: free}, mass: 1, inertia: 0.1}\n")),
            "models/x.yaml:4:70: body 'a': inertia: expected a list of 6 numbers [Ixx, Iyy, Izz, Ixy, Ixz, Iyz], got "
            "'0.1'");
}

TEST(ParseSpatialModel, NamesTheAnglesOfAJointRotation) {
  EXPECT_EQ(
      error_of(spatial("  - {name: a, parent: ground, joint: {type: revolute, axis: [0, 0, 1], rotation: [0.1, 0.2]}, "
                       "mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n")),
      "models/x.yaml:4:82: body 'a': joint.rotation: expected a list of 3 numbers [roll, pitch, yaw], got a list "
      "of 2 items");
}

TEST(ParseSpatialModel, RefusesBeamsContactsAndLinks) {
  EXPECT_EQ(error_of("model: m\ndimension: 3\nbeams:\n  - {name: b}\n"),
            "models/x.yaml:3:1: beams: a spatial model (dimension: 3) cannot have beams: 3D beams do not exist yet");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: free}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n") +
                     "contacts: []\n"),
            "models/x.yaml:5:1: contacts: a spatial model (dimension: 3) cannot have contacts: they act on beams, and "
            "3D beams do not exist yet");
}

TEST(ParseSpatialModel, RefusesWhatOnlyOneCoordinateJointsTake) {
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: spherical, motion: \"t\"}, mass: 1, "
                             "inertia: [1, 1, 1, 0, 0, 0]}\n")),
            "models/x.yaml:4:56: body 'a': joint.motion drives one coordinate: a revolute or prismatic joint, not a "
            "spherical one");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: spherical}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n") +
                     "loads:\n  - {type: spring_damper, joint: a, stiffness: 1}\n"),
            "models/x.yaml:6:34: load #1: a spring_damper acts on one joint coordinate; body 'a' has a spherical "
            "joint (expected a revolute or prismatic one)");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: spherical}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n") +
                     "initial: {q: {a: [0, 0, 0, 0]}}\n"),
            "models/x.yaml:5:18: initial.q.a: the quaternion (w, x, y, z) must be non-zero and finite (it is "
            "normalised)");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: spherical}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n") +
                     "initial: {qd: {a: 1}}\n"),
            "models/x.yaml:5:19: initial.qd.a: expected a list of 3 numbers [wx, wy, wz], got '1'");
}

TEST(ParseSpatialModel, RefusesQuaternionJointsInThePlaneAndThreeVectorsThere) {
  EXPECT_EQ(error_of("model: m\nbodies:\n  - {name: a, parent: ground, joint: {type: spherical}, mass: 1, inertia: 1}\n"),
            "models/x.yaml:3:45: body 'a': joint.type: a spherical joint exists in spatial models only (add "
            "'dimension: 3' at the top of the file); a planar joint is revolute or prismatic");
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: free}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n") +
                     "loads:\n  - {type: torque, body: a, value: 2}\n"),
            "models/x.yaml:6:36: load #1: value: expected a list of 3 values [x, y, z], got '2'");
  EXPECT_EQ(error_of("model: m\ndimension: 4\n"),
            "models/x.yaml:2:12: dimension: expected one of 2, 3, got '4'");
}

TEST(ParseSpatialModel, RefusesABodyNamedLikeAQuaternionCoordinate) {
  EXPECT_EQ(error_of(spatial("  - {name: a_qw, parent: ground, joint: {type: free}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n"
                             "  - {name: a, parent: ground, joint: {type: spherical}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n")),
            "models/x.yaml:5:12: body 'a': its spherical joint names its coordinates a_..., and 'a_qw' is already the "
            "name at line 4");
}

TEST(ParseSpatialModel, OutputColumnsFollowWhatEachJointWrites) {
  // A spherical or free joint writes <body>_qw.. and <body>_wx.. (no <body>
  // and no <body>_dot column): bodies b and b_dot beside it were refused as a
  // clash of two b_dot columns, and so was a spherical a_dot beside a
  // revolute a.
  const std::string inertia = "mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n";
  EXPECT_EQ(error_of(spatial("  - {name: b, parent: ground, joint: {type: spherical}, " + inertia +
                             "  - {name: b_dot, parent: b, joint: {type: revolute, axis: [0, 0, 1]}, " + inertia +
                             "  - {name: c, parent: ground, joint: {type: free}, " + inertia +
                             "  - {name: c_dot, parent: c, joint: {type: prismatic, axis: [1, 0, 0]}, " + inertia +
                             "  - {name: a, parent: ground, joint: {type: revolute, axis: [0, 1, 0]}, " + inertia +
                             "  - {name: a_dot, parent: a, joint: {type: spherical}, " + inertia)),
            "(accepted)");
  // The columns that would be written twice still are refused: a revolute
  // a_dot beside a revolute a (the rate of a); a body named loop_residual in
  // a model with closed loops: tests/malformed/output_name_loop_residual.yaml.
  EXPECT_EQ(error_of(spatial("  - {name: a, parent: ground, joint: {type: revolute, axis: [0, 1, 0]}, " + inertia +
                             "  - {name: a_dot, parent: a, joint: {type: revolute, axis: [1, 0, 0]}, " + inertia)),
            "models/x.yaml:5:12: body 'a_dot' (its coordinate) writes the column 'a_dot', which body 'a' (its rate) "
            "(line 4) writes too; output columns need distinct names: rename one");
}

/// n bodies in series on revolute joints, the first n_free on free joints.
std::string spatial_chain(int n, int n_free) {
  std::string bodies;
  for (int i = 1; i <= n; ++i)
    bodies += "  - {name: l" + std::to_string(i) + ", parent: " + (i == 1 ? "ground" : "l" + std::to_string(i - 1)) +
              ", joint: {type: " + (i <= n_free ? "free" : "revolute, axis: [0, 0, 1]") +
              "}, mass: 1, inertia: [1, 1, 1, 0, 0, 0]}\n";
  return spatial(bodies);
}

TEST(ParseSpatialModel, BodiesAndVelocitiesAreBoundedByTheCompileCost) {
  // A 200-joint spatial chain (within the planar limit of 200 bodies) made
  // 12 MB of C++ that takes minutes to compile; the spatial limits keep the
  // largest model they allow near the planar limit's compile time.
  const ParseLimits limits;
  ASSERT_EQ(limits.max_spatial_bodies, 50);
  ASSERT_EQ(limits.max_spatial_velocities, 100);
  EXPECT_EQ(error_of(spatial_chain(50, 0)), "(accepted)");
  EXPECT_EQ(error_of(spatial_chain(50, 10)), "(accepted)");  // 10 x 6 + 40 = 100 velocities
  EXPECT_EQ(error_of(spatial_chain(51, 0)),
            "models/x.yaml:4:3: bodies: 51 entries, more than the limit of 50 (ParseLimits::max_spatial_bodies) of a "
            "spatial model: its generated solver would take too long to compile (docs/performance.md, \"Model size "
            "and compile time\")");
  // The 17th free joint brings 102 velocities: refused at that body.
  EXPECT_EQ(error_of(spatial_chain(17, 17)),
            "models/x.yaml:20:5: body 'l17': the joints up to here have 102 velocity coordinates (a free joint 6, a "
            "spherical one 3, the others 1), more than the limit of 100 (ParseLimits::max_spatial_velocities) of a "
            "spatial model: its generated solver would take too long to compile (docs/performance.md, \"Model size "
            "and compile time\")");
  // A planar chain keeps the planar limit.
  std::string planar = "model: m\nbodies:\n";
  for (int i = 1; i <= 100; ++i)
    planar += "  - {name: l" + std::to_string(i) + ", parent: " + (i == 1 ? "ground" : "l" + std::to_string(i - 1)) +
              ", joint: {type: revolute}, mass: 1, inertia: 1}\n";
  EXPECT_EQ(error_of(planar), "(accepted)");
}

}  // namespace
}  // namespace mbfe::frontend
