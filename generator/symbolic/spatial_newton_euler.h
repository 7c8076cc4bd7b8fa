// The backward pass of the spatial derivation (the recursive Newton-Euler
// algorithm with v' = 0), the counterpart of newton_euler.h: for every body,
// leaves to ground, the net force and the moment about its joint origin that
// its subtree needs (inertial, in the body frame) and receives (applied:
// gravity, point forces, torques, in the ground frame), and the
// spring-damper terms of its joint. Projected on the joint's motion columns
// they are F and Q of M v' + F = Q.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/spatial_kinematics.h"
#include "generator/symbolic/spatial_vectors.h"
#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::gen {

/// Per body: subtree forces and moments about its joint origin, inertial in
/// the body's own frame (project them on SpatialBodyKinematics::local_columns)
/// and applied in the ground frame (on columns); per velocity coordinate the
/// spring-damper generalized force.
struct SpatialSubtreeForces {
  std::vector<Vec3x> inertial_force, applied_force;
  std::vector<Vec3x> inertial_moment, applied_moment;
  std::vector<GiNaC::ex> spring;  // nv
};

SpatialSubtreeForces spatial_newton_euler_pass(const ir::Model& model, const ir::CoordinateLayout& layout,
                                               const std::vector<SpatialBodyKinematics>& kin,
                                               const std::vector<std::vector<int>>& children,
                                               const std::vector<GiNaC::symbol>& q,
                                               const std::vector<GiNaC::symbol>& v, const GiNaC::symbol& t,
                                               CodeList& code);

/// The generalized force of a column for a force f and a moment n about the
/// body's joint origin: angular . n + linear . f.
GiNaC::ex project(const SpatialColumn& column, const Vec3x& force, const Vec3x& moment);

}  // namespace mbfe::gen
