// Probes: the transverse displacement of a beam at a position along it, as an
// output column ("beam1@0.5"), or its acceleration ("beam1@0.5:acc"), for
// models with beams; and a body's coordinate acceleration ("wheel:acc").
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ir/model.h"
#include "runtime/damping/beam_model.h"
#include "runtime/fem/beam_system.h"
#include "runtime/simulation/simulation_types.h"

namespace mbfe::runtime {

/// A probe resolved on the assembled beams: w(s) = sum_a weights.w[a] q_c[offset + free_index[a]].
struct BeamProbe {
  std::string label;
  bool acceleration = false;  // the column is d2/dt2 of the value (m/s^2)
  int body = -1;    // a body's coordinate acceleration: index into the model's bodies (beam -1)
  int beam = -1;    // index into the model's beams
  int offset = 0;   // first q_c coordinate of the beam
  BeamPointWeights weights;
  /// The displacement (or, given rates, its rate) from the beam coordinates
  /// q_c (every beam's free DOFs, model order).
  double value(const double* qc) const;
};

/// @throws InvalidInput naming the probe for an unknown beam or body, S off
///         the beam, or a label given twice (the labels are column names).
std::vector<BeamProbe> resolve_probes(const std::vector<ProbeSpec>& specs, const ir::Model& model,
                                      const BeamModel& beams);

}  // namespace mbfe::runtime
