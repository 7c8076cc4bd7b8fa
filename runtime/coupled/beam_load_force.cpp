#include "runtime/coupled/beam_load_force.h"

namespace mbfe::runtime {

BeamLoadForce::BeamLoadForce(std::shared_ptr<const BeamSystem> beam, int offset)
    : beam_(std::move(beam)), offset_(offset), name_("loads on '" + beam_->name + "'") {}

void BeamLoadForce::add_force(const ForceArgs& x, ForceState& state, ForceSink& out) const {
  std::vector<NodalForce>& nodal = static_cast<State&>(state).nodal;
  time_dependent_loads(*beam_, x.t, nodal);
  for (const NodalForce& f : nodal) out.fc[offset_ + f.index] += f.value;
}

}  // namespace mbfe::runtime
