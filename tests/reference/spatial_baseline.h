// The kinematic tree of a spatial model held by a numerical rigid-body library
// (MuJoCo: mujoco_tree.h; RBDL: rbdl_tree.h), the independent oracles of the
// generated kernels and their competitors in bench/spatial_baselines_bench.cpp.
//
// Each library has its own coordinates: its own order of the joints (MuJoCo
// numbers them depth first), its own quaternion layout (RBDL keeps the w
// entries at the end of q) and its own velocity of a free joint (MuJoCo's is
// in the ground frame). A tree converts mbfe's state to its own once
// (`to_native`), evaluates in its own coordinates (what is timed), and reads
// the result back in mbfe's: with the library's velocities qvel = T v,
//   M = T^T M_lib T,   bias = T^T bias_lib.
//
// bias = C(q, v) v - Q_gravity: the velocity terms and the weights, as both
// libraries compute them (MuJoCo's qfrc_bias, RBDL's NonlinearEffects). For a
// model whose only load is gravity this is F - Q of the generated kernels
// (M v' + F = Q); with gravity switched off it is F.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <string>

#include "ir/model.h"

namespace mbfe::reference {

class SpatialBaseline {
 public:
  virtual ~SpatialBaseline() = default;

  /// The library and its version, e.g. "MuJoCo 2.2.2".
  virtual std::string name() const = 0;
  /// Sizes of the library's own position and velocity vectors.
  virtual int native_positions() const = 0;
  virtual int native_velocities() const = 0;
  /// mbfe's q (nq) and v (nv, docs/model-format.md "Coordinates") in the
  /// library's coordinates (native_positions(), native_velocities()).
  virtual void to_native(const double* q, const double* v, double* native_q, double* native_v) const = 0;
  /// M and bias at a native state, in the library's coordinates: the
  /// cheapest sequence of its calls that yields both (what is timed).
  virtual void evaluate(const double* native_q, const double* native_v) = 0;
  /// After evaluate(): M (nv x nv, row-major) and bias (nv) in mbfe's velocity
  /// coordinates.
  virtual void result(double* M, double* bias) const = 0;
  /// Gravity on (the model's) or off (bias = F).
  virtual void set_gravity(bool on) = 0;
};

/// The fixed rotation of a joint frame (joint frame -> parent frame),
/// R = Rz(yaw) Ry(pitch) Rx(roll) of `rotation` = (roll, pitch, yaw).
inline Eigen::Matrix3d rpy_rotation(const ir::Vec3& rpy) {
  return (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

inline Eigen::Vector3d vector3(const ir::Vec3& v) { return {v[0], v[1], v[2]}; }

/// The inertia tensor of the model file ([Ixx, Iyy, Izz, Ixy, Ixz, Iyz]) as a matrix.
inline Eigen::Matrix3d inertia_matrix(const ir::InertiaTensor& i) {
  Eigen::Matrix3d m;
  m << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
  return m;
}

}  // namespace mbfe::reference
