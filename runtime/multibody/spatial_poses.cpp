#include "runtime/multibody/spatial_poses.h"

#include <Eigen/Geometry>
#include <stdexcept>

#include "ir/coordinate_layout.h"

namespace mbfe::runtime {

namespace {

Eigen::Vector3d vec(const ir::Vec3& v) { return {v[0], v[1], v[2]}; }

// R = Rz(yaw) Ry(pitch) Rx(roll), URDF's rpy.
Eigen::Matrix3d rpy(const ir::Vec3& r) {
  return (Eigen::AngleAxisd(r[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(r[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(r[0], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Matrix3d quaternion(const double* w) {
  return Eigen::Quaterniond(w[0], w[1], w[2], w[3]).normalized().toRotationMatrix();
}

}  // namespace

std::vector<BodyPose> spatial_poses(const ir::Model& model, const double* q) {
  if (model.dimension != 3) throw std::invalid_argument("spatial_poses: model '" + model.name + "' is planar");
  const ir::CoordinateLayout layout = ir::coordinate_layout(model);
  std::vector<BodyPose> poses(model.bodies.size());
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    const ir::Body& body = model.bodies[b];
    const ir::Joint& joint = body.joint;
    BodyPose parent{Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()};
    if (body.parent >= 0) parent = poses[static_cast<std::size_t>(body.parent)];
    const double* qb = q + layout.first_position[b];
    const Eigen::Matrix3d joint_rotation = parent.rotation * rpy(joint.rotation);
    const Eigen::Vector3d joint_origin = parent.origin + parent.rotation * vec(joint.at3);
    BodyPose& pose = poses[b];
    switch (joint.type) {
      case ir::JointType::kRevolute:
        pose.rotation = joint_rotation * Eigen::AngleAxisd(qb[0], vec(joint.axis3).normalized()).toRotationMatrix();
        pose.origin = joint_origin;
        break;
      case ir::JointType::kPrismatic:
        pose.rotation = joint_rotation;
        pose.origin = parent.origin + parent.rotation * (vec(joint.at3) + qb[0] * vec(joint.axis3).normalized());
        break;
      case ir::JointType::kSpherical:
        pose.rotation = joint_rotation * quaternion(qb);
        pose.origin = joint_origin;
        break;
      case ir::JointType::kFree:
        pose.rotation = joint_rotation * quaternion(qb + 3);
        pose.origin = joint_origin + joint_rotation * Eigen::Vector3d(qb[0], qb[1], qb[2]);
        break;
    }
  }
  return poses;
}

}  // namespace mbfe::runtime
