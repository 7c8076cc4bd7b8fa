// The body frames the runtime computes for drawing against the generated
// kernels: every named point, placed by its body's pose, where
// point_position3 (derived symbolically by the generator) puts it, at random
// states of the shipped spatial models and of a tree with fixed joint
// rotations, a prismatic joint and a free joint.
#include "runtime/multibody/spatial_poses.h"

#include <gtest/gtest.h>

#include <random>
#include <string>

#include "api/mbfe.h"
#include "ir/coordinate_layout.h"

namespace mbfe {
namespace {

// Two computations of the same product of rotations, positions of order 1 m.
constexpr double kPointTol = 1e-13;  // m

const char* kTree = R"(model: pose_tree
dimension: 3
gravity: [0, 0, -9.81]
bodies:
  - {name: base, parent: ground, joint: {type: free, at: [0.1, 0.2, 0.3], rotation: [0.3, -0.2, 0.5]}, mass: 1, inertia: [0.1, 0.1, 0.1, 0, 0, 0], points: {a: [0.2, 0.1, -0.3]}}
  - {name: arm, parent: base, joint: {type: revolute, axis: [1, 2, 3], at: [0.4, 0, 0.1], rotation: [-0.4, 0.7, 0.1]}, mass: 1, inertia: [0.1, 0.1, 0.1, 0, 0, 0], points: {tip: [0.5, -0.2, 0.1], mid: [0.1, 0.1, 0.1]}}
  - {name: slide, parent: arm, joint: {type: prismatic, axis: [0, 1, 1], at: [0.5, 0, 0], rotation: [0.2, 0.1, -0.3]}, mass: 1, inertia: [0.1, 0.1, 0.1, 0, 0, 0], points: {end: [0.3, 0.2, 0.1]}}
  - {name: ball, parent: slide, joint: {type: spherical, at: [0, 0.1, 0.2], rotation: [0, 0, 1.0]}, mass: 1, inertia: [0.1, 0.1, 0.1, 0, 0, 0], points: {p: [0.1, -0.3, 0.2]}}
)";

void check_points(const Model& model, std::mt19937& rng) {
  const ir::Model& ir = model.ir();
  const ir::CoordinateLayout layout = ir::coordinate_layout(ir);
  std::uniform_real_distribution<double> value(-1.5, 1.5);
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<double> q(layout.num_positions);
    for (double& x : q) x = value(rng);
    // Quaternions unit, as a run keeps them.
    for (std::size_t b = 0; b < ir.bodies.size(); ++b) {
      const ir::JointType type = ir.bodies[b].joint.type;
      if (type != ir::JointType::kSpherical && type != ir::JointType::kFree) continue;
      double* w = q.data() + layout.first_position[b] + (type == ir::JointType::kFree ? 3 : 0);
      const double norm = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] + w[3] * w[3]);
      for (int k = 0; k < 4; ++k) w[k] /= norm;
    }
    const std::vector<runtime::BodyPose> poses = runtime::spatial_poses(ir, q.data());
    for (std::size_t b = 0; b < ir.bodies.size(); ++b) {
      for (std::size_t p = 0; p < ir.bodies[b].points.size(); ++p) {
        double kernel[3];
        model.solver()->point_position3(q.data(), static_cast<int>(b), static_cast<int>(p), kernel);
        const ir::Vec3& local = ir.bodies[b].points[p].position3;
        const Eigen::Vector3d placed = poses[b].origin + poses[b].rotation * Eigen::Vector3d(local[0], local[1], local[2]);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(placed[k], kernel[k], kPointTol) << ir.bodies[b].name << "." << ir.bodies[b].points[p].name;
      }
    }
  }
}

TEST(SpatialPoses, PointsPlacedByThePosesAreTheKernels) {
  std::mt19937 rng(29);
  for (const char* file : {"models/double_pendulum_3d.yaml", "models/slider_crank_3d.yaml"}) {
    SCOPED_TRACE(file);
    check_points(Model::load(std::string(MBFE_SOURCE_DIR) + "/" + file), rng);
  }
  SCOPED_TRACE("pose_tree");
  check_points(Model::parse(kTree, "pose_tree.yaml"), rng);
}

}  // namespace
}  // namespace mbfe
