// The forward pass of the spatial derivation, the counterpart of
// rigid_kinematics.h: for every body, ground outwards, its rotation matrix
// (each sine and cosine computed once), joint origin, the unit motion of each
// of its velocity coordinates, its angular velocity, and the accelerations
// with v' = 0 (the velocity-product terms), every quantity a named
// intermediate of the code list. Twice: in the ground frame (for M, Q, points
// and loops) and in the body's own frame (for F: there the joint offsets,
// axes and inertias are constants, so the recursion costs a rotation by the
// joint's own, sparse, rotation per vector instead of full matrix products).
//
// Conventions (docs/model-format.md, "Spatial models"): the joint frame is
// the parent frame translated to `at` and turned by the fixed roll-pitch-yaw
// `rotation`; a revolute body turns about `axis` (joint frame) by q, a
// prismatic one moves by q along `axis` (parent frame), a spherical one turns
// by a unit quaternion (w, x, y, z) and a free one moves by (x, y, z) in the
// joint frame and turns by a quaternion. A quaternion joint's angular
// velocity coordinates are the angular velocity relative to the joint frame,
// in the body frame.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/spatial_vectors.h"
#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::gen {

/// The motion of a body for a unit rate of one of its velocity coordinates
/// (a column of the joint's motion subspace), ground frame.
struct SpatialColumn {
  Vec3x angular;  // angular velocity
  Vec3x linear;   // velocity of the body's own origin o_i
};

/// What the forward pass knows of one body.
struct SpatialBodyKinematics {
  Mat3x rotation;         // R_i: body frame -> ground frame
  Mat3x joint_rotation;   // R_J: joint frame -> ground frame (R_i for a prismatic joint)
  Vec3x origin;           // o_i, ground frame
  Vec3x offset;           // o_i - o_parent
  GiNaC::ex offset_squared;  // |o_i - o_parent|^2 (a constant unless the joint translates)
  Vec3x axis;             // revolute and prismatic: the joint axis, ground frame
  std::vector<SpatialColumn> columns;  // one per velocity coordinate of the joint
  Vec3x com_offset;       // p_i - o_i, ground frame
  Vec3x omega;            // angular velocity
  Vec3x velocity;         // velocity of o_i
  Vec3x alpha;            // angular acceleration with v' = 0
  Vec3x bias_accel;       // acceleration of o_i with v' = 0

  // The same motion in the body's own frame.
  Mat3x relative;         // E_i = R_parent^T R_i: body frame -> parent frame
  Vec3x local_offset;     // o_i - o_parent in the parent frame
  std::vector<SpatialColumn> local_columns;  // the columns in the body frame
  Vec3x local_omega;      // angular velocity, body frame
  Vec3x local_alpha;      // angular acceleration with v' = 0, body frame
  Vec3x local_accel;      // acceleration of o_i with v' = 0, body frame
};

/// The kinematics of every body of a spatial `model` in terms of q (nq
/// symbols) and v (nv symbols), laid out by `layout`.
std::vector<SpatialBodyKinematics> spatial_forward_kinematics(const ir::Model& model,
                                                              const ir::CoordinateLayout& layout,
                                                              const std::vector<GiNaC::symbol>& q,
                                                              const std::vector<GiNaC::symbol>& v, CodeList& code);

}  // namespace mbfe::gen
