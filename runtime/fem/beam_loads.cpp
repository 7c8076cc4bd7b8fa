#include "runtime/fem/beam_loads.h"

#include <cmath>

namespace mbfe::runtime {

namespace {

/// `value` of `load` at t, which must be finite.
double checked(const ir::Expression& load, double value, double t) {
  if (std::isfinite(value)) return value;
  const auto fault = load.fault_at(t);
  if (!fault) throw LoadValueError("a beam load is " + std::to_string(value) + " at t = " + std::to_string(t) + " s", t);
  throw LoadValueError(ir::describe_fault(load, *fault, t) + " (" + ir::node_location(load, fault->node) + ")", t);
}

}  // namespace

void time_dependent_loads(const BeamSystem& beam, double t, std::vector<NodalForce>& out) {
  out.clear();
  for (const TimedNodalLoad& load : beam.timed_loads) {
    if (load.window.contains(t)) out.push_back({load.free_index, checked(load.value, load.value.evaluate(t), t)});
  }
  for (const ir::BeamMovingLoad& load : beam.moving_loads) {
    const double s = moving_load_position(load, t);
    if (!(s >= 0.0 && s <= beam.length)) continue;  // not on the beam (yet, or any more)
    const double value = checked(load.value, load.value.evaluate(t), t);
    const BeamPointWeights w = point_weights(beam, s);
    for (int a = 0; a < 4; ++a) {
      if (w.free_index[a] >= 0 && w.w[a] != 0.0) out.push_back({w.free_index[a], value * w.w[a]});
    }
  }
}

}  // namespace mbfe::runtime
