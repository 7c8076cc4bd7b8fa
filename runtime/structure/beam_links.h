// Where a link between two beams (ir::Link, docs/catenary.md) acts: its
// extension as a linear map of the beams' coordinates,
//
//   e = w_b(s_b) - w_a(s_a) - rest = g q - rest,
//
// g = -N_a on a's element and +N_b on b's (Hermite shape functions). The
// force element (runtime/coupled/link_force.h) and the joined structures'
// stiffness (joined_structures.h) both use it.
#pragma once

#include <vector>

#include "ir/model.h"
#include "runtime/structure/beam_mesh.h"

namespace mbfe::runtime {

/// g = de/dq of one link: up to 8 entries (coordinate index, value).
struct LinkGradient {
  int cols[8];
  double values[8];
  int size = 0;
};

/// g of `link` on the beams `meshes`, whose free DOFs start at `offsets` in
/// the vector g indexes (q_c, or a joined structure's coordinates).
LinkGradient link_gradient(const ir::Link& link, const std::vector<BeamMesh>& meshes, const std::vector<int>& offsets);

}  // namespace mbfe::runtime
