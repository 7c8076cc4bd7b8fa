// Where each body of a spatial model (dimension: 3) is at q: its frame's
// origin and orientation in the ground frame, by the joint conventions of
// ir::Joint, evaluated numerically (for drawing: the VTK animation's triads).
// The generated kernels give points (point_position3), not frames.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "ir/model.h"

namespace mbfe::runtime {

struct BodyPose {
  Eigen::Matrix3d rotation;  // body frame to ground frame
  Eigen::Vector3d origin;    // m, ground frame
};

/// One pose per body, model order, at q (nq entries, ir::coordinate_layout's
/// order; quaternions read normalised). @throws std::invalid_argument for a
/// planar model.
std::vector<BodyPose> spatial_poses(const ir::Model& model, const double* q);

}  // namespace mbfe::runtime
