// The kinematics of a planar or a spatial tree as the loop kernels read it
// (loop_constraints.h): ground-frame 3-vectors, a planar model's in the plane
// z = 0 turning about z.
#pragma once

#include <ginac/ginac.h>

#include <vector>

#include "generator/symbolic/code_list.h"
#include "generator/symbolic/loop_constraints.h"
#include "generator/symbolic/rigid_kinematics.h"
#include "generator/symbolic/spatial_kinematics.h"
#include "ir/coordinate_layout.h"
#include "ir/model.h"

namespace mbfe::gen {

/// From the planar forward pass; `qd` are the rates (q' = v). The origins'
/// velocities are derived here (the planar dynamics does not need them).
LoopKinematics planar_loop_kinematics(const ir::Model& model, const std::vector<BodyKinematics>& kin,
                                      const std::vector<GiNaC::symbol>& qd, CodeList& code);

/// From the spatial forward pass.
LoopKinematics spatial_loop_kinematics(const ir::Model& model, const ir::CoordinateLayout& layout,
                                       const std::vector<SpatialBodyKinematics>& kin);

}  // namespace mbfe::gen
