// A beam's mesh and DOF numbering, as the parts that act on a beam by its
// shape functions (contacts, links, probes) need it.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace mbfe::runtime {

class RunningSurface;

/// What the constraints need to know of one beam: its mesh and DOF numbering.
struct BeamMesh {
  std::string name;
  int num_elements = 0;        // > 0
  double element_length = 0.0; // m, > 0 (uniform mesh)
  /// full_to_free[i] = free index (within the beam) of full DOF i (2 per node),
  /// -1 if fixed by a support. Size 2 (num_elements + 1).
  std::vector<int> full_to_free;
  int num_free = 0;            // free DOFs of this beam
  /// The offset of the running surface slider contacts ride on (profile,
  /// camber); null: they ride on the axis, w(s).
  std::shared_ptr<const RunningSurface> surface;
  double length() const { return element_length * num_elements; }
};

}  // namespace mbfe::runtime
