#include "runtime/structure/beam_links.h"

#include <algorithm>
#include <cmath>

#include "runtime/fem/hermite_shape.h"

namespace mbfe::runtime {

namespace {

/// Adds sign N(s) on the element holding s to g (its free DOFs only).
void add_point(const BeamMesh& mesh, int offset, double s, double sign, LinkGradient& g) {
  const int element = std::clamp(static_cast<int>(std::floor(s / mesh.element_length)), 0, mesh.num_elements - 1);
  const double xi = (s - element * mesh.element_length) / mesh.element_length;
  const hermite::Row4 n = hermite::N(xi, mesh.element_length);
  for (int j = 0; j < 4; ++j) {
    const int f = mesh.full_to_free[2 * element + j];
    if (f < 0 || n[j] == 0.0) continue;
    g.cols[g.size] = offset + f;
    g.values[g.size] = sign * n[j];
    ++g.size;
  }
}

}  // namespace

LinkGradient link_gradient(const ir::Link& link, const std::vector<BeamMesh>& meshes, const std::vector<int>& offsets) {
  LinkGradient g;
  add_point(meshes[link.a.beam], offsets[link.a.beam], link.a.at, -1.0, g);
  add_point(meshes[link.b.beam], offsets[link.b.beam], link.b.at, +1.0, g);
  return g;
}

}  // namespace mbfe::runtime
