#include "runtime/structure/coupled_beam.h"

namespace mbfe::runtime {

BeamMesh beam_mesh(const BeamSystem& beam) {
  BeamMesh mesh;
  mesh.name = beam.name;
  mesh.num_elements = beam.num_nodes - 1;
  mesh.element_length = beam.element_length;
  mesh.full_to_free = beam.full_to_free;
  mesh.num_free = static_cast<int>(beam.M.rows());
  mesh.surface = beam.surface;
  return mesh;
}

CoupledBeam coupled_beam(const BeamSystem& beam, int offset) {
  CoupledBeam out;
  out.mesh = beam_mesh(beam);
  out.offset = offset;
  out.M = beam.M;
  out.P = beam.P;
  out.C = beam.C;
  out.K = beam.K;
  if (beam.has_time_loads()) out.time_loads = std::make_shared<const BeamSystem>(beam);
  return out;
}

}  // namespace mbfe::runtime
