// Where each body's generalized coordinates sit in the position vector q (nq
// entries) and the velocity vector v (nv entries), and what they are called.
//
// A revolute or prismatic joint has one of each (q' = v); a spherical joint
// has a unit quaternion (w, x, y, z) in q and the angular velocity relative
// to its joint frame, in the body frame, in v; a free joint has its position
// (x, y, z) then the quaternion in q, and the rates of x, y, z then the
// angular velocity in v. A planar model therefore has nq = nv = one
// coordinate per body, in model order, and so has every spatial model of
// revolute and prismatic joints.
#pragma once

#include <string>
#include <vector>

#include "ir/model.h"
#include "ir/quantity.h"

namespace mbfe::ir {

struct CoordinateLayout {
  int num_positions = 0;   // nq
  int num_velocities = 0;  // nv
  std::vector<int> first_position;  // per body: index of its first entry of q
  std::vector<int> first_velocity;  // per body: index of its first entry of v
  /// Per entry of q: the body's name, or <body>_x, _y, _z, _qw, _qx, _qy, _qz.
  std::vector<std::string> position_names;
  /// Per entry of v: the body's name, or <body>_vx, _vy, _vz, _wx, _wy, _wz.
  std::vector<std::string> velocity_names;
  /// Per entry of v: the body it belongs to.
  std::vector<int> velocity_body;
  /// Per entry of q: what it measures (an angle, a length, or a quaternion
  /// entry, a ratio).
  std::vector<Quantity> position_quantity;
  /// Per entry of v: the quantity it is the rate of (an angle for an
  /// angular velocity, a length for a translation's rate).
  std::vector<Quantity> velocity_quantity;
};

CoordinateLayout coordinate_layout(const Model& model);

/// The names a joint of `type` gives the coordinates of body `body` (one
/// list for q, one for v).
std::vector<std::string> position_names(JointType type, const std::string& body);
std::vector<std::string> velocity_names(JointType type, const std::string& body);
/// What those coordinates measure, in the same order.
std::vector<Quantity> position_quantities(JointType type);
std::vector<Quantity> velocity_quantities(JointType type);

}  // namespace mbfe::ir
