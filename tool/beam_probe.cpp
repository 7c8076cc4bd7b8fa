#include "tool/beam_probe.h"

#include <stdexcept>

#include "tool/cli_args.h"

namespace mbfe::tool {

void locate_probe(const std::string& spec, const ir::Model& model, int& beam, double& s) {
  const auto at = spec.find('@');
  if (at == std::string::npos)
    throw UsageError("--probe '" + spec + "': expected BEAM@S (S in m along the beam), e.g. beam1@0.5");
  const std::string name = spec.substr(0, at);
  s = parse_number(spec.substr(at + 1), "--probe " + spec);
  for (std::size_t i = 0; i < model.beams.size(); ++i) {
    if (model.beams[i].name == name) {
      beam = static_cast<int>(i);
      return;
    }
  }
  std::string names;
  for (const auto& b : model.beams) names += (names.empty() ? "" : ", ") + b.name;
  throw UsageError("--probe '" + spec + "': no beam named '" + name + "' (beams: " + names + ")");
}

runtime::BeamPointWeights probe_weights(const std::string& spec, const runtime::BeamSystem& system, double s) {
  try {
    return runtime::point_weights(system, s);
  } catch (const std::invalid_argument& e) {
    throw UsageError("--probe '" + spec + "': " + e.what());
  }
}

}  // namespace mbfe::tool
