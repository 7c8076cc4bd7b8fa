// `--probe BEAM@S`: the transverse displacement at S m along a beam, as a CSV
// column. Shared by the beam and the coupled simulate drivers.
#pragma once

#include <string>
#include <vector>

#include "runtime/fem/beam_system.h"
#include "ir/model.h"

namespace mbfe::tool {

struct BeamProbe {
  std::string label;  // as given, e.g. "beam1@0.5" (the CSV column name)
  int beam = -1;      // index into Model::beams
  runtime::BeamPointWeights weights;  // on the beam's free DOFs
};

/// Parses each BEAM@S. `beam_system(i)` gives the assembled system of beam i.
/// @throws UsageError naming the probe for a bad form, an unknown beam or S off the beam.
template <typename BeamSystemOf>
std::vector<BeamProbe> parse_beam_probes(const std::vector<std::string>& specs, const ir::Model& model,
                                         BeamSystemOf beam_system);

/// The beam and position of one BEAM@S, validated against the model.
/// @throws UsageError.
void locate_probe(const std::string& spec, const ir::Model& model, int& beam, double& s);

/// Point weights of `s` on `system`, as a UsageError naming `spec` when s is off the beam.
runtime::BeamPointWeights probe_weights(const std::string& spec, const runtime::BeamSystem& system, double s);

template <typename BeamSystemOf>
std::vector<BeamProbe> parse_beam_probes(const std::vector<std::string>& specs, const ir::Model& model,
                                         BeamSystemOf beam_system) {
  std::vector<BeamProbe> out;
  for (const std::string& spec : specs) {
    BeamProbe p;
    double s = 0.0;
    locate_probe(spec, model, p.beam, s);
    p.label = spec;
    p.weights = probe_weights(spec, beam_system(p.beam), s);
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace mbfe::tool
