// An independent numerical model of a spatial tree, written straight from the
// conventions of docs/model-format.md ("Spatial models") with Eigen, for the
// oracle tests of the generated spatial kernels: forward kinematics, the
// step q (+) dv along the velocity coordinates (a quaternion turned by the
// exponential of a body-frame rotation vector), and Jacobians and
// velocity-product accelerations by finite differences along it.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <cmath>
#include <vector>

#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::test {

struct SpatialPose {
  std::vector<Eigen::Matrix3d> rotation;  // body -> ground
  std::vector<Eigen::Vector3d> origin;
};

inline Eigen::Vector3d vec(const ir::Vec3& v) { return {v[0], v[1], v[2]}; }

/// Rz(yaw) Ry(pitch) Rx(roll).
inline Eigen::Matrix3d rpy_matrix(const ir::Vec3& rpy) {
  return (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

/// (w, x, y, z) -> rotation, Eigen's Hamilton quaternion (normalised here).
inline Eigen::Matrix3d quaternion_matrix(const double* wxyz) {
  return Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized().toRotationMatrix();
}

inline SpatialPose spatial_pose(const ir::Model& m, const ir::CoordinateLayout& layout, const Eigen::VectorXd& q) {
  SpatialPose pose;
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const ir::Body& b = m.bodies[i];
    const Eigen::Matrix3d rp = b.parent < 0 ? Eigen::Matrix3d::Identity() : pose.rotation[b.parent];
    const Eigen::Vector3d op = b.parent < 0 ? Eigen::Vector3d::Zero() : pose.origin[b.parent];
    const Eigen::Matrix3d joint = rp * rpy_matrix(b.joint.rotation);
    const int k = layout.first_position[i];
    Eigen::Vector3d origin = op + rp * vec(b.joint.at3);
    Eigen::Matrix3d r = joint;
    switch (b.joint.type) {
      case ir::JointType::kRevolute:
        r = joint * Eigen::AngleAxisd(q[k], vec(b.joint.axis3)).toRotationMatrix();
        break;
      case ir::JointType::kPrismatic:
        origin += q[k] * (rp * vec(b.joint.axis3));
        break;
      case ir::JointType::kSpherical:
        r = joint * quaternion_matrix(q.data() + k);
        break;
      case ir::JointType::kFree:
        origin += joint * Eigen::Vector3d(q[k], q[k + 1], q[k + 2]);
        r = joint * quaternion_matrix(q.data() + k + 3);
        break;
    }
    pose.rotation.push_back(r);
    pose.origin.push_back(origin);
  }
  return pose;
}

/// q moved by dv along the velocity coordinates: q + dv for one-coordinate
/// joints and a free joint's x, y, z; a quaternion times exp(dw / 2), dw a
/// body-frame rotation vector (the motion at constant v for one unit of time).
inline Eigen::VectorXd step_positions(const ir::Model& m, const ir::CoordinateLayout& layout, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& dv) {
  Eigen::VectorXd out = q;
  for (std::size_t i = 0; i < m.bodies.size(); ++i) {
    const ir::JointType type = m.bodies[i].joint.type;
    int k = layout.first_position[i], j = layout.first_velocity[i];
    if (type == ir::JointType::kRevolute || type == ir::JointType::kPrismatic) {
      out[k] += dv[j];
      continue;
    }
    if (type == ir::JointType::kFree) {
      for (int c = 0; c < 3; ++c) out[k + c] += dv[j + c];
      k += 3;
      j += 3;
    }
    const Eigen::Vector3d w(dv[j], dv[j + 1], dv[j + 2]);
    const double angle = w.norm();
    const Eigen::Quaterniond turn =
        angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, w / angle)) : Eigen::Quaterniond::Identity();
    const Eigen::Quaterniond now = Eigen::Quaterniond(q[k], q[k + 1], q[k + 2], q[k + 3]) * turn;
    out[k] = now.w();
    out[k + 1] = now.x();
    out[k + 2] = now.y();
    out[k + 3] = now.z();
  }
  return out;
}

