#include "runtime/simulation/beam_probes.h"

#include "runtime/errors/invalid_input.h"

namespace mbfe::runtime {

double BeamProbe::value(const double* qc) const {
  double v = 0.0;
  for (int a = 0; a < 4; ++a)
    if (weights.free_index[a] >= 0) v += weights.w[a] * qc[offset + weights.free_index[a]];
  return v;
}

std::vector<BeamProbe> resolve_probes(const std::vector<ProbeSpec>& specs, const ir::Model& model,
                                      const BeamModel& beams) {
  std::vector<BeamProbe> out;
  for (const ProbeSpec& spec : specs) {
    // The label is the column's name: two alike would be two columns of one name.
    for (const BeamProbe& earlier : out)
      if (earlier.label == spec.label)
        throw InvalidRequest("probes", "'" + spec.label + "' is given twice; each probe is a column and needs a name of its own");
    BeamProbe p;
    p.label = spec.label;
    p.acceleration = spec.acceleration;
    if (spec.body) {
      for (std::size_t i = 0; i < model.bodies.size(); ++i)
        if (model.bodies[i].name == spec.beam) p.body = static_cast<int>(i);
      if (p.body < 0) {
        std::string names;
        for (const auto& b : model.bodies) names += (names.empty() ? "" : ", ") + b.name;
        throw InvalidRequest("probes", "'" + spec.label + "': no body named '" + spec.beam + "' (bodies: " +
                                           (names.empty() ? "none" : names) + ")");
      }
      out.push_back(std::move(p));
      continue;
    }
    for (std::size_t i = 0; i < model.beams.size(); ++i)
      if (model.beams[i].name == spec.beam) p.beam = static_cast<int>(i);
    if (p.beam < 0) {
      std::string names;
      for (const auto& b : model.beams) names += (names.empty() ? "" : ", ") + b.name;
      throw InvalidRequest("probes", "'" + spec.label + "': no beam named '" + spec.beam + "' (beams: " +
                                         (names.empty() ? "none" : names) + ")");
    }
    const BeamPart& part = beams.beams[p.beam];
    p.offset = part.offset;
    try {
      p.weights = point_weights(part.system, spec.s);
    } catch (const std::invalid_argument& e) {
      throw InvalidRequest("probes", "'" + spec.label + "': " + e.what());
    }
    out.push_back(std::move(p));
  }
  return out;
}

}  // namespace mbfe::runtime
