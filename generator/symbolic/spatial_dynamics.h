// Closed-form equations of motion of a spatial tree of rigid bodies,
//   M(q) v' + F(q, v) = Q(q, v, t),
// as straight-line kernels: the spatial counterpart of rigid_dynamics.h.
//
// q holds nq position coordinates and v nv velocity coordinates (they differ
// when a joint has a quaternion, ir/coordinate_layout.h); M is nv x nv, F and
// Q have nv entries, F holds the velocity terms only, gravity, loads and
// springs are in Q. The forward pass (spatial_kinematics.h) gives rotations,
// origins, velocities and the accelerations with v' = 0; F and Q come from
// the recursive Newton-Euler algorithm (spatial_newton_euler.h), M from the
// composite-rigid-body algorithm (spatial_composite_rigid_body.h) with its
// pairs summed by a loop in the emitted code. position_derivative gives
// q' = G(q) v for integrating positions: q' = v for revolute and prismatic
// joints, the rates of x, y, z, and q_quat' = 1/2 q_quat (0, w) (Hamilton's
// product) for a quaternion with body-frame angular velocity w. Every kernel
// reads a quaternion as unit; keeping it so is the integrator's job.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/spatial_kinematics.h"
#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::gen {

/// Symbols and kernels of a spatial model.
struct SpatialDerivation {
  std::vector<GiNaC::symbol> q, v;  // nq and nv, model order
  GiNaC::symbol t{"t"};
  CodeList code;
  ir::CoordinateLayout layout;
  std::vector<SpatialBodyKinematics> kinematics;
  Kernel mass_matrix, inertial_forces, generalized_forces;
  Kernel dynamics;             // all three at once, kinematics shared
  Kernel position_derivative;  // q' = G(q) v
  /// One kernel per named point: body b, point p -> ground-frame position.
  struct PointKernel {
    int body, point;
    Kernel kernel;
  };
  std::vector<PointKernel> points;
};

/// Derives the kernels of a spatial `model` (bodies and loads).
void derive_spatial_dynamics(const ir::Model& model, SpatialDerivation& out);

}  // namespace mbfe::gen
