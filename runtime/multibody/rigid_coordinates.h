// The state of a model's bodies as the integrators see it: nq position
// coordinates q and nv velocity coordinates v (ir/coordinate_layout.h), and
// the two operations a unit quaternion needs that a plain coordinate does
// not: moving q by a velocity-space increment (q (+) dv) and renormalising
// after a step. A planar model, and a spatial one of revolute and prismatic
// joints only, has nq = nv and q (+) dv = q + dv.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ir/model.h"
#include "ir/quantity.h"

namespace mbfe::runtime {

struct RigidCoordinates {
  int nq = 0;  // position coordinates
  int nv = 0;  // velocity coordinates
  /// Index into q of the w entry of each unit quaternion (w, x, y, z).
  std::vector<int> quaternions;
  /// Per entry of v: the index into q of the coordinate it is the rate of,
  /// or -1 for a component of an angular velocity (body frame).
  std::vector<int> rate_of;
  /// Per entry of v that is an angular velocity component: the index into q
  /// of its quaternion's w and the axis (0 x, 1 y, 2 z); -1 otherwise.
  std::vector<int> rotation_of, rotation_axis;
  /// Output column names: q's (ir::CoordinateLayout::position_names), then
  /// v's: "<name>_dot" for a coordinate that is its own rate's, the layout's
  /// <body>_vx .. _wz for the velocities of spherical and free joints.
  std::vector<std::string> position_columns, velocity_columns;
  /// What each entry of q and v measures (ir::CoordinateLayout's): the
  /// columns' units are ir::si_unit(position_quantity[i]) and
  /// ir::si_unit(velocity_quantity[i], 1).
  std::vector<ir::Quantity> position_quantity, velocity_quantity;
  /// Per entry of v: the body it moves.
  std::vector<int> velocity_body;

  bool has_quaternions() const { return !quaternions.empty(); }
};

RigidCoordinates rigid_coordinates(const ir::Model& model);

/// q <- q (+) dv: plain coordinates by dv, each quaternion turned by the
/// rotation vector of its angular-velocity entries of dv (body frame, rad:
/// quat <- quat * exp(dv / 2)), so that to first order the kernels' J dv is
/// the change of Phi. q has nq entries and dv nv.
void displace(const RigidCoordinates& c, double* q, const Eigen::VectorXd& dv);

/// Every quaternion of q scaled back to unit length.
void normalize_quaternions(const RigidCoordinates& c, double* q);

/// Largest | |quaternion| - 1 | over the quaternions of q (0 without any).
double quaternion_norm_error(const RigidCoordinates& c, const double* q);

}  // namespace mbfe::runtime