/// A body-frame point in the ground frame.
inline Eigen::Vector3d spatial_point(const ir::Model& m, const ir::CoordinateLayout& layout, const Eigen::VectorXd& q,
                                     int body, const Eigen::Vector3d& local) {
  if (body < 0) return local;  // a point of the ground
  const SpatialPose pose = spatial_pose(m, layout, q);
  return pose.origin[body] + pose.rotation[body] * local;
}

inline Eigen::Matrix3d body_rotation(const ir::Model& m, const ir::CoordinateLayout& layout, const Eigen::VectorXd& q,
                                     int body) {
  return body < 0 ? Eigen::Matrix3d::Identity() : spatial_pose(m, layout, q).rotation[body];
}

// Central differences along the velocity coordinates: h = 1e-5 for first
// derivatives (truncation ~1e-10, round-off ~1e-11 of O(1) positions).
constexpr double kFirstStep = 1e-5;
constexpr double kSecondStep = 1e-4;  // second derivatives: truncation and round-off ~1e-8

/// d p / d v (3 x nv) of a body-frame point.
inline Eigen::MatrixXd point_jacobian(const ir::Model& m, const ir::CoordinateLayout& layout, const Eigen::VectorXd& q,
                                      int body, const Eigen::Vector3d& local) {
  const int nv = layout.num_velocities;
  Eigen::MatrixXd J(3, nv);
  for (int j = 0; j < nv; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(nv, j) * kFirstStep;
    J.col(j) = (spatial_point(m, layout, step_positions(m, layout, q, e), body, local) -
                spatial_point(m, layout, step_positions(m, layout, q, -e), body, local)) /
               (2 * kFirstStep);
  }
  return J;
}

/// The angular velocity Jacobian (3 x nv): w = vee(R' R^T).
inline Eigen::MatrixXd angular_jacobian(const ir::Model& m, const ir::CoordinateLayout& layout, const Eigen::VectorXd& q,
                                        int body) {
  const int nv = layout.num_velocities;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(3, nv);
  if (body < 0) return J;
  const Eigen::Matrix3d r = body_rotation(m, layout, q, body);
  for (int j = 0; j < nv; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(nv, j) * kFirstStep;
    const Eigen::Matrix3d dr = (body_rotation(m, layout, step_positions(m, layout, q, e), body) -
                                body_rotation(m, layout, step_positions(m, layout, q, -e), body)) /
                               (2 * kFirstStep);
    const Eigen::Matrix3d w = dr * r.transpose();
    J.col(j) = Eigen::Vector3d(w(2, 1) - w(1, 2), w(0, 2) - w(2, 0), w(1, 0) - w(0, 1)) / 2;
  }
  return J;
}

/// Acceleration of a body-frame point at v' = 0: d^2/ds^2 p(q (+) s v).
inline Eigen::Vector3d point_bias_acceleration(const ir::Model& m, const ir::CoordinateLayout& layout,
                                               const Eigen::VectorXd& q, const Eigen::VectorXd& v, int body,
                                               const Eigen::Vector3d& local) {
  const double h = kSecondStep;
  return (spatial_point(m, layout, step_positions(m, layout, q, h * v), body, local) -
          2 * spatial_point(m, layout, q, body, local) +
          spatial_point(m, layout, step_positions(m, layout, q, -h * v), body, local)) /
         (h * h);
}

/// Angular acceleration at v' = 0: d/ds of J_w(q (+) s v) v.
inline Eigen::Vector3d angular_bias_acceleration(const ir::Model& m, const ir::CoordinateLayout& layout,
                                                 const Eigen::VectorXd& q, const Eigen::VectorXd& v, int body) {
  const double h = kSecondStep;
  return (angular_jacobian(m, layout, step_positions(m, layout, q, h * v), body) * v -
          angular_jacobian(m, layout, step_positions(m, layout, q, -h * v), body) * v) /
         (2 * h);
}

/// The inertia tensor of the model file as a matrix (body frame).
inline Eigen::Matrix3d inertia_matrix(const ir::InertiaTensor& i) {
  Eigen::Matrix3d m;
  m << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
  return m;
}

}  // namespace mbfe::test
